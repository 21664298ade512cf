// SPDX-License-Identifier: BSD-3-Clause
#include "dsFrontGrid.h"

#include "dsMultilevel.h" // FrontGridMax, FrontLookSteps, FrontLookVoxels

#include <algorithm>
#include <cmath>

namespace dsurf
{
int FrontGridDivisions(const Vec3& a, const Vec3& b, const Vec3& d, double voxel)
{
  const Vec3 normal = Cross(b - a, d - a);
  if (!(Dot(normal, normal) > 0))
  {
    return 0;
  }
  const double longest =
    std::sqrt(std::max({ Dot(b - a, b - a), Dot(d - b, d - b), Dot(a - d, a - d) }));
  return static_cast<int>(
    std::ceil(std::min<double>(FrontGridMax, std::max(1.0, longest / voxel))));
}

long long FrontGridSamples(int divisions)
{
  return divisions > 0 ? FrontLookSteps * (divisions + 1LL) * (divisions + 2) / 2 : 0;
}

void FrontSamplePoints(const Vec3& a, const Vec3& b, const Vec3& d, int divisions, double voxel,
  std::vector<Vec3>& points)
{
  points.clear();
  const int k = divisions;
  const Vec3 normal = Cross(b - a, d - a);
  const Vec3 out = (FrontLookVoxels * voxel / std::sqrt(Dot(normal, normal))) * normal;
  for (int i = 0; i <= k; ++i)
  {
    for (int j = 0; i + j <= k; ++j)
    {
      const double u = static_cast<double>(i) / k, w = static_cast<double>(j) / k;
      const Vec3 x = (1.0 - u - w) * a + u * b + w * d;
      for (int step = 0; step < FrontLookSteps; ++step)
      {
        const double depth = static_cast<double>(step) / (FrontLookSteps - 1);
        points.push_back(x + depth * out);
      }
    }
  }
}

bool ObjectBeyond(const double* inObject, long long samples)
{
  for (long long at = 0; at < samples; at += FrontLookSteps)
  {
    if (std::all_of(inObject + at, inObject + at + FrontLookSteps, [](double n) { return n > 0; }))
    {
      return true;
    }
  }
  return false;
}
} // namespace dsurf
