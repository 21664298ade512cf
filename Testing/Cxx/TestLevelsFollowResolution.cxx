// SPDX-License-Identifier: BSD-3-Clause
// The levels follow the resolution (docs/METHOD.md §6, dsMultilevel.h): from the box around the
// volume, every parameter default, a run refines while the error estimator (in voxels) says
// detail is present and ends at the level solved at sigma's floor, so a larger volume gets more
// levels; MaxLevels only caps them. The reason the levels ended is reported. With constant sigma
// (HierarchicalSigma off) and no Sigma given, sigma is the paper's small one: one voxel.
// UnsplitEdgeLength: the voxel; with the region force sigma, 2 sigma from sigma_0 / 8 on.
#include "DSTestHelpers.h"
#include "HierarchyPhantoms.h"
#include "TestSolverMeshes.h"
#include "dsMultilevel.h"
#include "dsSelfIntersectionCount.h"

#include <cmath>

using namespace dsurf;

namespace
{
struct Run
{
  MultilevelSolver Solver;
  TriangleMesh Mesh;
  dsphantom::Accuracy Accuracy;
};

void Solve(Run& run, const std::vector<float>& volume, const ImageGeometry& geometry,
  const MultilevelParameters& p, int n, double radius)
{
  run.Solver.SetParameters(p);
  std::string err;
  DS_CHECK(run.Solver.Run(volume.data(), geometry, run.Mesh, &err), err);
  run.Accuracy = dsphantom::Measure(
    run.Mesh, [n, radius](const Vec3& x) { return dsphantom::SphereDistance(x, n, radius); });
  const auto& levels = run.Solver.GetLevels();
  std::cout << "  " << n << "^3: " << levels.size() << " levels, sigma " << levels.front().Sigma
            << " -> " << levels.back().Sigma << ", " << StopReasonName(run.Solver.GetStopReason())
            << ", " << run.Mesh.NumberOfTriangles() << " triangles, mean |d| " << run.Accuracy.Mean
            << ", max " << run.Accuracy.Max << std::endl;
}

void HierarchyFollowsResolution()
{
  // Sphere of radius n/4 in n^3 from the box: sigma_0 = n / 6 halves to its floor, 2/3 voxel,
  // which takes log2(n / 4) halvings: 4 at 64^3, 5 at 128^3 (the former fixed 4 stopped at
  // 1.3 voxels at 128^3).
  int previousLevels = 0;
  for (const int n : { 64, 128 })
  {
    Run run;
    run.Mesh = dsphantom::EnclosingBox(n, 1);
    Solve(run, dsphantom::Sphere(n, n / 4.0), dsphantom::Geometry(n), MultilevelParameters(), n,
      n / 4.0);
    const auto& levels = run.Solver.GetLevels();
    const int halvings = static_cast<int>(std::lround(std::log2(n / 4.0)));
    DS_CHECK(static_cast<int>(levels.size()) == halvings + 1, "levels from sigma_0 to the floor");
    DS_CHECK(std::abs(levels.back().Sigma - SigmaFloorVoxels) < 1e-12,
      "the last level at sigma's floor, 2/3 voxel");
    DS_CHECK(run.Solver.GetStopReason() == StopReason::SigmaFloor, "stop reason: sigma floor");
    DS_CHECK(static_cast<int>(levels.size()) > previousLevels, "a finer volume, more levels");
    previousLevels = static_cast<int>(levels.size());
    DS_CHECK_LE(CountSelfIntersections(run.Mesh), 0, "self-intersecting pairs");
    if (n == 128)
    {
      // The accuracy goals for the binary sphere of radius 32 (the former schedule: 0.079 / 0.336
      // with 4 levels, and ~10 000 triangles with the relative threshold run to the floor).
      DS_CHECK_LE(run.Accuracy.Mean, 0.07, "sphere r 32: mean |d| (voxels)");
      DS_CHECK_LE(run.Accuracy.Max, 0.30, "sphere r 32: max |d| (voxels)");
      DS_CHECK_LE(run.Mesh.NumberOfTriangles(), 6000, "sphere r 32: triangles");
    }
  }
}

void LastStepToTheFloor()
{
  // Sigma halves, and goes straight to its floor when the half would lie less than a third of
  // an octave (2^(1/3) = 1.26) above it.
  const double floor = 2.0 / 3.0;
  DS_CHECK(NextHierarchicalSigma(4.0, floor) == 2.0, "far above the floor: sigma halves");
  DS_CHECK(NextHierarchicalSigma(2.0, floor) == 1.0, "1 lies 1.5 floors up: sigma halves");
  DS_CHECK(NextHierarchicalSigma(1.875, floor) == 0.9375,
    "0.94 lies 1.41 floors up (the capsule of mpi_image_pieces): sigma halves");
  DS_CHECK(NextHierarchicalSigma(1.0, floor) == floor, "1 / 2 is below the floor: the floor");
  DS_CHECK(NextHierarchicalSigma(1.59, floor) == floor,
    "0.795 lies 1.19 floors up (the Colin27 click's 1.59 -> 0.80 -> 0.67 mm): the floor");
  DS_CHECK(NextHierarchicalSigma(floor, floor) == floor, "at the floor sigma stays");
  DS_CHECK(NextHierarchicalSigma(0.5, floor) == 0.5, "a sigma below the floor stays");
  int levels = 1;
  for (double s = 12.6; s > floor; s = NextHierarchicalSigma(s, floor))
  {
    ++levels;
  }
  DS_CHECK(levels == 5, "12.6 / floor = 2^4.24: 12.6, 6.3, 3.15, 1.58, 2/3 (five levels, not six)");

  // In a solve: the sphere of radius 16 in 64^3 from the box with Sigma 6.4 voxels solves
  // 6.4, 3.2, 1.6 and the floor (0.8 would lie 1.2 floors up), and still ends on the sphere.
  const int n = 64;
  MultilevelParameters p;
  p.Sigma = 6.4;
  Run run;
  run.Mesh = dsphantom::EnclosingBox(n, 1);
  Solve(run, dsphantom::Sphere(n, 16), dsphantom::Geometry(n), p, n, 16);
  const auto& solved = run.Solver.GetLevels();
  DS_CHECK(solved.size() == 4, "Sigma 6.4: four levels");
  DS_CHECK(solved.size() == 4 && solved[2].Sigma == 1.6 && solved[3].Sigma == floor,
    "Sigma 6.4: 1.6 then the floor");
  DS_CHECK_LE(run.Accuracy.Mean, 0.1, "Sigma 6.4: mean |d| (voxels)");
}

void CapAndBudget()
{
  const int n = 64;
  const std::vector<float> volume = dsphantom::Sphere(n, 16);
  MultilevelParameters p;
  p.MaxLevels = 2;
  Run capped;
  capped.Mesh = dsphantom::EnclosingBox(n, 1);
  Solve(capped, volume, dsphantom::Geometry(n), p, n, 16);
  DS_CHECK(capped.Solver.GetLevels().size() == 3, "MaxLevels 2: levels 0..2");
  DS_CHECK(capped.Solver.GetStopReason() == StopReason::MaxLevels, "stop reason: MaxLevels");

  p = MultilevelParameters();
  p.MaxSweeps = 30;
  Run budget;
  budget.Mesh = dsphantom::EnclosingBox(n, 1);
  Solve(budget, volume, dsphantom::Geometry(n), p, n, 16);
  DS_CHECK(budget.Solver.GetTotalSweeps() == 30, "MaxSweeps 30: thirty sweeps");
  DS_CHECK(budget.Solver.GetStopReason() == StopReason::MaxSweeps, "stop reason: MaxSweeps");

  p = MultilevelParameters();
  Run aborted;
  aborted.Mesh = dsphantom::EnclosingBox(n, 1);
  aborted.Solver.SetProgressCallback([](double) { return false; });
  Solve(aborted, volume, dsphantom::Geometry(n), p, n, 16);
  DS_CHECK(aborted.Solver.GetStopReason() == StopReason::Aborted, "stop reason: aborted");
  DS_CHECK(std::string(StopReasonName(StopReason::NoDetail)) == "no detail", "reason names");
}

void ConstantSigmaDefault()
{
  // A start 2.5 voxels outside the sphere of radius 32, constant sigma, no Sigma: one voxel,
  // kept on every level; the run ends when nothing is left to refine (or at the cap).
  const int n = 128;
  const std::vector<float> volume = dsphantom::Sphere(n, 32);
  const double c = dsphantom::Center(n);
  MultilevelParameters p;
  p.HierarchicalSigma = false;
  Run run;
  run.Mesh = dstest::MakeIcosphere(3, 34.5, { c, c, c });
  Solve(run, volume, dsphantom::Geometry(n), p, n, 32);
  for (const LevelRecord& level : run.Solver.GetLevels())
  {
    DS_CHECK(level.Sigma == 1.0, "constant sigma: one voxel on every level");
  }
  const StopReason why = run.Solver.GetStopReason();
  DS_CHECK(why == StopReason::NoDetail || why == StopReason::MaxLevels,
    "constant sigma ends when nothing is refined, or at the cap");
  DS_CHECK_LE(run.Accuracy.Mean, 0.15, "constant sigma 1 voxel: mean |d| (voxels)");
  DS_CHECK_LE(run.Accuracy.Max, 0.5, "constant sigma 1 voxel: max |d| (voxels)");

  // In world units: the mean spacing (0.5, 0.5, 1) -> 2/3.
  ImageGeometry g = dsphantom::Geometry(32);
  g.Spacing[0] = g.Spacing[1] = 0.5;
  const std::vector<float> small = dsphantom::Sphere(32, 8);
  p.MaxLevels = 0;
  Run scaled;
  scaled.Mesh = dstest::MakeIcosphere(2, 5, { 5, 5, 20 });
  scaled.Solver.SetParameters(p);
  std::string err;
  DS_CHECK(scaled.Solver.Run(small.data(), g, scaled.Mesh, &err), err);
  DS_CHECK(std::abs(scaled.Solver.GetFinalSigma() - 2.0 / 3.0) < 1e-12,
    "constant sigma: one mean spacing (2/3)");
}

void AbsoluteMarks()
{
  // The marking threshold is absolute: the same estimator marks the same triangles whatever the
  // rest of the mesh does (a relative threshold marked the busier half of a uniform one).
  TriangleMesh m = dstest::MakeIcosphere(1, 1, { 0, 0, 0 });
  std::string err;
  DS_CHECK(m.BuildTopology(&err), err);
  std::vector<double> e(m.NumberOfPoints(), 0.2);
  const auto count = [&](double threshold)
  {
    const std::vector<char> marks = MultilevelSolver::MarkTriangles(m, e, threshold, false);
    return static_cast<int>(std::count(marks.begin(), marks.end(), 1));
  };
  DS_CHECK(count(0.1) == m.NumberOfTriangles(), "an estimator above the threshold everywhere");
  DS_CHECK(count(0.3) == 0, "an estimator below the threshold everywhere: nothing marked");
  e[0] = 2.0; // one busy vertex: its fan's mean (2 + 0.2 + 0.2) / 3 = 0.8
  DS_CHECK(count(0.5) == m.VertexTriangleOffsets[1] - m.VertexTriangleOffsets[0],
    "one busy vertex: its fan is marked");
}
void UnsplitEdges()
{
  // Adaptive refinement leaves triangles whose edges are all shorter than UnsplitEdgeLength
  // (docs/METHOD.md §9.3): the voxel; with the region force sigma, and 2 sigma from the level
  // where the force has faded to an eighth (sigma_0 / 8: the Colin27 click's 25 -> 3.125 mm).
  const double voxel = 1.0, s0 = 25.0;
  DS_CHECK(UnsplitEdgeLength(voxel, 12.5, s0, false) == voxel, "no region force: the voxel");
  DS_CHECK(UnsplitEdgeLength(voxel, 0.5, s0, true) == voxel, "below a voxel: the voxel");
  DS_CHECK(
    UnsplitEdgeLength(voxel, 25.0, s0, true) == 25.0, "region force at full strength: sigma");
  DS_CHECK(UnsplitEdgeLength(voxel, 6.25, s0, true) == 6.25, "region force at a quarter: sigma");
  DS_CHECK(UnsplitEdgeLength(voxel, 3.125, s0, true) == 6.25, "faded to an eighth: 2 sigma");
  DS_CHECK(UnsplitEdgeLength(voxel, 1.5625, s0, true) == 3.125, "faded further: 2 sigma");
  DS_CHECK(UnsplitEdgeLength(voxel, 0.4, s0, true) == voxel, "2 sigma below a voxel: the voxel");
  DS_CHECK(UnsplitEdgeLength(voxel, 3.0, 3.0, true) == 3.0, "constant sigma never fades: sigma");
  DS_CHECK(RegionFade(3.125, s0) == RegionFadedShare, "three halvings: the fade is an eighth");
  DS_CHECK(RegionFade(50.0, s0) == 1.0, "above sigma_0 the force does not grow");
}
} // namespace

int TestLevelsFollowResolution(int, char*[])
{
  std::cout << "hierarchical sigma, defaults:" << std::endl;
  HierarchyFollowsResolution();
  LastStepToTheFloor();
  UnsplitEdges();
  std::cout << "caps:" << std::endl;
  CapAndBudget();
  std::cout << "constant sigma:" << std::endl;
  ConstantSigmaDefault();
  AbsoluteMarks();
  return dstest::Result("TestLevelsFollowResolution");
}

int main(int argc, char* argv[])
{
  return TestLevelsFollowResolution(argc, argv);
}
