// SPDX-License-Identifier: BSD-3-Clause
#include "dsTriangleDistance.h"

#include "dsSelfIntersectionCount.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dsurf
{
Vec3 ClosestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
  if (d1 <= 0 && d2 <= 0)
  {
    return a;
  }
  const Vec3 bp = p - b;
  const double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
  {
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    return a + (d1 / (d1 - d3)) * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
  {
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    return a + (d2 / (d2 - d6)) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0))
  {
    // Degenerate (zero area): the nearest of its three edges' points.
    Vec3 best = a;
    double bestD = Dot(p - a, p - a);
    const Vec3 corners[3] = { a, b, c };
    for (int k = 0; k < 3; ++k)
    {
      const Vec3& s = corners[k];
      const Vec3 e = corners[(k + 1) % 3] - s;
      const double ee = Dot(e, e);
      const double t = ee > 0 ? std::min(1.0, std::max(0.0, Dot(p - s, e) / ee)) : 0.0;
      const Vec3 q = s + t * e;
      const double d = Dot(p - q, p - q);
      if (d < bestD)
      {
        bestD = d;
        best = q;
      }
    }
    return best;
  }
  const double v = vb / sum, w = vc / sum;
  return a + v * ab + w * ac;
}

Vec3 SegmentSeparation(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1)
{
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = Dot(d1, d1), e = Dot(d2, d2), f = Dot(d2, r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0)
  {
    return q0 - p0;
  }
  if (a <= 0)
  {
    t = std::min(1.0, std::max(0.0, f / e));
  }
  else
  {
    const double c = Dot(d1, r);
    if (e <= 0)
    {
      s = std::min(1.0, std::max(0.0, -c / a));
    }
    else
    {
      const double b = Dot(d1, d2);
      const double denom = a * e - b * b;
      s = denom > 0 ? std::min(1.0, std::max(0.0, (b * f - c * e) / denom)) : 0.0;
      t = (b * s + f) / e;
      if (t < 0)
      {
        t = 0;
        s = std::min(1.0, std::max(0.0, -c / a));
      }
      else if (t > 1)
      {
        t = 1;
        s = std::min(1.0, std::max(0.0, (b - c) / a));
      }
    }
  }
  return (q0 + t * d2) - (p0 + s * d1);
}

double SegmentDistance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1)
{
  return Norm(SegmentSeparation(p0, p1, q0, q1));
}

Vec3 TriangleSeparation(
  const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2)
{
  if (TrianglesIntersect(a0, a1, a2, b0, b1, b2))
  {
    return Vec3{ 0, 0, 0 };
  }
  const Vec3 a[3] = { a0, a1, a2 }, b[3] = { b0, b1, b2 };
  Vec3 best{ 0, 0, 0 };
  double nearest = std::numeric_limits<double>::infinity();
  auto keep = [&](const Vec3& v)
  {
    const double d = Norm(v);
    if (d < nearest)
    {
      nearest = d;
      best = v;
    }
  };
  for (int k = 0; k < 3; ++k)
  {
    keep(ClosestPointOnTriangle(a[k], b0, b1, b2) - a[k]);
    keep(b[k] - ClosestPointOnTriangle(b[k], a0, a1, a2));
    for (int j = 0; j < 3; ++j)
    {
      keep(SegmentSeparation(a[k], a[(k + 1) % 3], b[j], b[(j + 1) % 3]));
    }
  }
  return best;
}

double TriangleDistance(
  const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2)
{
  return Norm(TriangleSeparation(a0, a1, a2, b0, b1, b2));
}
} // namespace dsurf
