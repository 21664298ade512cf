// SPDX-License-Identifier: BSD-3-Clause
// Where the force -grad P of a binary cube (faces halfway between voxels) vanishes near its
// creases, at the fine sigmas that end the hierarchy (docs/METHOD.md §6 item 1): on a face it
// is on the face; on the bisector of an edge and on the diagonal of a corner it lies inside,
// as for the continuous Gaussian (1.32 sigma along a corner's diagonal: 0.88 voxel at 2/3), and
// no further. The force is the chain rule's, H grad s / |grad s|: with central differences of P
// the zeros lay 0.95 and 1.63 voxels inside at sigma 2/3 (0.84 and 1.50 at 1/2), and the
// solved surface's worst vertex (the 128^3 cube from the box) 0.81 voxel off.
#include "DSTestHelpers.h"
#include "HierarchyPhantoms.h"

#include "dsScaleSpace.h"

#include <cmath>
#include <iostream>
#include <vector>

using namespace dsurf;

namespace
{
const int N = 40;
const double Half = 12.0; // faces at centre +- 12, corners at (7.5 or 31.5) on every axis

/// The distance from `start` along the unit direction `inward` at which the force's component
/// along `inward` changes sign from pulling inward to pushing outward (searched from 2 voxels
/// outside to 3 inside); NaN when it does not.
double ZeroAlong(const ForceField& field, const Vec3& start, const Vec3& inward)
{
  double previous = 0, previousT = -2.0;
  for (int s = 0; s <= 500; ++s)
  {
    const double t = -2.0 + 0.01 * s;
    const Vec3 x = start + t * inward;
    double f[3];
    field.SampleForce(x.data(), f);
    const double along = f[0] * inward[0] + f[1] * inward[1] + f[2] * inward[2];
    if (s > 0 && previous > 0 && along <= 0)
    {
      return previousT + (t - previousT) * previous / (previous - along);
    }
    previous = along;
    previousT = t;
  }
  return std::nan("");
}
} // namespace

int TestScaleSpaceCorner(int, char*[])
{
  const std::vector<float> cube = dsphantom::Cube(N, Half);
  const ImageGeometry geometry = dsphantom::Geometry(N);
  const double c = dsphantom::Center(N), e = c + Half; // a corner at (e, e, e)
  const double r2 = 1.0 / std::sqrt(2.0), r3 = 1.0 / std::sqrt(3.0);
  // sigma, and the largest distance inside allowed for the zero on an edge's bisector and on a
  // corner's diagonal (measured 0.37 / 0.71 at 1/2 and 0.45 / 0.86 at 2/3 voxel).
  struct Case
  {
    double Sigma, Edge, Corner;
  };
  for (const Case& k : { Case{ 0.5, 0.45, 0.85 }, Case{ 2.0 / 3.0, 0.55, 1.0 } })
  {
    ScaleSpaceParameters p;
    p.Sigma = k.Sigma;
    ForceField field;
    std::string error;
    DS_CHECK(ComputeScaleSpaceForce(cube.data(), geometry, p, field, &error), error);
    const double face = ZeroAlong(field, Vec3{ e, c + 3, c - 2 }, Vec3{ -1, 0, 0 });
    const double edge = ZeroAlong(field, Vec3{ e, e, c + 1 }, Vec3{ -r2, -r2, 0 });
    const double corner = ZeroAlong(field, Vec3{ e, e, e }, Vec3{ -r3, -r3, -r3 });
    std::cout << "sigma " << k.Sigma << ": the force vanishes " << face << " inside a face, "
              << edge << " along an edge's bisector, " << corner << " along a corner's diagonal"
              << std::endl;
    DS_CHECK_LE(std::abs(face), 0.01, "|zero on a face's normal - the face| (voxels)");
    DS_CHECK(edge > 0 && corner > edge, "the creases' zeros lie inside, the corner's deepest");
    DS_CHECK_LE(edge, k.Edge, "zero on an edge's bisector, inside the edge (voxels)");
    DS_CHECK_LE(corner, k.Corner, "zero on a corner's diagonal, inside the corner (voxels)");
  }
  return dstest::Result("TestScaleSpaceCorner");
}

int main(int argc, char* argv[])
{
  return TestScaleSpaceCorner(argc, argv);
}
