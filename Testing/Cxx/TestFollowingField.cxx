// SPDX-License-Identifier: BSD-3-Clause
// The first level's force field on the image's own grid follows the surface
// (MultilevelSolver::FollowSurface, docs/METHOD.md §9.7): a click near one end of a capsule
// (CapsulePhantom.h) padded into a 272 x 272 x 240 image (17.8 million voxels), Sigma 4 voxels,
// RegionWeight 1, every other default. The first level is on the image's own grid and the
// surface grows along the capsule far beyond its first box:
// - the field is made again at least once, its last box at most an eighth of the image, and no
//   force sample misses it (LevelRecord::FieldBoxes, FieldVoxels, FieldMisses);
// - the surface lies on the capsule (mean 0.3 voxel at most) and reaches its far end;
// - 2 and 4 ranks give the serial surface bit for bit: every rank decides alike when to make the
//   field again, and on 4 two pieces hold nothing of the first box, then part of a later one.
// A test of its own: the image is large, and under the sanitizers this case takes minutes.
#include "DistributedSolveCheck.h"
#include "TestSolverMeshes.h"

#include "dsFieldGrid.h"

#include <cmath>

using namespace dsdistributed;

namespace
{
/// How far WideCapsule moves the capsule along x and y (its axis at 128.5).
constexpr int WideCapsuleShift = 113;

/// The capsule padded with noisy background into a 272 x 272 x 240 image (17.8 million voxels),
/// moved by WideCapsuleShift along x and y.
Phantom WideCapsule()
{
  Phantom phantom;
  const int n = 272, shift = WideCapsuleShift;
  phantom.Geometry.Dimensions[0] = phantom.Geometry.Dimensions[1] = n;
  const std::vector<float> capsule = dstest::CapsuleImage();
  phantom.Image.assign(static_cast<std::size_t>(n) * n * dstest::CapsuleNZ, 0.0f);
  unsigned state = 815;
  for (std::size_t v = 0; v < phantom.Image.size(); ++v)
  {
    state = state * 1664525u + 1013904223u;
    phantom.Image[v] = static_cast<float>(10.0 * ((state >> 8) / 16777216.0 - 0.5));
  }
  for (int k = 0; k < dstest::CapsuleNZ; ++k)
    for (int j = 0; j < dstest::CapsuleNY; ++j)
      for (int i = 0; i < dstest::CapsuleNX; ++i)
      {
        phantom.Image[(i + shift) + n * ((j + shift) + static_cast<std::size_t>(n) * k)] =
          capsule[i + dstest::CapsuleNX * (j + static_cast<std::size_t>(dstest::CapsuleNY) * k)];
      }
  return phantom;
}

/// A click near one end of the capsule in a large image (Sigma 4 voxels,
/// RegionWeight 1, every other default): the first level is on the image's own grid, and the
/// surface grows along the capsule far beyond its first box (from the click, sigma_0 would be
/// 17 voxels, the capsule's length showing in its rays: block means).
/// The first level's field follows it (MultilevelSolver::FollowSurface): made again over larger
/// boxes, the last still a small part of the image, the surface reaching the capsule's far end;
/// every rank decides alike when to make it again, so 2 and 4 ranks give the serial surface.
void FollowingField(const MultilevelParameters& defaults)
{
  const Phantom phantom = WideCapsule();
  MultilevelParameters p = defaults;
  p.RegionWeight = 1.0;
  p.Sigma = 4.0;
  Outcome serial;
  SameAsSerial("a click grown along the capsule, its first field following it", p,
    dstest::MakeIcosphere(2, 3.0, { 128.5, 128.5, 70.5 }), true, { 2, 4 }, phantom, &serial);
  const LevelRecord& first = serial.First;
  double zMax = 0, off = 0; // off: the vertices' mean distance from the capsule's surface
  for (const Vec3& x : serial.Mesh.Points)
  {
    zMax = std::max(zMax, x[2]);
    off +=
      std::abs(dstest::CapsuleAxisDistance(x[0] - WideCapsuleShift, x[1] - WideCapsuleShift, x[2]) -
        dstest::CapsuleRadius);
  }
  off /= std::max(1, serial.Mesh.NumberOfPoints());
  std::cout << "following field: sigma_0 " << first.Sigma << ", " << first.FieldBoxes
            << " boxes on the first level, the last of " << first.FieldVoxels << " of "
            << phantom.Geometry.NumberOfVoxels() << " voxels, " << first.FieldMisses
            << " samples missed; the surface reaches z " << zMax << ", " << off
            << " voxel from the capsule (mean)" << std::endl;
  DS_CHECK(first.Sigma < 9.0, "following field: the first level is on the image's own grid");
  DS_CHECK(first.FieldBoxes >= 2, "following field: the first level's box followed the surface");
  DS_CHECK_LE(first.FieldVoxels, phantom.Geometry.NumberOfVoxels() / 8,
    "following field: the first level's last box (voxels)");
  DS_CHECK(first.FieldMisses == 0, "following field: every force sample fell in the field");
  DS_CHECK_LE(off, 0.3, "following field: the vertices' mean distance from the capsule (voxels)");
  DS_CHECK(std::abs(zMax - (dstest::CapsuleZ1 + dstest::CapsuleRadius)) < 2.0,
    "following field: the surface reaches the capsule's far end (z " + std::to_string(zMax) +
      ", the end at " + std::to_string(dstest::CapsuleZ1 + dstest::CapsuleRadius) + ")");
}

} // namespace

int TestFollowingField(int, char*[])
{
  MultilevelParameters defaults;
  defaults.Solver.NumberOfThreads = 1;
  FollowingField(defaults);
  return dstest::Result("TestFollowingField");
}

int main(int argc, char* argv[])
{
  return TestFollowingField(argc, argv);
}
