// SPDX-License-Identifier: BSD-3-Clause
#include "dsContact.h"

#include "dsSelfIntersectionCount.h"
#include "dsTriangleDistance.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace dsurf
{
namespace
{
/// Facing: two triangles whose normals point alike face each other when the chord between their
/// centres leaves one of them at more than 30 degrees.
constexpr double FacingChordSine = 0.5;

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
  return mesh.Objects.empty() ? 0 : mesh.Objects[mesh.Triangles[t][0]];
}

Vec3 TriangleNormal(const std::vector<Vec3>& points, const std::array<int, 3>& c)
{
  return Cross(points[c[1]] - points[c[0]], points[c[2]] - points[c[0]]);
}

bool ShareCorner(const std::array<int, 3>& a, const std::array<int, 3>& b)
{
  for (int x : a)
  {
    if (x == b[0] || x == b[1] || x == b[2])
    {
      return true;
    }
  }
  return false;
}

/// Whether two triangles of one object (normals na, nb, unnormalised) are parts of the surface
/// that face each other (a fold in the making: the two sides of a gap the surface grows
/// around), not neighbours on one sheet. Neighbours on one smooth sheet point alike and lie
/// along it: the chord between their centres is nearly tangent to both. Two parts of a surface
/// that do not cross it face each other (the space between them lies outside both, or inside
/// both), so their normals point against each other, or, where two sheets meet at an angle
/// (the rims of two balls of one surface pressed together), the chord runs across at least one
/// of them (TestContactBounds). Triangles two edges apart count too: where a crease closes they
/// are the two sides that meet (left out, a Colin27 click kept 21 crossing pairs at the level
/// of its fold, and 231 at the end once refinement had split them). Two triangles sharing a
/// corner always touch, so no plane lies between them: §5's rule keeps them apart
/// (dsSelfIntersectionRule.h).
bool Facing(const std::vector<Vec3>& points, const std::array<int, 3>& a,
  const std::array<int, 3>& b, const Vec3& na, const Vec3& nb)
{
  if (ShareCorner(a, b))
  {
    return false;
  }
  if (Dot(na, nb) < 0)
  {
    return true;
  }
  const Vec3 chord = (points[b[0]] + points[b[1]] + points[b[2]]) -
    (points[a[0]] + points[a[1]] + points[a[2]]); // three times the centres' difference
  const double across =
    std::max(std::abs(Dot(chord, na)) / Norm(na), std::abs(Dot(chord, nb)) / Norm(nb));
  return across >= FacingChordSine * Norm(chord);
}

/// The pairs of triangles of different objects (and with `self`, of one object facing each
/// other: Facing) whose boxes, each grown by `grow`, overlap (a uniform grid of cells about the
/// size of the grown boxes; each pair is reported by the one cell holding the low corner of the
/// two boxes' overlap). Sorted.
std::vector<std::pair<int, int>> NearPairs(
  const TriangleMesh& mesh, const std::vector<Vec3>& points, double grow, bool self)
{
  const int n = mesh.NumberOfTriangles();
  std::vector<Box> boxes(n);
  std::vector<Vec3> normals(self ? n : 0);
  double size = 0;
  for (int t = 0; t < n; ++t)
  {
    if (self)
    {
      normals[t] = TriangleNormal(points, mesh.Triangles[t]);
    }
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
  // (cell, triangle) entries sorted by cell: the triangles of a cell are one run (a hash map of
  // vectors cost more than the pairs themselves).
  std::vector<std::pair<long long, int>> entries;
  entries.reserve(static_cast<std::size_t>(n) * 8);
  for (int t = 0; t < n; ++t)
  {
    const Box& b = boxes[t];
    for (long long i = index(b[0]); i <= index(b[3]); ++i)
      for (long long j = index(b[1]); j <= index(b[4]); ++j)
        for (long long k = index(b[2]); k <= index(b[5]); ++k)
          entries.emplace_back(key(i, j, k), t);
  }
  std::sort(entries.begin(), entries.end());
  std::vector<std::size_t> runs;
  for (std::size_t e = 0; e < entries.size(); ++e)
  {
    if (e == 0 || entries[e].first != entries[e - 1].first)
    {
      runs.push_back(e);
    }
  }
  runs.push_back(entries.size());
  // The runs in parallel, each into its own list; sorted together after, so the result does not
  // depend on the threads.
  vtkSMPThreadLocal<std::vector<std::pair<int, int>>> found;
  vtkSMPTools::For(0, static_cast<vtkIdType>(runs.size() - 1),
    [&](vtkIdType first, vtkIdType last)
    {
      std::vector<std::pair<int, int>>& local = found.Local();
      for (vtkIdType r = first; r < last; ++r)
      {
        const long long cellKey = entries[runs[r]].first;
        for (std::size_t x = runs[r]; x < runs[r + 1]; ++x)
        {
          for (std::size_t y = x + 1; y < runs[r + 1]; ++y)
          {
            const int s = entries[x].second, t = entries[y].second;
            if (!Overlap(boxes[s], boxes[t]) ||
              (TriangleObject(mesh, s) == TriangleObject(mesh, t) &&
                !(self &&
                  Facing(points, mesh.Triangles[s], mesh.Triangles[t], normals[s], normals[t]))))
            {
              continue;
            }
            const double lo[3] = { std::max(boxes[s][0], boxes[t][0]),
              std::max(boxes[s][1], boxes[t][1]), std::max(boxes[s][2], boxes[t][2]) };
            if (key(index(lo[0]), index(lo[1]), index(lo[2])) == cellKey)
            {
              local.emplace_back(std::min(s, t), std::max(s, t));
            }
          }
        }
      }
    });
  std::vector<std::pair<int, int>> pairs;
  for (const auto& local : found)
  {
    pairs.insert(pairs.end(), local.begin(), local.end());
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}
} // namespace

void ContactLimiter::Build(const TriangleMesh& mesh, double reach)
{
  this->Anchor = mesh.Points;
  this->Candidates = NearPairs(mesh, mesh.Points, 0.5 * reach, this->Self);
  ++this->BuildCount;
}

double ContactStepScale(const ContactBounds& bounds, int v, const Vec3& point, const Vec3& step)
{
  double scale = 1.0;
  // The ball: the larger root of |q + s step| = r, q inside it.
  const Vec3 q = point - bounds.Anchors[v];
  const double r2 = bounds.Radii[v] * bounds.Radii[v];
  const Vec3 end = q + step;
  if (Dot(end, end) > r2)
  {
    const double a = Dot(step, step), b = 2 * Dot(q, step), c = Dot(q, q) - r2;
    scale = c >= 0 ? 0.0 : (-b + std::sqrt(std::max(0.0, b * b - 4 * a * c))) / (2 * a);
  }
  for (int e = bounds.Offsets[v]; e < bounds.Offsets[v + 1]; ++e)
  {
    const double along = Dot(step, bounds.Normals[e]);
    const double room = std::max(0.0, bounds.Limits[e] - Dot(point, bounds.Normals[e]));
    if (along > room)
    {
      scale = std::min(scale, room / along);
    }
  }
  return std::max(0.0, std::min(1.0, scale));
}

void ContactLimiter::Limits(
  const TriangleMesh& mesh, double clearance, double budget, bool self, ContactBounds& bounds)
{
  const int n = mesh.NumberOfPoints();
  const std::vector<Vec3>& p = mesh.Points;
  double travelled = 0;
  const bool sameMesh = this->Anchor.size() == static_cast<std::size_t>(n) &&
    clearance == this->Clearance && budget == this->Budget && self == this->Self;
  for (int v = 0; v < n && sameMesh; ++v)
  {
    travelled = std::max(travelled, Norm(p[v] - this->Anchor[v]));
  }
  if (!sameMesh || travelled > 0.5 * budget)
  {
    this->Clearance = clearance;
    this->Budget = budget;
    this->Self = self;
    this->Build(mesh, clearance + 2 * budget);
  }
  this->Measure(mesh, clearance + 2 * budget);
  bounds.Anchors = this->Anchor;
  bounds.Radii.assign(n, budget);
  // Per candidate and corner, the half-space that keeps the corner on its side of the pair's
  // midway plane (dsContact.h), where it may bind within the corner's ball; in candidate order,
  // then grouped by vertex (a stable counting sort), so that the bounds do not depend on threads.
  struct Plane
  {
    int Vertex;
    Vec3 Normal;
    double Limit;
  };
  std::vector<Plane> planes;
  for (std::size_t i = 0; i < this->Candidates.size(); ++i)
  {
    const auto& a = mesh.Triangles[this->Candidates[i].first];
    const auto& b = mesh.Triangles[this->Candidates[i].second];
    const Vec3& d = this->Directions[i];
    if (!(Norm(d) > 0))
    {
      // Intersecting: a fold of one object already there (a refinement's) is left to the
      // smoothing (dsUntangle.h); two objects stay where they are.
      if (TriangleObject(mesh, this->Candidates[i].first) !=
        TriangleObject(mesh, this->Candidates[i].second))
      {
        for (int k = 0; k < 3; ++k)
        {
          bounds.Anchors[a[k]] = p[a[k]];
          bounds.Radii[a[k]] = 0.0;
          bounds.Anchors[b[k]] = p[b[k]];
          bounds.Radii[b[k]] = 0.0;
        }
      }
      continue;
    }
    double reachA = -std::numeric_limits<double>::infinity();
    double reachB = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k)
    {
      reachA = std::max(reachA, Dot(p[a[k]], d));
      reachB = std::min(reachB, Dot(p[b[k]], d));
    }
    const double middle = 0.5 * (reachA + reachB);
    for (int k = 0; k < 3; ++k)
    {
      // A corner already past its side's plane (two triangles nearer than the clearance) keeps
      // where it is along d.
      const double alongA = Dot(p[a[k]], d);
      const double limitA = std::max(middle - 0.5 * clearance, alongA);
      if (limitA - alongA < budget)
      {
        planes.push_back({ a[k], d, limitA });
      }
      const double alongB = Dot(p[b[k]], d);
      const double limitB = std::min(middle + 0.5 * clearance, alongB);
      if (alongB - limitB < budget)
      {
        planes.push_back({ b[k], -1.0 * d, -limitB });
      }
    }
  }
  std::vector<int>& count = this->PlaneCount;
  count.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const Plane& plane : planes)
  {
    ++count[plane.Vertex + 1];
  }
  for (int v = 0; v < n; ++v)
  {
    count[v + 1] += count[v];
  }
  bounds.Offsets = count;
  bounds.Normals.resize(planes.size());
  bounds.Limits.resize(planes.size());
  std::vector<int> next(count.begin(), count.end() - 1);
  for (const Plane& plane : planes)
  {
    const int e = next[plane.Vertex]++;
    bounds.Normals[e] = plane.Normal;
    bounds.Limits[e] = plane.Limit;
  }
}

void ContactLimiter::Measure(const TriangleMesh& mesh, double far)
{
  // In parallel: each pair's direction is its own (the bounds are made in order after).
  const std::vector<Vec3>& p = mesh.Points;
  this->Directions.resize(this->Candidates.size());
  vtkSMPTools::For(0, static_cast<vtkIdType>(this->Candidates.size()),
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType i = first; i < last; ++i)
      {
        const auto& a = mesh.Triangles[this->Candidates[i].first];
        const auto& b = mesh.Triangles[this->Candidates[i].second];
        const Box ba = TriangleBox(mesh, p, this->Candidates[i].first, 0.0);
        const Box bb = TriangleBox(mesh, p, this->Candidates[i].second, 0.0);
        // Boxes `far` apart along an axis: that axis separates the two triangles too, and its
        // plane lies beyond their balls (Limits adds no bound), so the nearest points are not
        // needed.
        double widest = 0;
        int axis = -1;
        double sign = 1;
        for (int x = 0; x < 3; ++x)
        {
          const double ahead = bb[x] - ba[x + 3], behind = ba[x] - bb[x + 3];
          const double g = std::max({ 0.0, ahead, behind });
          if (g > widest)
          {
            widest = g;
            axis = x;
            sign = ahead > 0 ? 1.0 : -1.0;
          }
        }
        if (widest >= far)
        {
          Vec3 d{ 0, 0, 0 };
          d[axis] = sign;
          this->Directions[i] = d;
          continue;
        }
        const Vec3 d = TriangleSeparation(p[a[0]], p[a[1]], p[a[2]], p[b[0]], p[b[1]], p[b[2]]);
        const double g = Norm(d);
        this->Directions[i] = g > 0 ? (1.0 / g) * d : Vec3{ 0, 0, 0 };
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
