// SPDX-License-Identifier: BSD-3-Clause
#include "dsContact.h"

#include "dsSelfIntersectionCount.h"
#include "dsTriangleDistance.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace dsurf
{
namespace
{
using Box = std::array<double, 6>; // min xyz, max xyz

Box TriangleBox(const TriangleMesh& mesh, const std::vector<Vec3>& points, int t, double grow)
{
  Box b{ std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() };
  for (int c : mesh.Triangles[t])
  {
    for (int a = 0; a < 3; ++a)
    {
      b[a] = std::min(b[a], points[c][a] - grow);
      b[a + 3] = std::max(b[a + 3], points[c][a] + grow);
    }
  }
  return b;
}

bool Overlap(const Box& a, const Box& b)
{
  return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] &&
    b[2] <= a[5];
}

int TriangleObject(const TriangleMesh& mesh, int t)
{
  return mesh.Objects[mesh.Triangles[t][0]];
}

/// The pairs of triangles of different objects whose boxes, each grown by `grow`, overlap
/// (a uniform grid of cells about the size of the grown boxes; each pair is reported by the one
/// cell holding the low corner of the two boxes' overlap). Sorted.
std::vector<std::pair<int, int>> NearPairs(
  const TriangleMesh& mesh, const std::vector<Vec3>& points, double grow)
{
  const int n = mesh.NumberOfTriangles();
  std::vector<Box> boxes(n);
  double size = 0;
  for (int t = 0; t < n; ++t)
  {
    boxes[t] = TriangleBox(mesh, points, t, grow);
    size +=
      std::max({ boxes[t][3] - boxes[t][0], boxes[t][4] - boxes[t][1], boxes[t][5] - boxes[t][2] });
  }
  // Cells of the mean box, but no box over 16 cells wide: a few coarse triangles among many fine
  // ones would otherwise fill thousands of cells each.
  double largest = 0;
  for (const Box& b : boxes)
  {
    largest = std::max({ largest, b[3] - b[0], b[4] - b[1], b[5] - b[2] });
  }
  const double cell = n > 0 ? std::max({ size / n, largest / 16, 1e-12 }) : 1.0;
  auto index = [cell](double x) { return static_cast<long long>(std::floor(x / cell)); };
  auto key = [](long long i, long long j, long long k)
  { return (i & 0x1FFFFF) | ((j & 0x1FFFFF) << 21) | ((k & 0x1FFFFF) << 42); };
  std::unordered_map<long long, std::vector<int>> grid;
  for (int t = 0; t < n; ++t)
  {
    const Box& b = boxes[t];
    for (long long i = index(b[0]); i <= index(b[3]); ++i)
      for (long long j = index(b[1]); j <= index(b[4]); ++j)
        for (long long k = index(b[2]); k <= index(b[5]); ++k)
          grid[key(i, j, k)].push_back(t);
  }
  std::vector<std::pair<int, int>> pairs;
  for (const auto& entry : grid)
  {
    const std::vector<int>& ts = entry.second;
    for (std::size_t x = 0; x < ts.size(); ++x)
    {
      for (std::size_t y = x + 1; y < ts.size(); ++y)
      {
        const int s = ts[x], t = ts[y];
        if (TriangleObject(mesh, s) == TriangleObject(mesh, t) || !Overlap(boxes[s], boxes[t]))
        {
          continue;
        }
        const double lo[3] = { std::max(boxes[s][0], boxes[t][0]),
          std::max(boxes[s][1], boxes[t][1]), std::max(boxes[s][2], boxes[t][2]) };
        if (key(index(lo[0]), index(lo[1]), index(lo[2])) == entry.first)
        {
          pairs.emplace_back(std::min(s, t), std::max(s, t));
        }
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}
} // namespace

void ContactLimiter::Build(const TriangleMesh& mesh, double reach)
{
  this->Anchor = mesh.Points;
  this->Candidates = NearPairs(mesh, mesh.Points, 0.5 * reach);
  this->Measured.clear(); // the new list's distances are measured next
  ++this->BuildCount;
}

void ContactLimiter::Limits(
  const TriangleMesh& mesh, double clearance, double budget, std::vector<double>& limits)
{
  const int n = mesh.NumberOfPoints();
  double travelled = 0;
  const bool sameMesh = this->Anchor.size() == static_cast<std::size_t>(n) &&
    clearance == this->Clearance && budget == this->Budget;
  for (int v = 0; v < n && sameMesh; ++v)
  {
    travelled = std::max(travelled, Norm(mesh.Points[v] - this->Anchor[v]));
  }
  if (!sameMesh || travelled > 0.5 * budget)
  {
    this->Clearance = clearance;
    this->Budget = budget;
    this->Build(mesh, clearance + 2 * budget);
  }
  limits.resize(n);
  double moved = this->Measured.size() == static_cast<std::size_t>(n) ? 0.0 : budget;
  for (int v = 0; v < n; ++v)
  {
    limits[v] = std::max(0.0, budget - Norm(mesh.Points[v] - this->Anchor[v]));
    if (this->Measured.size() == static_cast<std::size_t>(n))
    {
      moved = std::max(moved, Norm(mesh.Points[v] - this->Measured[v]));
    }
  }
  if (this->Measured.empty() || moved > 0.125 * budget)
  {
    this->Measure(mesh, clearance + 2 * budget);
  }
  // Since they were measured, a pair's triangles have closed in by at most their corners'
  // longest moves.
  std::vector<double>& away = this->Moved;
  away.resize(n);
  for (int v = 0; v < n; ++v)
  {
    away[v] = Norm(mesh.Points[v] - this->Measured[v]);
  }
  for (std::size_t i = 0; i < this->Candidates.size(); ++i)
  {
    const auto& a = mesh.Triangles[this->Candidates[i].first];
    const auto& b = mesh.Triangles[this->Candidates[i].second];
    const double g = this->Gaps[i] - std::max({ away[a[0]], away[a[1]], away[a[2]] }) -
      std::max({ away[b[0]], away[b[1]], away[b[2]] });
    const double limit = std::max(0.0, 0.5 * (g - clearance));
    for (int k = 0; k < 3; ++k)
    {
      limits[a[k]] = std::min(limits[a[k]], limit);
      limits[b[k]] = std::min(limits[b[k]], limit);
    }
  }
}

void ContactLimiter::Measure(const TriangleMesh& mesh, double far)
{
  // In parallel: each pair's distance is its own (the limits take their minima in order after).
  // A pair whose boxes lie `far` apart (2 B + c) limits nothing the budget does not already.
  this->Measured = mesh.Points;
  const std::vector<Vec3>& p = mesh.Points;
  this->Gaps.resize(this->Candidates.size());
  vtkSMPTools::For(0, static_cast<vtkIdType>(this->Candidates.size()),
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType i = first; i < last; ++i)
      {
        const auto& a = mesh.Triangles[this->Candidates[i].first];
        const auto& b = mesh.Triangles[this->Candidates[i].second];
        const Box ba = TriangleBox(mesh, p, this->Candidates[i].first, 0.0);
        const Box bb = TriangleBox(mesh, p, this->Candidates[i].second, 0.0);
        double gap2 = 0;
        for (int x = 0; x < 3; ++x)
        {
          const double g = std::max({ 0.0, bb[x] - ba[x + 3], ba[x] - bb[x + 3] });
          gap2 += g * g;
        }
        this->Gaps[i] = gap2 >= far * far
          ? far
          : TriangleDistance(p[a[0]], p[a[1]], p[a[2]], p[b[0]], p[b[1]], p[b[2]]);
      }
    });
}

int CountCrossingPairs(const TriangleMesh& mesh)
{
  if (mesh.Objects.size() != mesh.Points.size())
  {
    return 0;
  }
  std::vector<std::pair<int, int>> pairs;
  CountSelfIntersections(mesh, &pairs);
  int crossing = 0;
  for (const auto& pair : pairs)
  {
    crossing += TriangleObject(mesh, pair.first) != TriangleObject(mesh, pair.second) ? 1 : 0;
  }
  return crossing;
}
} // namespace dsurf
