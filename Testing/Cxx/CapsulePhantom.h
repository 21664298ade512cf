// SPDX-License-Identifier: BSD-3-Clause
// A soft capsule along z in a 32 x 32 x 240 image with noise, and closed box meshes around
// it: the phantom of TestDistributedSolve and TestRegionCapsule.
#ifndef CapsulePhantom_h
#define CapsulePhantom_h

#include "DSTestHelpers.h"
#include "TestSolverMeshes.h"

#include "dsScaleSpace.h"
#include "dsTriangleMesh.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace dstest
{
constexpr int CapsuleNX = 32, CapsuleNY = 32, CapsuleNZ = 240;
constexpr double CapsuleRadius = 9.0, CapsuleAxis = 15.5, CapsuleZ0 = 50.0, CapsuleZ1 = 190.0;

inline dsurf::ImageGeometry CapsuleGeometry()
{
  dsurf::ImageGeometry g;
  g.Dimensions[0] = CapsuleNX;
  g.Dimensions[1] = CapsuleNY;
  g.Dimensions[2] = CapsuleNZ;
  return g;
}

/// Distance of p from the capsule's axis segment (x = y = 15.5, z in [50, 190]).
inline double CapsuleAxisDistance(double x, double y, double z)
{
  const double zc = std::min(CapsuleZ1, std::max(CapsuleZ0, z));
  return std::sqrt((x - CapsuleAxis) * (x - CapsuleAxis) + (y - CapsuleAxis) * (y - CapsuleAxis) +
    (z - zc) * (z - zc));
}

/// The capsule of radius 9, soft edged (100 inside, 0 outside, 50 on the radius), with noise of
/// a tenth of the contrast.
inline std::vector<float> CapsuleImage()
{
  std::vector<float> v;
  unsigned state = 4711;
  for (int k = 0; k < CapsuleNZ; ++k)
    for (int j = 0; j < CapsuleNY; ++j)
      for (int i = 0; i < CapsuleNX; ++i)
      {
        const double d = CapsuleAxisDistance(i, j, k);
        state = state * 1664525u + 1013904223u;
        const double noise = 10.0 * ((state >> 8) / 16777216.0 - 0.5);
        v.push_back(
          static_cast<float>(100.0 / (1.0 + std::exp(2.0 * (d - CapsuleRadius))) + noise));
      }
  return v;
}

/// A closed box mesh around centre c with half sides h, 2 triangles per face subdivided.
inline dsurf::TriangleMesh CapsuleBox(const dsurf::Vec3& c, const dsurf::Vec3& h)
{
  dsurf::TriangleMesh m = MakeCubeSurface(1, 1.0, { 0, 0, 0 });
  for (dsurf::Vec3& p : m.Points)
  {
    p = { c[0] + h[0] * p[0], c[1] + h[1] * p[1], c[2] + h[2] * p[2] };
  }
  std::string err;
  DS_CHECK(m.BuildTopology(&err), err);
  return m;
}
} // namespace dstest

#endif
