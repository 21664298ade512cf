// SPDX-License-Identifier: BSD-3-Clause
// Phantoms and start surfaces shared by the hierarchy tests and benchmark: a binary
// cube and a binary sphere in an n^3 volume (unit spacing, origin 0), the box
// enclosing the volume as a coarse closed triangle mesh, and exact distances.
#ifndef HierarchyPhantoms_h
#define HierarchyPhantoms_h

#include "dsScaleSpace.h"
#include "dsTriangleMesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace dsphantom
{
using namespace dsurf;

inline dsurf::ImageGeometry Geometry(int n)
{
  dsurf::ImageGeometry g;
  g.Dimensions[0] = g.Dimensions[1] = g.Dimensions[2] = n;
  return g;
}

inline double Center(int n)
{
  return 0.5 * (n - 1);
}

/// 1 inside the axis-aligned cube of half-side `half` voxels around the centre, 0
/// elsewhere. With the centre at (n-1)/2 and an integer half side the boundary lies
/// exactly halfway between voxels, at distance `half` from the centre.
inline std::vector<float> Cube(int n, double half)
{
  std::vector<float> v(static_cast<size_t>(n) * n * n, 0.f);
  const double c = Center(n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (std::abs(i - c) < half && std::abs(j - c) < half && std::abs(k - c) < half)
          v[(static_cast<size_t>(k) * n + j) * n + i] = 1.f;
  return v;
}

/// Fraction (0..1, 4^3 supersampling) of the voxel at offset (x, y, z) from the centre that lies
/// inside the sphere of radius r: exact away from the boundary.
inline double SphereInsideFraction(double x, double y, double z, double r)
{
  const double d = std::sqrt(x * x + y * y + z * z);
  if (d < r - 1.0)
    return 1.0;
  if (d >= r + 1.0)
    return 0.0;
  int inside = 0;
  for (int s = 0; s < 64; ++s)
  {
    const double sx = x + ((s & 3) + 0.5) / 4 - 0.5;
    const double sy = y + (((s >> 2) & 3) + 0.5) / 4 - 0.5;
    const double sz = z + (((s >> 4) & 3) + 0.5) / 4 - 0.5;
    inside += sx * sx + sy * sy + sz * sz < r * r ? 1 : 0;
  }
  return inside / 64.0;
}

/// Binary sphere of radius r around the centre, anti-aliased by 4^3 supersampling so
/// the boundary is at radius r to well under a tenth of a voxel.
inline std::vector<float> Sphere(int n, double r)
{
  std::vector<float> v(static_cast<size_t>(n) * n * n, 0.f);
  const double c = Center(n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        v[(static_cast<size_t>(k) * n + j) * n + i] =
          static_cast<float>(SphereInsideFraction(i - c, j - c, k - c, r));
  return v;
}

/// The box enclosing the volume ([inset, n-1-inset]^3), each face a k x k grid of
/// quads split into two triangles, outward oriented, shared points merged.
inline dsurf::TriangleMesh EnclosingBox(int n, int k, double inset = 0.5)
{
  dsurf::TriangleMesh m;
  std::map<std::array<int, 3>, int> ids;
  const double lo = inset, hi = n - 1 - inset;
  auto point = [&](std::array<int, 3> g)
  {
    auto it = ids.find(g);
    if (it != ids.end())
      return it->second;
    const int id = static_cast<int>(m.Points.size());
    m.Points.push_back(
      { lo + (hi - lo) * g[0] / k, lo + (hi - lo) * g[1] / k, lo + (hi - lo) * g[2] / k });
    ids[g] = id;
    return id;
  };
  const double c = Center(n);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
    {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b)
        {
          auto at = [&](int da, int db)
          {
            std::array<int, 3> g{};
            g[axis] = side * k;
            g[u] = a + da;
            g[w] = b + db;
            return point(g);
          };
          const int p00 = at(0, 0), p10 = at(1, 0), p11 = at(1, 1), p01 = at(0, 1);
          std::array<int, 3> t1{ p00, p10, p11 }, t2{ p00, p11, p01 };
          for (auto* t : { &t1, &t2 })
          {
            const Vec3 nrm = dsurf::Cross(
              m.Points[(*t)[1]] - m.Points[(*t)[0]], m.Points[(*t)[2]] - m.Points[(*t)[0]]);
            const Vec3 out = m.Points[(*t)[0]] - Vec3{ c, c, c };
            if (dsurf::Dot(nrm, out) < 0)
              std::swap((*t)[1], (*t)[2]);
            m.Triangles.push_back(*t);
          }
        }
    }
  return m;
}

/// |distance| from p to the surface of the cube of half-side `half` around the centre.
inline double CubeDistance(const Vec3& p, int n, double half)
{
  const double c = Center(n);
  double q[3], outside = 0, inside = -1e300;
  for (int a = 0; a < 3; ++a)
  {
    q[a] = std::abs(p[a] - c) - half;
    outside += std::max(q[a], 0.0) * std::max(q[a], 0.0);
    inside = std::max(inside, q[a]);
  }
  return outside > 0 ? std::sqrt(outside) : std::abs(inside);
}

inline double SphereDistance(const Vec3& p, int n, double r)
{
  const double c = Center(n);
  return std::abs(dsurf::Norm(p - Vec3{ c, c, c }) - r);
}

struct Accuracy
{
  double Mean = 0, Max = 0;
};

template <typename Dist>
Accuracy Measure(const dsurf::TriangleMesh& m, Dist dist)
{
  Accuracy a;
  for (const auto& p : m.Points)
  {
    const double d = dist(p);
    a.Mean += d;
    a.Max = std::max(a.Max, d);
  }
  a.Mean /= std::max<size_t>(1, m.Points.size());
  return a;
}

/// Surface accuracy, weighted by area: each triangle sampled at its centroid and edge
/// midpoints. Unlike the vertex mean it does not favour meshes that put many vertices
/// where the error is small (or penalise adaptive ones that put them where it is large).
template <typename Dist>
Accuracy MeasureArea(const dsurf::TriangleMesh& m, Dist dist)
{
  Accuracy a;
  double area = 0;
  for (const auto& t : m.Triangles)
  {
    const Vec3 &p0 = m.Points[t[0]], &p1 = m.Points[t[1]], &p2 = m.Points[t[2]];
    const double ta = 0.5 * Norm(Cross(p1 - p0, p2 - p0));
    const Vec3 samples[4] = { (1.0 / 3.0) * (p0 + p1 + p2), 0.5 * (p0 + p1), 0.5 * (p1 + p2),
      0.5 * (p2 + p0) };
    for (const auto& s : samples)
    {
      const double d = dist(s);
      a.Mean += 0.25 * ta * d;
      a.Max = std::max(a.Max, d);
    }
    area += ta;
  }
  a.Mean /= area > 0 ? area : 1.0;
  return a;
}

/// Fraction of triangles whose smallest angle is at least `degrees`.
inline double FractionMinAngleAtLeast(const dsurf::TriangleMesh& m, double degrees)
{
  int ok = 0;
  for (int t = 0; t < m.NumberOfTriangles(); ++t)
    ok += m.MinAngleDegrees(t) >= degrees ? 1 : 0;
  return m.NumberOfTriangles() ? double(ok) / m.NumberOfTriangles() : 0.0;
}
} // namespace dsphantom

#endif
