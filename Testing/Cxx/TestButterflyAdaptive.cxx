// SPDX-License-Identifier: BSD-3-Clause
// Butterfly prolongation through greens (docs/METHOD.md §6.5): in adaptive red-green runs the
// stencils are read at each edge's level (greens as their parents, finer regions as the
// triangles they refine), so the butterfly, not the midpoint fallback, places new vertices
// next to greens.
// 1. A cubic height field over a regular grid, refined at nested patches for three steps
//    without moving a point: at most 5 % of each step's new vertices fall back to the
//    midpoint (where a patch's border turns, a corner vertex has no ring at the finer level
//    on its coarse side), and every other new point away from the grid's boundary lies
//    exactly on the cubic (the 8-point butterfly reproduces cubics on a regular grid; a
//    stencil read at the wrong level or a midpoint is off by ~1e-3).
// 2. The accuracy phantoms from the box enclosing the volume, every default: in every adaptive
//    step at most 5 % of the new vertices fall back to the midpoint (a closed surface has no
//    real boundary; before, up to two thirds of a step's vertices did next to greens).
#include "DSTestHelpers.h"
#include "HierarchyPhantoms.h"
#include "TestSolverMeshes.h"
#include "dsMultilevel.h"
#include "dsRedGreen.h"

#include <cmath>

using namespace dsurf;

namespace
{
double Cubic(double x, double y)
{
  return 0.01 * x * x * x - 0.004 * x * y * y + 0.02 * y * y + 0.3 * x;
}

void CubicGridStaysExact()
{
  const int n = 16;
  TriangleMesh m = dstest::HeightGrid(n, Cubic);
  RedGreenRefiner rg;
  std::string err;
  DS_CHECK(rg.Initialize(m, &err), err);
  int greensSeen = 0;
  for (int step = 0; step < 3; ++step)
  {
    // Nested patches, as the phantoms refine (a region around detail, greens at its border):
    // triangles whose centroid lies within a radius shrinking per step of a point off the
    // grid's symmetry lines.
    std::vector<char> marks(m.NumberOfTriangles(), 0);
    for (int t = 0; t < m.NumberOfTriangles(); ++t)
    {
      const auto& tri = m.Triangles[t];
      const Vec3 c = (1.0 / 3.0) * (m.Points[tri[0]] + m.Points[tri[1]] + m.Points[tri[2]]);
      marks[t] = std::hypot(c[0] - 7.7, c[1] - 8.3) < 5.0 - step ? 1 : 0;
    }
    const int before = m.NumberOfPoints();
    const RefinementCounts rc = rg.Refine(m, marks, Prolongation::Butterfly);
    DS_CHECK(rc.Ok, "refine: " + rc.Error);
    greensSeen += rc.Greens;
    int inexact = 0;
    for (int v = before; v < m.NumberOfPoints(); ++v)
    {
      const Vec3& p = m.Points[v];
      // Away from the grid's boundary (the level-0 stencil reaches two units from its edge),
      // only a midpoint fallback may leave the cubic.
      inexact += std::min({ p[0], p[1], n - p[0], n - p[1] }) >= 3.0 &&
          std::abs(p[2] - Cubic(p[0], p[1])) > 1e-12
        ? 1
        : 0;
    }
    const std::string name = "cubic grid, step " + std::to_string(step + 1);
    std::cout << name << ": " << rc.NewVertices << " new vertices, " << rc.FallbackVertices
              << " at the midpoint, " << rc.Greens << " greens" << std::endl;
    DS_CHECK_LE(
      double(rc.FallbackVertices) / rc.NewVertices, 0.05, name + ": share of midpoint fallbacks");
    DS_CHECK_LE(inexact, rc.FallbackVertices,
      name + ": new points off the cubic away from the boundary (at most the fallbacks)");
  }
  DS_CHECK_GE(greensSeen, 100, "greens present during the refinement");
}

void PhantomFallbacks(const char* name, const std::vector<float>& volume, int n)
{
  TriangleMesh mesh = dsphantom::EnclosingBox(n, 1);
  MultilevelParameters p;
  p.CheckTopology = true;
  MultilevelSolver s;
  s.SetParameters(p);
  std::string err;
  DS_CHECK(s.Run(volume.data(), dsphantom::Geometry(n), mesh, &err), err);
  int worstNew = 0, worstFallback = 0, total = 0, totalFallback = 0;
  double worst = 0;
  for (const LevelRecord& l : s.GetLevels())
  {
    const RefinementCounts& rc = l.Refinement;
    if (rc.NewVertices == 0)
      continue;
    total += rc.NewVertices;
    totalFallback += rc.FallbackVertices;
    const double share = double(rc.FallbackVertices) / rc.NewVertices;
    if (share >= worst)
    {
      worst = share;
      worstNew = rc.NewVertices;
      worstFallback = rc.FallbackVertices;
    }
  }
  std::cout << name << ": " << totalFallback << " of " << total
            << " new vertices at the midpoint; worst step " << worstFallback << " of " << worstNew
            << std::endl;
  DS_CHECK_GE(total, 500, std::string(name) + ": new vertices over the run");
  DS_CHECK_LE(worst, 0.05, std::string(name) + ": worst step's share of midpoint fallbacks");
}
} // namespace

int TestButterflyAdaptive(int, char*[])
{
  CubicGridStaysExact();
  const int n = 128;
  std::vector<float> sphere = dsphantom::Sphere(n, 32), cube = dsphantom::Cube(n, 16);
  PhantomFallbacks("sphere r32", sphere, n);
  PhantomFallbacks("cube 16", cube, n);
  return dstest::Result("TestButterflyAdaptive");
}

int main(int argc, char* argv[])
{
  return TestButterflyAdaptive(argc, argv);
}
