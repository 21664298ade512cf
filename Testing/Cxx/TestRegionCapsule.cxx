// SPDX-License-Identifier: BSD-3-Clause
// The region force on a long, thin object from a box start (docs/METHOD.md §9.3): the soft
// capsule (radius 9 voxels, 140 long, noise of a tenth of the contrast) from a box just
// outside it (24 x 24 x 168 voxels, 2 triangles per quad: 12 x 84 voxel triangles), Sigma
// 2.5 voxels, IntensityRange [50, 200] (the capsule's 100 inside, 0 outside, 50 on its
// radius), the default RegionWeight.
// - TriangleMesh::SplitElongatedEdges: the box's long edges (84 and 85 voxels) come down to
//   about the length asked (14: measured 442 vertices, the longest edge 17, an end quad's
//   diagonal, not twice its neighbours); the shape, volume,
//   closedness, orientation and Euler characteristic are kept; no round passes the budget of
//   points; a cube (edges 12 and 17, none twice another of its triangle) is left untouched.
// - The solve: before the split, the uniform splits left 3 x 21 voxel triangles whose creases
//   slid along themselves and folded (5 165 vertices, mean 5.8 voxels off, 3 617 intersecting
//   pairs); now the surface rests on the capsule: mean distance to its radius < 0.2 voxel, no
//   self-intersections, fewer than 2 000 vertices (measured: 793, 0.045 voxel, 0 pairs).
#include "CapsulePhantom.h"
#include "DSTestHelpers.h"

#include "dsMultilevel.h"
#include "dsSelfIntersectionCount.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

using namespace dsurf;

namespace
{
const Vec3 BoxCentre = { 15.5, 15.5, 119.5 }, BoxHalf = { 12.0, 12.0, 84.0 };

void CheckSplit()
{
  TriangleMesh box = dstest::CapsuleBox(BoxCentre, BoxHalf);
  const double volume = box.SignedVolume();
  const int euler = box.EulerCharacteristic();
  std::string error;
  const int split = box.SplitElongatedEdges(14.0, 100000, &error);
  double longest = 0;
  for (const auto& e : box.Edges)
  {
    longest = std::max(longest, Norm(box.Points[e[1]] - box.Points[e[0]]));
  }
  std::cout << "the box's elongated edges: " << split << " split, " << box.NumberOfPoints()
            << " vertices, the longest edge " << longest << " voxels (85 before)" << std::endl;
  DS_CHECK(split > 0 && error.empty(), "the box's long edges are split: " + error);
  DS_CHECK(box.IsClosed() && box.IsConsistentlyOriented() && box.EulerCharacteristic() == euler,
    "the split box is closed, oriented, with its Euler characteristic");
  DS_CHECK(std::abs(box.SignedVolume() - volume) < 1e-9 * volume, "the split keeps the volume");
  DS_CHECK(longest < 17.0,
    "the long edges come down to about the length asked (the longest "
    "left: a 12 x 12 end quad's diagonal, 17)");
  TriangleMesh small = dstest::CapsuleBox(BoxCentre, BoxHalf);
  const int pointsBefore = small.NumberOfPoints();
  small.SplitElongatedEdges(14.0, 100, &error);
  std::cout << "with a budget of 100 points: " << pointsBefore << " -> " << small.NumberOfPoints()
            << std::endl;
  DS_CHECK(small.NumberOfPoints() <= 100 && small.IsClosed(),
    "a round of splits that would pass the budget of points is not taken");
  DS_CHECK(small.NumberOfPoints() > pointsBefore, "the rounds within the budget are taken");
  TriangleMesh cube = dstest::MakeCubeSurface(1, 12.0, { 0, 0, 0 });
  DS_CHECK(cube.BuildTopology(&error), error);
  const std::vector<Vec3> before = cube.Points;
  DS_CHECK(cube.SplitElongatedEdges(1.0, 100000, &error) == 0 && cube.Points == before,
    "a cube's triangles (edges 12 and 17) are left as they are");
}
} // namespace

int TestRegionCapsule(int, char*[])
{
  CheckSplit();
  const ImageGeometry g = dstest::CapsuleGeometry();
  const std::vector<float> image = dstest::CapsuleImage();
  TriangleMesh mesh = dstest::CapsuleBox(BoxCentre, BoxHalf);
  MultilevelParameters p;
  p.Sigma = 2.5;
  p.IntensityRange[0] = 50.0;
  p.IntensityRange[1] = 200.0;
  MultilevelSolver solver;
  solver.SetParameters(p);
  std::string error;
  DS_CHECK(solver.Run(image.data(), g, mesh, &error), "the solve runs: " + error);
  double sum = 0, worst = 0;
  for (const Vec3& x : mesh.Points)
  {
    const double d =
      std::abs(dstest::CapsuleAxisDistance(x[0], x[1], x[2]) - dstest::CapsuleRadius);
    sum += d;
    worst = std::max(worst, d);
  }
  const double mean = mesh.Points.empty() ? 1e9 : sum / mesh.Points.size();
  const int crossings = CountSelfIntersections(mesh);
  std::cout << "the capsule from a box, region force on: " << mesh.NumberOfPoints()
            << " vertices, mean distance " << mean << " voxel (max " << worst << "), " << crossings
            << " intersecting pairs" << std::endl;
  DS_CHECK(mean < 0.2, "the surface rests on the capsule (mean distance < 0.2 voxel)");
  DS_CHECK(crossings == 0, "no self-intersections");
  DS_CHECK(mesh.NumberOfPoints() < 2000, "a capsule's vertex count (< 2000)");
  return dstest::Result("TestRegionCapsule");
}

int main(int argc, char* argv[])
{
  return TestRegionCapsule(argc, argv);
}
