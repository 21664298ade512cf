// SPDX-License-Identifier: BSD-3-Clause
// The sphere (radius 32 voxels in 128^3) from the box enclosing the volume: accuracy,
// triangle quality, no self-intersection, invariants after every level; and butterfly
// prolongation against linear (midpoint) prolongation by the sweeps each needs.
#include "DSSurfaceInvariants.h"
#include "HierarchyPhantoms.h"
#include "dsMultilevel.h"
#include "dsSelfIntersectionCount.h"

#include <algorithm>

using namespace dsurf;

namespace
{
const int N = 128;
const double R = 32.0;

struct Outcome
{
  int Sweeps = 0;
  /// Mean over the refined levels of the first sweep's mean correction in edge lengths:
  /// how far the new vertices' start values are from where the solver wants them.
  double FirstCorrection = 0;
};

Outcome Solve(const std::vector<float>& volume, MultilevelParameters p, TriangleMesh& mesh,
  const std::string& name)
{
  mesh = dsphantom::EnclosingBox(N, 2);
  p.CheckTopology = true;
  MultilevelSolver s;
  s.SetParameters(p);
  std::string err;
  DS_CHECK(s.Run(volume.data(), dsphantom::Geometry(N), mesh, &err), err);
  dstest::CheckSurfaceInvariants(dsphantom::EnclosingBox(N, 2), mesh, name);
  std::cout << "  " << name << ": sweeps per level";
  for (const auto& l : s.GetLevels())
  {
    std::cout << " " << l.Sweeps << (l.Converged ? "" : "(cap)");
    DS_CHECK(l.Converged, name + ": every level converges below the cap");
  }
  Outcome o;
  o.Sweeps = s.GetTotalSweeps();
  int refined = 0;
  for (const auto& l : s.GetLevels())
  {
    if (l.Level == 0)
    {
      continue;
    }
    for (const auto& r : s.GetSweeps())
    {
      if (r.Level == l.Level)
      {
        o.FirstCorrection += r.MeanCorrection / l.MeanEdgeLength;
        ++refined;
        break;
      }
    }
  }
  o.FirstCorrection /= std::max(1, refined);
  std::cout << " = " << o.Sweeps << ", triangles " << mesh.NumberOfTriangles()
            << ", first-sweep correction after refinement " << o.FirstCorrection << " edge"
            << std::endl;
  return o;
}
} // namespace

int TestHierarchySphere(int, char*[])
{
  const std::vector<float> volume = dsphantom::Sphere(N, R);
  auto dist = [](const Vec3& x) { return dsphantom::SphereDistance(x, N, R); };

  TriangleMesh mesh;
  MultilevelParameters p; // defaults: 4 levels, adaptive, butterfly, halving sigma
  Solve(volume, p, mesh, "adaptive, butterfly");
  const auto acc = dsphantom::Measure(mesh, dist);
  DS_CHECK_LE(acc.Mean, 0.15, "mean |distance| to the sphere (voxels)");
  DS_CHECK_LE(acc.Max, 0.5, "max |distance| (voxels)");
  DS_CHECK_GE(dsphantom::FractionMinAngleAtLeast(mesh, 20.0), 0.99,
    "fraction of triangles with min angle >= 20 deg");
  DS_CHECK_LE(CountSelfIntersections(mesh), 0, "self-intersecting triangle pairs");
  std::string msg;
  DS_CHECK(CheckTopologyInvariants(mesh, 2, true, &msg), msg);
  int labelled = 0, levelled = 0;
  for (int v = 0; v < mesh.NumberOfPoints(); ++v)
  {
    labelled += mesh.Labels[v] != LabelN ? 1 : 0;
    levelled += mesh.Levels[v] == 4 ? 1 : 0;
  }
  DS_CHECK(labelled > 0 && levelled > 0, "red-green labels and level-4 vertices present");

  // Butterfly vs linear prolongation. Butterfly puts new vertices nearer to where the
  // solver wants them: the first sweep after each refinement corrects less, in both modes.
  // With uniform refinement (the same meshes, only the start values differ) that also
  // saves sweeps; adaptively the two runs mark different triangles, so their sweep counts
  // are not comparable (measured: butterfly 198, linear 189 on different meshes).
  for (int uniform = 1; uniform >= 0; --uniform)
  {
    MultilevelParameters q;
    q.UniformRefinement = uniform != 0;
    TriangleMesh mb, ml;
    const std::string kind = uniform ? "uniform" : "adaptive";
    const Outcome ob = Solve(volume, q, mb, kind + ", butterfly");
    q.ButterflyProlongation = false;
    const Outcome ol = Solve(volume, q, ml, kind + ", linear");
    DS_CHECK_LE(ob.FirstCorrection / ol.FirstCorrection, 0.9,
      kind + ": first-sweep correction after refinement, butterfly / linear");
    if (uniform)
    {
      DS_CHECK_GE(ol.Sweeps - ob.Sweeps, 1,
        kind + ": sweeps saved by butterfly prolongation (linear - butterfly)");
    }
  }
  return dstest::Result("TestHierarchySphere");
}

int main(int argc, char* argv[])
{
  return TestHierarchySphere(argc, argv);
}
