// SPDX-License-Identifier: BSD-3-Clause
// What the benchmark tables report about an output surface, for any method alike (our filter,
// an iso-surface, ITK's level set through an iso-surface): triangles, connected pieces, the
// distribution of the smallest angle per triangle, and the analytic distance of the vertices to
// the phantom's true boundary (mean and max, in voxels).
#ifndef BenchMeasure_h
#define BenchMeasure_h

#include "vtkCellArray.h"
#include "vtkIdList.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

namespace dsbench
{
using Point = std::array<double, 3>;
/// |distance| of a point (world = voxel coordinates: unit spacing, origin 0) to the boundary.
using DistanceFunction = std::function<double(const Point&)>;

struct SurfaceMeasures
{
  long long Triangles = 0;
  long long Pieces = 0;
  double MinAngle = 0, AngleP5 = 0, AngleMedian = 0; ///< smallest angle per triangle, degrees
  double Below20 = 0;                                ///< fraction of triangles with one < 20 deg
  double MeanDistance = 0, MaxDistance = 0;          ///< over the vertices, voxels
  /// The same over the vertices of the largest piece (an iso-surface of a noisy volume has
  /// many small pieces around noise; this is its main surface).
  double LargestPieceMean = 0, LargestPieceMax = 0;
};

inline double SmallestAngleDegrees(const Point& a, const Point& b, const Point& c)
{
  const Point* p[3] = { &a, &b, &c };
  double smallest = 180;
  for (int k = 0; k < 3; ++k)
  {
    const Point &o = *p[k], &u = *p[(k + 1) % 3], &v = *p[(k + 2) % 3];
    double du[3], dv[3], uu = 0, vv = 0, uv = 0;
    for (int i = 0; i < 3; ++i)
    {
      du[i] = u[i] - o[i];
      dv[i] = v[i] - o[i];
      uu += du[i] * du[i];
      vv += dv[i] * dv[i];
      uv += du[i] * dv[i];
    }
    const double den = std::sqrt(uu * vv);
    const double angle = den > 0 ? std::acos(std::clamp(uv / den, -1.0, 1.0)) * 180 / M_PI : 0.0;
    smallest = std::min(smallest, angle);
  }
  return smallest;
}

/// The connected piece of each point (sharing a point joins two triangles): a representative
/// point id per point, -1 for points no triangle uses.
inline std::vector<vtkIdType> PieceOfPoints(
  vtkIdType points, const std::vector<std::array<vtkIdType, 3>>& tris)
{
  std::vector<vtkIdType> parent(static_cast<size_t>(points));
  std::iota(parent.begin(), parent.end(), vtkIdType(0));
  auto find = [&](vtkIdType x)
  {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& t : tris)
    for (int k = 1; k < 3; ++k)
      parent[find(t[k])] = find(t[0]);
  std::vector<vtkIdType> piece(static_cast<size_t>(points), -1);
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k)
      piece[t[k]] = find(t[k]);
  return piece;
}

inline SurfaceMeasures Measure(vtkPolyData* surface, const DistanceFunction& distance)
{
  SurfaceMeasures m;
  std::vector<std::array<vtkIdType, 3>> tris;
  vtkIdType npts;
  const vtkIdType* ids;
  vtkCellArray* polys = surface->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
    for (vtkIdType k = 1; k + 1 < npts; ++k) // fan: our outputs and iso-surfaces are triangles
      tris.push_back({ ids[0], ids[k], ids[k + 1] });
  const vtkIdType n = surface->GetNumberOfPoints();
  std::vector<Point> p(static_cast<size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
    surface->GetPoint(i, p[i].data());
  m.Triangles = static_cast<long long>(tris.size());
  const std::vector<vtkIdType> piece = PieceOfPoints(n, tris);
  std::vector<vtkIdType> pieceSize(static_cast<size_t>(n), 0);
  for (vtkIdType i = 0; i < n; ++i)
    if (piece[i] >= 0)
      m.Pieces += pieceSize[piece[i]]++ == 0 ? 1 : 0;
  const vtkIdType largest = n > 0
    ? static_cast<vtkIdType>(
        std::max_element(pieceSize.begin(), pieceSize.end()) - pieceSize.begin())
    : -1;
  std::vector<double> angles;
  angles.reserve(tris.size());
  for (const auto& t : tris)
    angles.push_back(SmallestAngleDegrees(p[t[0]], p[t[1]], p[t[2]]));
  if (!angles.empty())
  {
    std::sort(angles.begin(), angles.end());
    m.MinAngle = angles.front();
    m.AngleP5 = angles[angles.size() / 20];
    m.AngleMedian = angles[angles.size() / 2];
    m.Below20 = double(std::lower_bound(angles.begin(), angles.end(), 20.0) - angles.begin()) /
      double(angles.size());
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double d = distance(p[i]);
    m.MeanDistance += d;
    m.MaxDistance = std::max(m.MaxDistance, d);
    if (piece[i] == largest)
    {
      m.LargestPieceMean += d;
      m.LargestPieceMax = std::max(m.LargestPieceMax, d);
    }
  }
  m.MeanDistance /= std::max<double>(1.0, double(n));
  m.LargestPieceMean /= std::max<double>(1.0, largest >= 0 ? double(pieceSize[largest]) : 0.0);
  return m;
}

/// The table cells of a measured surface: triangles | pieces | min/p5/median angle | < 20 deg
/// | mean d | max d; with several pieces, the largest piece's mean and max in `notes`.
inline std::string MeasureCells(const SurfaceMeasures& m, std::string* notes = nullptr)
{
  char buf[256];
  std::snprintf(buf, sizeof buf, "%lld | %lld | %.1f / %.1f / %.1f | %.1f%% | %.3f | %.3f",
    m.Triangles, m.Pieces, m.MinAngle, m.AngleP5, m.AngleMedian, 100 * m.Below20, m.MeanDistance,
    m.MaxDistance);
  if (notes && m.Pieces > 1)
  {
    char piece[96];
    std::snprintf(piece, sizeof piece, "largest piece: mean %.3f, max %.3f; ", m.LargestPieceMean,
      m.LargestPieceMax);
    *notes = piece;
  }
  return buf;
}

} // namespace dsbench

#endif
