// SPDX-License-Identifier: BSD-3-Clause
// The whole multilevel solve on a distributed image (MultilevelSolver::SetDistribution), the
// processes emulated by threads (EmulatedRanks.h): a soft capsule along z in a 32 x 32 x 240
// image with noise, split into 2 and 3 slabs along z (neighbouring pieces share their border
// voxels, as VTK's), each rank holding its slab and DistributedGhostVoxels() around it.
// - Every default, from the box around the volume: every rank ends with the serial surface, bit
//   for bit (the levels on the image's own grid use the recursive Gaussian, its state passed
//   from piece to piece), and no rank holds the whole image.
// - A start near the object with Sigma 2.5 voxels and the edge force alone (RegionWeight 0; the
//   region force's exchange is TestForceExchange's): the serial surface bit for bit, and no rank
//   holds the whole image.
// - Every default from the near start (sigma_0 from the start, the intensity range estimated,
//   both from the pieces), 3 slabs: the serial surface bit for bit (its levels pass 3-9 voxels
//   of sigma), and no rank holds the whole image.
// - A click grown by the region force in the ridged ball of TestRegionForce (RegionWeight 1,
//   every other default), 2 slabs: the serial surface bit for bit through the levels where the
//   force has faded and refinement keeps triangles finer than 2 sigma (UnsplitEdgeLength).
// - A click in the tube and slab phantom's ball (SeveralObjectPhantoms.h), every default, 2 and 4
//   slabs: front levels (at least one) follow its tube three voxels wide, the serial surface bit
//   for bit and the serial number of front levels, though on 4 slabs the outer ones hold nothing
//   of the surface's neighbourhood (every rank decides alike whether to make the field again).
// - Two clicks in the capsule as two objects (RegionWeight 1): they grow toward each other and
//   meet without crossing; the serial surface bit for bit on 2 ranks, and on two threads.
// - The ghost layers the request allows for (DistributedGhostVoxels): 13 with every default on
//   this image (the sampled Gaussian's largest radius and one, or the sigma_0 probe's), twice the
//   coarsest block for sigma_0 = extent / 6 at 512^3 and 1024^3 (54, 110), 11 with Sigma 2.5
//   voxels, one for a single level at 5 voxels (the recursive Gaussian), 13 for Sigma 8 voxels
//   (its levels below 3 voxels) at spacings 1 and 1.05; the whole axis for the
//   sigma_0 probe along an axis 3.7 times finer than the mean spacing.
// - Bad input: an empty piece on one rank fails every rank with a message (no rank waits in a
//   reduction: a hang would hit the ctest timeout); one rank's progress callback asking to stop
//   stops every rank after the same sweep, with the same surface; a click whose range leaves
//   out the capsule collapses, and every rank fails with the serial message.
#include "CapsulePhantom.h"
#include "DSTestHelpers.h"
#include "DistributedSolveCheck.h"
#include "PieceSlabs.h"
#include "SeveralObjectPhantoms.h"
#include "SoftBallImage.h"
#include "TestSolverMeshes.h"

#include "dsMultilevel.h"
#include "dsPieceField.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace dsurf;
using namespace dsdistributed;

namespace
{
/// The ridged ball of TestRegionForce (radius 30 +- 3 in 96^3, value 100 inside) as floats.
Phantom RidgedBall()
{
  const int n = 96;
  const double c = 47.5;
  vtkSmartPointer<vtkImageData> image = dstest::SoftRadialImage(
    n, c, [](double x, double y, double z) { return dstest::RidgedRadius(x, y, z, 30.0, 3.0); },
    100.0);
  Phantom phantom;
  phantom.Geometry = ImageGeometry();
  for (int a = 0; a < 3; ++a)
  {
    phantom.Geometry.Dimensions[a] = n;
  }
  const float* values =
    static_cast<vtkFloatArray*>(image->GetPointData()->GetScalars())->GetPointer(0);
  phantom.Image.assign(values, values + static_cast<size_t>(n) * n * n);
  return phantom;
}

/// A click at the centre of the tube and slab phantom's ball (SeveralObjectPhantoms.h: a tube
/// three voxels wide sticks out of it along y), every default: past sigma's floor front levels
/// follow the tube, each rank sampling the front where it owns the image (FrontTriangles). On 2
/// ranks the ball and tube straddle the slabs' border; on 4 the outer slabs hold nothing of the
/// surface's neighbourhood, yet every rank must make the field again or none (a front level keeps
/// sigma). The ranks give the serial surface and front levels.
void FrontLevels(const MultilevelParameters& defaults)
{
  const dsobjects::SeveralPhantom s = dsobjects::TubeSlabPhantom();
  Phantom phantom;
  ImageGeometry& g = phantom.Geometry;
  g = ImageGeometry();
  s.Phantom.Image->GetDimensions(g.Dimensions);
  const float* values =
    static_cast<vtkFloatArray*>(s.Phantom.Image->GetPointData()->GetScalars())->GetPointer(0);
  phantom.Image.assign(values, values + g.NumberOfVoxels());
  const dsobjects::Point3& c = dsobjects::tubeslab::Centre;
  const int front = SameAsSerial("a click followed along a tube (front levels)", defaults,
    dstest::MakeIcosphere(2, 5.0, { c[0], c[1], c[2] }), true, { 2, 4 }, phantom);
  DS_CHECK_GE(front, 1, "a click followed along a tube: front levels");
}

/// Two clicks in the capsule as two objects (docs/METHOD.md §9.9), RegionWeight 1: they grow
/// along it and meet. Two threads give the one-thread surface bit for bit, the ranks the serial
/// one, and no pair of the objects' triangles crosses.
void TwoObjects(const MultilevelParameters& defaults)
{
  TriangleMesh start = dstest::MakeIcosphere(2, 3.0, { 15.5, 15.5, 90.5 });
  const TriangleMesh second = dstest::MakeIcosphere(2, 3.0, { 15.5, 15.5, 150.5 });
  const int offset = start.NumberOfPoints();
  start.Objects.assign(offset, 0);
  for (const Vec3& x : second.Points)
  {
    start.Points.push_back(x);
    start.Objects.push_back(1);
  }
  for (const auto& t : second.Triangles)
  {
    start.Triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
  }
  MultilevelParameters p = defaults;
  p.RegionWeight = 1.0;
  SameAsSerial("two objects grown toward each other in the capsule", p, start, true, { 2 });
  const ImageGeometry g = dstest::CapsuleGeometry();
  const std::vector<float> image = dstest::CapsuleImage();
  TriangleMesh one = start, two = start;
  MultilevelSolver s1, s2;
  std::string e1, e2;
  s1.SetParameters(p);
  p.Solver.NumberOfThreads = 2;
  s2.SetParameters(p);
  DS_CHECK(s1.Run(image.data(), g, one, &e1) && s2.Run(image.data(), g, two, &e2), e1 + e2);
  DS_CHECK(one.Points == two.Points, "two objects: two threads give the one-thread surface");
  double gap = 1e300; // the nearest vertices of the two objects
  for (int v = 0; v < one.NumberOfPoints(); ++v)
  {
    for (int w = 0; w < one.NumberOfPoints() && one.Objects[v] == 0; ++w)
    {
      gap = one.Objects[w] == 1 ? std::min(gap, Norm(one.Points[v] - one.Points[w])) : gap;
    }
  }
  std::cout << "two objects: " << one.NumberOfPoints() << " vertices, " << s1.GetCrossingPairs()
            << " crossing pairs, nearest vertices " << gap << " apart" << std::endl;
  DS_CHECK(s1.GetCrossingPairs() == 0, "two objects: no pair crosses");
  DS_CHECK(gap < 1.0, "two objects: they meet (vertices less than a voxel apart)");
  DS_CHECK(one.Objects.size() == one.Points.size(), "every point keeps its object");
}

void GhostLayers(const MultilevelParameters& defaults)
{
  const auto ghost = [](const MultilevelParameters& p, const ImageGeometry& g)
  { return MultilevelSolver::DistributedGhostVoxels(p, g, 2); };
  ImageGeometry cube;
  cube.Dimensions[0] = cube.Dimensions[1] = cube.Dimensions[2] = 512;
  DS_CHECK(ghost(defaults, dstest::CapsuleGeometry()) == 13, "every default, 32 x 32 x 240: 13");
  DS_CHECK(ghost(defaults, cube) == 54, "every default, 512^3: 54 (blocks of 27)");
  cube.Dimensions[0] = cube.Dimensions[1] = cube.Dimensions[2] = 1024;
  DS_CHECK(ghost(defaults, cube) == 110, "every default, 1024^3: 110 (blocks of 55)");
  MultilevelParameters p = defaults;
  p.Sigma = 2.5;
  DS_CHECK(ghost(p, cube) == 11, "Sigma 2.5 voxels: 11");
  p.Sigma = 5.0;
  p.HierarchicalSigma = false;
  // One layer for its recursive Gaussian, but a click's blend test reads ramps of
  // BlendReachVoxels (dsClickCompetition.h).
  DS_CHECK(ghost(p, cube) == 3, "a single level at 5 voxels: 3");
  // Sigma 8 voxels halves through 2 voxels (the sampled Gaussian): 13 layers, also where a world
  // sigma just under 3 spacings divides back to 3.0 (spacing 1.05).
  p.HierarchicalSigma = true;
  for (const double spacing : { 1.0, 1.05 })
  {
    ImageGeometry g;
    g.Dimensions[0] = g.Dimensions[1] = g.Dimensions[2] = 64;
    g.Spacing[0] = g.Spacing[1] = g.Spacing[2] = spacing;
    p.Sigma = 8.0 * spacing;
    DS_CHECK(ghost(p, g) == 13,
      "Sigma 8 voxels, spacing " + std::to_string(spacing) + ": 13 (the sampled levels)");
  }
  // The sigma_0 probe smooths each piece on its own: along an axis 3.7 times finer than the mean
  // spacing its Gaussian is recursive, and it asks for that whole axis.
  ImageGeometry fine = dstest::CapsuleGeometry();
  fine.Spacing[2] = 0.3;
  fine.Spacing[0] = fine.Spacing[1] = 1.5;
  DS_CHECK(ghost(defaults, fine) == fine.Dimensions[2],
    "every default, z 3.7 times finer than the mean: whole z");
}

void BadInput(const TriangleMesh& box)
{
  const ImageGeometry g = dstest::CapsuleGeometry();
  const std::vector<float> image = dstest::CapsuleImage();
  const MultilevelParameters defaults;
  Outcome serial;
  std::vector<Outcome> ranks;
  Solve(g, image, defaults, box, 3, 1, serial, ranks);
  int failed = 0, said = 0;
  for (const Outcome& o : ranks)
  {
    failed += !o.Ok;
    said += o.Error.find("empty") != std::string::npos;
  }
  std::cout << "an empty piece on rank 1: " << ranks[1].Error << " / rank 0: " << ranks[0].Error
            << std::endl;
  DS_CHECK(failed == 3 && said == 3, "an empty piece on one rank fails every rank, saying why");
}
/// A click in the capsule whose range takes the background but not the capsule (RegionWeight 1):
/// the surface collapses (MultilevelSolver's CollapsedObject), on the slabs' border. Every rank
/// fails after the same batch with the serial message, none left waiting in a reduction.
void Collapse()
{
  const ImageGeometry g = dstest::CapsuleGeometry();
  const std::vector<float> image = dstest::CapsuleImage();
  MultilevelParameters p;
  p.Solver.NumberOfThreads = 1;
  p.RegionWeight = 1.0;
  p.IntensityRange[0] = -10.0;
  p.IntensityRange[1] = 10.0;
  const TriangleMesh click = dstest::MakeIcosphere(2, 3.0, { 15.5, 15.5, 119.5 });
  MultilevelSolver serial;
  serial.SetParameters(p);
  TriangleMesh mesh = click;
  std::string serialError;
  const bool serialOk = serial.Run(image.data(), g, mesh, &serialError);
  std::cout << "a collapse: " << serialError << std::endl;
  DS_CHECK(!serialOk && serialError.find("collapsed") != std::string::npos,
    "a collapse: the serial run fails, saying so");
  std::vector<Outcome> ranks;
  RankRuns(g, image, p, click, 2, -1, ranks);
  DS_CHECK(
    !ranks[0].Ok && !ranks[1].Ok && ranks[0].Error == serialError && ranks[1].Error == serialError,
    "a collapse: every rank fails with the serial message");
}

/// Rank 1's progress callback asks to stop at its second call: every rank stops after the same
/// sweep, with the same surface, none left waiting.
void AgreedAbort(const TriangleMesh& near)
{
  const ImageGeometry g = dstest::CapsuleGeometry();
  const std::vector<float> image = dstest::CapsuleImage();
  MultilevelParameters p;
  p.Solver.NumberOfThreads = 1;
  p.Sigma = 2.5;
  p.RegionWeight = 0.0;
  const int nRanks = 3;
  dstest::EmulatedRanks emulated(nRanks);
  std::vector<Outcome> ranks(nRanks);
  std::vector<int> aborted(nRanks, 0), sweeps(nRanks, 0);
  emulated.Run(
    [&](int r)
    {
      std::vector<float> held;
      const ImagePiece piece = Slab(g, image, r, nRanks, p, held);
      MultilevelSolver s;
      s.SetParameters(p);
      s.SetDistribution(piece, dstest::ReductionsOf(emulated, r));
      int calls = 0;
      s.SetProgressCallback([&calls, r](double) { return r != 1 || ++calls < 2; });
      ranks[r].Mesh = near;
      ImageView whole = piece.Image;
      whole.Geometry = g;
      ranks[r].Ok = s.Run(whole, ranks[r].Mesh, &ranks[r].Error);
      aborted[r] = s.GetAborted() && s.GetStopReason() == StopReason::Aborted;
      sweeps[r] = s.GetTotalSweeps();
    });
  std::cout << "rank 1 stops at its second progress report: sweeps per rank " << sweeps[0] << " "
            << sweeps[1] << " " << sweeps[2] << std::endl;
  DS_CHECK(std::count(aborted.begin(), aborted.end(), 1) == nRanks, "every rank stopped");
  DS_CHECK(sweeps[0] == sweeps[1] && sweeps[1] == sweeps[2], "after the same sweep");
  DS_CHECK(
    ranks[0].Mesh.Points == ranks[1].Mesh.Points && ranks[1].Mesh.Points == ranks[2].Mesh.Points,
    "with the same surface");
}
} // namespace

int TestDistributedSolve(int, char*[])
{
  const TriangleMesh around = dstest::CapsuleBox({ 15.5, 15.5, 119.5 }, { 15.0, 15.0, 119.0 });
  const TriangleMesh near = dstest::CapsuleBox({ 15.5, 15.5, 119.5 }, { 12.0, 12.0, 84.0 });
  MultilevelParameters defaults;
  defaults.Solver.NumberOfThreads = 1;
  // sigma_0 = extent / 6 = 16.9 voxels: one level on block means of 5, then 8.4 voxels on the
  // image's grid, with the recursive Gaussian passed from piece to piece.
  SameAsSerial("every default from the box", defaults, around, true);
  // sigma_0 = 2.5 voxels: the sampled Gaussian only, a dozen ghost layers.
  MultilevelParameters small = defaults;
  small.Sigma = 2.5;
  small.RegionWeight = 0.0;
  SameAsSerial("a start near the capsule, Sigma 2.5, RegionWeight 0", small, near, true);
  // Every default from the near start: sigma_0 from the start, the intensity range estimated
  // (3 ranks here; mpi_image_pieces.py runs 2 and 3 under MPI).
  SameAsSerial("every default from a start near the capsule", defaults, near, true, { 3 });
  // A click grown by the region force (RegionWeight 1, every other default) in the ridged ball:
  // sigma_0 16 voxels, so from sigma 2 on the force has faded to an eighth and refinement leaves
  // triangles finer than 2 sigma unsplit (UnsplitEdgeLength: the same voxel, sigma and sigma_0
  // on every rank; measured 5 644 vertices, 6 884 without the rule).
  MultilevelParameters click = defaults;
  click.RegionWeight = 1.0;
  SameAsSerial("a click grown in the ridged ball, RegionWeight 1", click,
    dstest::MakeIcosphere(2, 3.0, { 49.5, 46.5, 48.5 }), true, { 2 }, RidgedBall());
  FrontLevels(defaults);
  TwoObjects(defaults);
  GhostLayers(defaults);
  BadInput(around);
  AgreedAbort(near);
  Collapse();
  return dstest::Result("TestDistributedSolve");
}

int main(int argc, char* argv[])
{
  return TestDistributedSolve(argc, argv);
}
