// SPDX-License-Identifier: BSD-3-Clause
// A piece's fine field smoothed in slabs (dsPieceSlabs.h), with the processes emulated by threads
// (EmulatedRanks.h): a 49 x 47 x 160 image of a soft ellipsoid with noise (spacings 1, 2 and 0.5:
// powers of two, so that a voxel's world point falls on the voxel in both fields' geometries and
// their samples compare bit for bit), two small spheres (near a corner, in the middle) as the
// surface,
// and a field over the whole image (a first level's box), so that each rank's part of the box
// holds more than half its piece and is smoothed slab by slab from the states the pieces pass,
// never held whole.
// - On 2 and 3 slabs along z, 3 bricks (z then y, as VTK's block mode cuts it) and 4 bricks
//   (2 along x, 2 along z), at sigma 1, 1.5, 3.5, 5.5 and 7 (0.5-14 voxels: the sampled
//   Gaussian or the recursive one on each axis, the sampled one along z at sigma 1 and the
//   recursive one along y at 7): every rank keeps its field in slabs, and its force equals the
//   serial field's bit for bit at every owned voxel near the surface, its pieces on two threads
//   against the serial field's one.
// - A box holding one slab and a few slices of the other: one rank smooths in slabs, the other
//   holds its part whole (each decides alone; the sums are the same), both bit for bit.
// - The surface moved to the far corner, past the tiles kept: every rank smooths its slabs again
//   alone (no sums: the emulated ranks would wait in them) and still equals the serial field
//   bit for bit.
#include "DSTestHelpers.h"
#include "PieceSlabs.h"
#include "ScaleSpaceTestUtils.h"
#include "TestSolverMeshes.h"

#include "dsFieldBricks.h"
#include "dsFieldGrid.h"
#include "dsPieceField.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace dsurf;

namespace
{
/// The image's geometry (the pieces' tests' one, spacings 1, 2 and 0.5), and the ellipsoid's centre
/// (world) and radii.
ImageGeometry Geometry()
{
  ImageGeometry g = dstest::AnisotropicGeometry(49, 47, 160);
  g.Spacing[1] = 2.0;
  g.Spacing[2] = 0.5;
  return g;
}
const Vec3 Centre{ 21.0, 48.0, 45.0 };
const Vec3 Radii{ 17.0, 38.0, 33.0 };

/// A soft ellipsoid (100 inside, 0 outside) with deterministic noise of 5 (SampleOnGrid visits
/// the voxels in order).
std::vector<float> Image(const ImageGeometry& g)
{
  unsigned state = 4242;
  return sstest::SampleOnGrid(g,
    [&](const double* x)
    {
      double r2 = 0.0;
      for (int a = 0; a < 3; ++a)
      {
        r2 += std::pow((x[a] - Centre[a]) / Radii[a], 2);
      }
      const double d = (std::sqrt(r2) - 1.0) * Radii[0]; // about the distance near the surface
      state = state * 1664525u + 1013904223u;
      return 100.0 / (1.0 + std::exp(d)) + 5.0 * (state >> 8) / 16777216.0;
    });
}

/// Whether world point x lies within `reach` of the sphere of `radius` around c.
bool Near(const double* x, const Vec3& c, double radius, double reach)
{
  return std::abs(Norm(Vec3{ x[0], x[1], x[2] } - c) - radius) <= reach;
}

/// Spheres of `radius` around the centres as one mesh.
TriangleMesh Spheres(const std::vector<Vec3>& centres, double radius)
{
  TriangleMesh mesh;
  for (const Vec3& c : centres)
  {
    const TriangleMesh sphere = dstest::MakeIcosphere(3, radius, c);
    const int offset = static_cast<int>(mesh.Points.size());
    mesh.Points.insert(mesh.Points.end(), sphere.Points.begin(), sphere.Points.end());
    for (std::array<int, 3> t : sphere.Triangles)
    {
      mesh.Triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
    }
  }
  std::string error;
  DS_CHECK(mesh.BuildTopology(&error), "spheres as one mesh: " + error);
  return mesh;
}

/// Largest |F_piece - F_whole| over the piece's owned voxels in `box` that `keep` accepts, and
/// how many of them lie in one field and not in the other; `compared` counts them.
void CompareOnOwned(const ForceField& whole, const ForceField& piece, const ImagePiece& p,
  const VoxelBox& box, const std::function<bool(const double*)>& keep, double& maxDiff,
  int& missing, long long& compared)
{
  for (int k = std::max(p.Owned.Begin[2], box.Begin[2]); k < std::min(p.Owned.End[2], box.End[2]);
       ++k)
    for (int j = std::max(p.Owned.Begin[1], box.Begin[1]); j < std::min(p.Owned.End[1], box.End[1]);
         ++j)
      for (int i = std::max(p.Owned.Begin[0], box.Begin[0]);
           i < std::min(p.Owned.End[0], box.End[0]); ++i)
      {
        const double ijk[3] = { double(i), double(j), double(k) };
        double x[3], a[3], b[3];
        p.Whole.IndexToWorld(ijk, x);
        if (!keep(x))
        {
          continue;
        }
        ++compared;
        const bool inWhole = whole.SampleForce(x, a);
        const bool inPiece = piece.SampleForce(x, b);
        missing += inWhole != inPiece;
        for (int c = 0; c < 3; ++c)
        {
          maxDiff = std::max(maxDiff, std::abs(a[c] - b[c]));
        }
      }
}

/// The owned voxels of rank r of 3 as VTK's block mode splits an image longest along z: rank 0
/// a third of z, ranks 1 and 2 the rest split along y.
VoxelBox BrickZY(const ImageGeometry& g, int r)
{
  VoxelBox owned = VoxelBox::Whole(g);
  dstest::SplitAxis(owned, 2, r == 0 ? 0 : 1, 3);
  if (r > 0)
  {
    owned.End[2] = g.Dimensions[2];
    dstest::SplitAxis(owned, 1, r - 1, 2);
  }
  return owned;
}

/// What a run of SlabFieldsExact solves: the level's box, the spheres of the surface, the rank
/// whose part is smoothed in slabs (the others hold it whole), and the far sphere the surface
/// moves to (none: not moved).
struct Scene
{
  VoxelBox Box;
  std::vector<Vec3> Centres;
  std::function<bool(int)> InSlabs;
  const Vec3* Far = nullptr;
};

/// Every rank's field of the scene's box around its spheres against the serial field; and again
/// after the surface moved to the far sphere, past the tiles kept.
void SlabFieldsExact(const ImageGeometry& g, const std::vector<float>& image, double sigma,
  const std::function<VoxelBox(int)>& ownedOf, int nRanks, const Scene& scene,
  const std::string& label)
{
  ScaleSpaceParameters parameters;
  parameters.Sigma = sigma;
  parameters.NumberOfThreads = 1;
  const VoxelBox& box = scene.Box;
  ForceField whole; // every value the bricks may hold
  std::string error;
  DS_CHECK(ComputeForceAtScale(ImageView::Of(image.data(), g), box, parameters, whole, &error),
    label + ": the serial field: " + error);
  parameters.NumberOfThreads = 2;
  const double radius = 5.0;
  const TriangleMesh surface = Spheres(scene.Centres, radius);
  const Vec3 far = scene.Far ? *scene.Far : Vec3{ 0.0, 0.0, 0.0 };
  const TriangleMesh moved = dstest::MakeIcosphere(3, radius, far);
  const auto nearSurface = [&](const double* x)
  {
    return std::any_of(scene.Centres.begin(), scene.Centres.end(),
      [&](const Vec3& c) { return Near(x, c, radius, 0.5 * sigma); });
  };
  dstest::EmulatedRanks ranks(nRanks);
  std::vector<double> diff(nRanks, -1.0), movedDiff(nRanks, -1.0);
  std::vector<int> ok(nRanks, 0), missing(nRanks, 0), smoothings(nRanks, 0), again(nRanks, 0);
  std::vector<long long> compared(nRanks, 0), movedCompared(nRanks, 0);
  ranks.Run(
    [&](int r)
    {
      std::vector<float> values;
      const ImagePiece piece = dstest::PieceOf<float>(
        g, image, ownedOf(r), [&](int a) { return PieceGhostVoxels(sigma, g, a); }, values);
      ForceField field;
      std::string message;
      ok[r] = ComputePieceForce(
        piece, box, parameters, dstest::ReductionsOf(ranks, r), field, &message, &surface);
      if (!ok[r] || !field.Bricks)
      {
        return;
      }
      smoothings[r] = field.Bricks->SlabSmoothings();
      diff[r] = 0.0;
      CompareOnOwned(whole, field, piece, box, nearSurface, diff[r], missing[r], compared[r]);
      if (!scene.Far)
      {
        return;
      }
      // Alone: the emulated ranks' sums would wait for the others.
      field.Bricks->Cover(moved);
      again[r] = field.Bricks->SlabSmoothings();
      movedDiff[r] = 0.0;
      CompareOnOwned(
        whole, field, piece, box,
        [&](const double* x) { return Near(x, far, radius, 0.5 * sigma); }, movedDiff[r],
        missing[r], movedCompared[r]);
    });
  std::cout << label << ": owned voxels compared per rank, near the first sphere and the moved one";
  for (int r = 0; r < nRanks; ++r)
  {
    std::cout << " " << compared[r] << " " << movedCompared[r] << ";";
  }
  std::cout << std::endl;
  for (int r = 0; r < nRanks; ++r)
  {
    const std::string rank = label + ", rank " + std::to_string(r);
    DS_CHECK(ok[r] == 1 && smoothings[r] == (scene.InSlabs(r) ? 1 : 0),
      rank +
        (scene.InSlabs(r) ? ": its field made, smoothed in slabs once"
                          : ": its field made, its part held whole"));
    DS_CHECK(diff[r] == 0.0,
      rank + ": the force at the owned voxels near the surface equals the serial field's");
    DS_CHECK(!scene.Far || (again[r] >= 1 && movedDiff[r] == 0.0),
      rank + ": the surface moved: still the serial field bit for bit");
    DS_CHECK(missing[r] == 0, rank + ": owned voxels inside one field and outside the other");
  }
  const auto some = [](const std::vector<long long>& c)
  { return std::count_if(c.begin(), c.end(), [](long long n) { return n > 0; }) > 0; };
  std::vector<long long> both(nRanks);
  for (int r = 0; r < nRanks; ++r)
  {
    both[r] = compared[r] + movedCompared[r];
  }
  DS_CHECK(std::count_if(both.begin(), both.end(), [](long long n) { return n > 0; }) >= 2,
    label + ": owned voxels compared on two ranks at least");
  DS_CHECK(!scene.Far || some(movedCompared), label + ": owned voxels near the far sphere");
  // The far sphere lies past the tiles kept near the others up to sigma 3.5 (above, they reach
  // 2 sigma and up to four bricks further, most of this image).
  DS_CHECK(!scene.Far || sigma > 3.5 || std::count(again.begin(), again.end(), 2) > 0,
    label + ": the rank holding the far sphere smoothed its slabs again, alone");
  DS_CHECK(ranks.Mismatches() == 0, label + ": the ranks reduced vectors of one size");
}
} // namespace

int TestPieceFieldSlabs(int, char*[])
{
  const ImageGeometry g = Geometry();
  const std::vector<float> image = Image(g);
  const auto slabs = [&g](int n)
  {
    return [&g, n](int r)
    {
      VoxelBox owned = VoxelBox::Whole(g);
      dstest::SplitAxis(owned, 2, r, n);
      return owned;
    };
  };
  const auto bricksXZ = [&g](int r)
  {
    VoxelBox owned = VoxelBox::Whole(g);
    dstest::SplitAxis(owned, 0, r % 2, 2);
    dstest::SplitAxis(owned, 2, r / 2, 2);
    return owned;
  };
  // A sphere near a corner and one in the middle (in the middle pieces, across the borders of
  // some), the far corner's to move to; the whole image as the box, every part in slabs.
  const Vec3 far{ 40.0, 85.0, 78.0 };
  Scene whole;
  whole.Box = VoxelBox::Whole(g);
  whole.Centres = { Vec3{ 5.0, 10.0, 12.0 }, Vec3{ 21.0, 40.0, 35.0 } };
  whole.InSlabs = [](int) { return true; };
  whole.Far = &far;
  for (const double sigma : { 1.0, 1.5, 3.5, 5.5, 7.0 })
  {
    const std::string s = ", sigma " + std::to_string(sigma).substr(0, 3);
    SlabFieldsExact(g, image, sigma, slabs(2), 2, whole, "2 slabs" + s);
    SlabFieldsExact(g, image, sigma, slabs(3), 3, whole, "3 slabs" + s);
    SlabFieldsExact(
      g, image, sigma, [&g](int r) { return BrickZY(g, r); }, 3, whole, "3 bricks z, y" + s);
    SlabFieldsExact(g, image, sigma, bricksXZ, 4, whole, "4 bricks x, z" + s);
  }
  // A box that holds the lower slab and a few slices of the upper one (a sphere across their
  // border): the lower rank smooths in slabs, the upper one holds its part whole, each deciding
  // alone, the same sums.
  Scene mixed;
  mixed.Box = VoxelBox::Whole(g);
  mixed.Box.End[2] = 92;
  mixed.Centres = { Vec3{ 21.0, 40.0, 45.0 } };
  mixed.InSlabs = [](int r) { return r == 0; };
  for (const double sigma : { 1.5, 5.5, 7.0 })
  {
    SlabFieldsExact(g, image, sigma, slabs(2), 2, mixed,
      "2 slabs, one in slabs and one whole, sigma " + std::to_string(sigma).substr(0, 3));
  }
  return dstest::Result("TestPieceFieldSlabs");
}

int main(int argc, char* argv[])
{
  return TestPieceFieldSlabs(argc, argv);
}
