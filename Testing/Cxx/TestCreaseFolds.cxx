// SPDX-License-Identifier: BSD-3-Clause
// A fine box around the 128^3 cube phantom with a small constant sigma (0.7 voxel): the start is
// subdivided to ~2-voxel edges (24 578 vertices) and the sweeps must leave no self-intersecting
// triangle pairs. The thin-plate term moves the vertices at the box's creases, and Gauss-Seidel
// passes a trace of that motion (1e-12 voxel) across the flat faces within one sweep; the
// self-intersection count once took the nearly coplanar neighbours that result for folds (234
// pairs after the first sweep, more after each "smoothing" of them), with the docs/METHOD.md §5
// rule on and with the edge force off alike. The count and the fold smoothing must see none.
#include "DSTestHelpers.h"
#include "HierarchyPhantoms.h"
#include "dsMultilevel.h"
#include "dsSelfIntersectionCount.h"

using namespace dsurf;

namespace
{
const int N = 128;

/// Level 0 only, at most `sweeps` sweeps from the box (it converges in ~5); the worst count after
/// any sweep in `worst`.
MultilevelSolver Solve(double edgeWeight, int sweeps, TriangleMesh& mesh, int& worst)
{
  MultilevelParameters p;
  p.HierarchicalSigma = false;
  p.Sigma = 0.7; // the start split to the mean edge nearest 4 sigma = 2.8: six times
  p.EdgeWeight = edgeWeight;
  p.MaxLevels = 0;
  p.MaxSweeps = sweeps;
  p.SweepBatch = 1;
  DS_CHECK(p.Solver.ProjectExternalForce, "the docs/METHOD.md §5 rule is on");
  mesh = dsphantom::EnclosingBox(N, 2);
  worst = 0;
  MultilevelSolver s;
  s.SetParameters(p);
  s.SetSweepCallback(
    [&worst](const SweepRecord&, const TriangleMesh& m)
    {
      worst = std::max(worst, CountSelfIntersections(m));
      return true;
    });
  const std::vector<float> volume = dsphantom::Cube(N, 16.0);
  std::string err;
  DS_CHECK(s.Run(volume.data(), dsphantom::Geometry(N), mesh, &err), err);
  return s;
}
} // namespace

int TestCreaseFolds(int, char*[])
{
  for (const double edgeWeight : { 1.0, 0.0 })
  {
    TriangleMesh mesh;
    int worst = -1;
    const MultilevelSolver s = Solve(edgeWeight, 10, mesh, worst);
    const LevelRecord& level = s.GetLevels().back();
    // The off-plane trace on the faces: vertices of the face x = 0.5 away from its edges.
    double offPlane = 0;
    for (const Vec3& p : mesh.Points)
    {
      if (std::abs(p[0] - 0.5) < 1e-6 && p[1] > 20 && p[1] < 107 && p[2] > 20 && p[2] < 107)
      {
        offPlane = std::max(offPlane, std::abs(p[0] - 0.5));
      }
    }
    std::cout << "  edge weight " << edgeWeight << ": " << s.GetInitialSubdivisions()
              << " subdivisions, " << mesh.NumberOfPoints() << " vertices, mean edge "
              << level.MeanEdgeLength << ", " << level.Sweeps << " sweeps; worst count " << worst
              << ", folds before/after smoothing " << level.Folds.Before << "/" << level.Folds.After
              << ", largest off-plane motion inside a face " << offPlane << std::endl;
    DS_CHECK(mesh.NumberOfPoints() == 24578 && level.Sweeps >= 1,
      "the fine start (24 578 vertices), solved");
    DS_CHECK(offPlane > 0, "the sweeps moved face vertices off their plane (the trace)");
    DS_CHECK_LE(worst, 0, "self-intersecting pairs after any sweep");
    DS_CHECK_LE(level.Folds.Before, 0, "pairs the fold smoothing found");
    DS_CHECK_LE(CountSelfIntersections(mesh), 0, "self-intersecting pairs at the end");
  }
  return dstest::Result("TestCreaseFolds");
}

int main(int argc, char* argv[])
{
  return TestCreaseFolds(argc, argv);
}
