// SPDX-License-Identifier: BSD-3-Clause
#include "dsSelfIntersectionCount.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace dsurf
{
namespace
{
/// Signed distances (times |n|) of the three points to the plane through p0 with normal n;
/// values within eps of zero are snapped to zero (touching = intersecting).
inline void PlaneDistances(const Vec3& n, const Vec3& p0, const Vec3& x0, const Vec3& x1,
  const Vec3& x2, double eps, double d[3])
{
  const double off = Dot(n, p0);
  d[0] = Dot(n, x0) - off;
  d[1] = Dot(n, x1) - off;
  d[2] = Dot(n, x2) - off;
  for (int i = 0; i < 3; ++i)
  {
    if (std::abs(d[i]) <= eps)
    {
      d[i] = 0;
    }
  }
}

/// Interval where the triangle with projections p[] and plane distances d[] crosses the
/// intersection line. False when the configuration is coplanar (all d zero).
inline bool Interval(const double p[3], const double d[3], double& lo, double& hi)
{
  int iso;
  if (d[0] * d[1] > 0)
  {
    iso = 2;
  }
  else if (d[0] * d[2] > 0)
  {
    iso = 1;
  }
  else if (d[1] * d[2] > 0 || d[0] != 0)
  {
    iso = 0;
  }
  else if (d[1] != 0)
  {
    iso = 1;
  }
  else if (d[2] != 0)
  {
    iso = 2;
  }
  else
  {
    return false;
  }
  const int j = (iso + 1) % 3, k = (iso + 2) % 3;
  const double tj =
    (d[iso] - d[j]) != 0 ? p[iso] + (p[j] - p[iso]) * d[iso] / (d[iso] - d[j]) : p[j];
  const double tk =
    (d[iso] - d[k]) != 0 ? p[iso] + (p[k] - p[iso]) * d[iso] / (d[iso] - d[k]) : p[k];
  lo = std::min(tj, tk);
  hi = std::max(tj, tk);
  return true;
}

inline double Orient2D(const double a[2], const double b[2], const double c[2])
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

inline bool SegmentsIntersect2D(
  const double a[2], const double b[2], const double c[2], const double d[2])
{
  const double o1 = Orient2D(a, b, c), o2 = Orient2D(a, b, d);
  const double o3 = Orient2D(c, d, a), o4 = Orient2D(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
  {
    return true;
  }
  auto onSegment = [](const double p[2], const double q[2], const double r[2])
  {
    return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) &&
      std::min(p[1], q[1]) <= r[1] && r[1] <= std::max(p[1], q[1]);
  };
  return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) ||
    (o3 == 0 && onSegment(c, d, a)) || (o4 == 0 && onSegment(c, d, b));
}

inline bool PointInTriangle2D(const double p[2], const double t[3][2])
{
  const double o0 = Orient2D(t[0], t[1], p), o1 = Orient2D(t[1], t[2], p),
               o2 = Orient2D(t[2], t[0], p);
  return (o0 >= 0 && o1 >= 0 && o2 >= 0) || (o0 <= 0 && o1 <= 0 && o2 <= 0);
}

bool CoplanarIntersect(const Vec3& n, const Vec3* a, const Vec3* b)
{
  // Drop the dominant axis of the normal.
  int drop = 0;
  if (std::abs(n[1]) > std::abs(n[drop]))
  {
    drop = 1;
  }
  if (std::abs(n[2]) > std::abs(n[drop]))
  {
    drop = 2;
  }
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  double pa[3][2], pb[3][2];
  for (int i = 0; i < 3; ++i)
  {
    pa[i][0] = a[i][u];
    pa[i][1] = a[i][v];
    pb[i][0] = b[i][u];
    pb[i][1] = b[i][v];
  }
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      if (SegmentsIntersect2D(pa[i], pa[(i + 1) % 3], pb[j], pb[(j + 1) % 3]))
      {
        return true;
      }
    }
  }
  return PointInTriangle2D(pa[0], pb) || PointInTriangle2D(pb[0], pa);
}

inline double Tolerance(const Vec3& n, const Vec3& x0, const Vec3& x1, const Vec3& x2)
{
  const double scale = std::max({ Norm(x1 - x0), Norm(x2 - x0), Norm(x2 - x1) });
  return 1e-12 * Norm(n) * scale;
}

/// Planes whose angle has a sine below this are treated as one plane and the pair is decided
/// in 2-D. Along the planes' common line, d / sin is the error of where the line lies for a
/// plane-distance error d: at sine 1e-12 (a vertex of a flat patch moved by 1e-12 of an edge
/// out of the patch's plane, as Gauss-Seidel sweeps do near a crease) the 3-D test put that line
/// anywhere and found overlaps between neighbours that only share a vertex. Two triangles that
/// meet and lie within 1e-6 of each other's plane (relative to their size) overlap as their
/// projections do, up to touching.
constexpr double CoplanarSine = 1e-6;

inline bool NearlyParallel(const Vec3& nA, const Vec3& nB, const Vec3& dir)
{
  return Norm(dir) <= CoplanarSine * Norm(nA) * Norm(nB);
}

/// Cross product of the 2-D vectors (a, b) after dropping coordinate `drop`.
inline double Cross2D(const Vec3& a, const Vec3& b, int drop)
{
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  return a[u] * b[v] - a[v] * b[u];
}

/// Whether direction d lies strictly inside the wedge (e1, e2) (both non-parallel) in 2-D.
inline bool InWedge2D(const Vec3& d, const Vec3& e1, const Vec3& e2, int drop)
{
  const double turn = Cross2D(e1, e2, drop);
  return Cross2D(e1, d, drop) * turn > 0 && Cross2D(d, e2, drop) * turn > 0;
}

/// The wedges at s of two (nearly) coplanar triangles (s, a1, a2) and (s, b1, b2), projected
/// along the dominant axis of the normal n: they overlap beyond s when a direction lies strictly
/// inside both (an edge of one inside the other, or, for equal wedges, the bisector).
bool CoplanarWedgesOverlap(
  const Vec3& n, const Vec3& s, const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2)
{
  int drop = 0;
  for (int k = 1; k < 3; ++k)
  {
    drop = std::abs(n[k]) > std::abs(n[drop]) ? k : drop;
  }
  const Vec3 ea1 = a1 - s, ea2 = a2 - s, eb1 = b1 - s, eb2 = b2 - s;
  if (Cross2D(ea1, ea2, drop) == 0 || Cross2D(eb1, eb2, drop) == 0)
  {
    return false; // degenerate in the projection
  }
  const Vec3 bisA = (1.0 / Norm(ea1)) * ea1 + (1.0 / Norm(ea2)) * ea2;
  const Vec3 bisB = (1.0 / Norm(eb1)) * eb1 + (1.0 / Norm(eb2)) * eb2;
  return InWedge2D(eb1, ea1, ea2, drop) || InWedge2D(eb2, ea1, ea2, drop) ||
    InWedge2D(ea1, eb1, eb2, drop) || InWedge2D(ea2, eb1, eb2, drop) ||
    InWedge2D(bisA, eb1, eb2, drop) || InWedge2D(bisB, ea1, ea2, drop);
}
} // namespace

bool TrianglesIntersect(
  const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2)
{
  const Vec3 nB = Cross(b1 - b0, b2 - b0);
  double da[3];
  PlaneDistances(nB, b0, a0, a1, a2, Tolerance(nB, b0, b1, b2), da);
  if ((da[0] > 0 && da[1] > 0 && da[2] > 0) || (da[0] < 0 && da[1] < 0 && da[2] < 0))
  {
    return false;
  }
  const Vec3 nA = Cross(a1 - a0, a2 - a0);
  double db[3];
  PlaneDistances(nA, a0, b0, b1, b2, Tolerance(nA, a0, a1, a2), db);
  if ((db[0] > 0 && db[1] > 0 && db[2] > 0) || (db[0] < 0 && db[1] < 0 && db[2] < 0))
  {
    return false;
  }
  const Vec3 a[3] = { a0, a1, a2 }, b[3] = { b0, b1, b2 };
  const Vec3 dir = Cross(nA, nB);
  if (NearlyParallel(nA, nB, dir))
  {
    return CoplanarIntersect(Norm(nA) > 0 ? nA : nB, a, b);
  }
  // Project onto the dominant axis of the intersection line (same order as the line).
  int axis = 0;
  if (std::abs(dir[1]) > std::abs(dir[axis]))
  {
    axis = 1;
  }
  if (std::abs(dir[2]) > std::abs(dir[axis]))
  {
    axis = 2;
  }
  const double pa[3] = { a0[axis], a1[axis], a2[axis] };
  const double pb[3] = { b0[axis], b1[axis], b2[axis] };
  double aLo, aHi, bLo, bHi;
  const bool okA = Interval(pa, da, aLo, aHi);
  const bool okB = Interval(pb, db, bLo, bHi);
  if (!okA || !okB)
  {
    return CoplanarIntersect(Norm(nA) > 0 ? nA : nB, a, b);
  }
  return !(aHi < bLo || bHi < aLo);
}

bool SharedVertexTrianglesOverlap(
  const Vec3& s, const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2)
{
  // The planes meet in a line through s; each triangle covers a segment of it that
  // starts at s (or only s). They overlap beyond s when both segments leave s on the
  // same side.
  const Vec3 nA = Cross(a1 - s, a2 - s), nB = Cross(b1 - s, b2 - s);
  const Vec3 dir = Cross(nA, nB);
  const double lenA = Norm(nA), lenB = Norm(nB);
  if (lenA == 0 || lenB == 0)
  {
    return false; // degenerate
  }
  if (NearlyParallel(nA, nB, dir))
  {
    return CoplanarWedgesOverlap(nA, s, a1, a2, b1, b2);
  }
  // Side of the crossing of the far edge (x1,x2) of one triangle with the other's plane.
  auto side = [&](const Vec3& n, const Vec3& x1, const Vec3& x2, double eps)
  {
    double d1 = Dot(n, x1 - s), d2 = Dot(n, x2 - s);
    if (std::abs(d1) <= eps)
    {
      d1 = 0;
    }
    if (std::abs(d2) <= eps)
    {
      d2 = 0;
    }
    if ((d1 > 0 && d2 > 0) || (d1 < 0 && d2 < 0) || (d1 == 0 && d2 == 0))
    {
      return 0; // touches the plane only at s (or lies in it: coplanar edge, ignored)
    }
    const double t = d1 / (d1 - d2);
    const Vec3 x = x1 + t * (x2 - x1);
    const double along = Dot(x - s, dir);
    return along > 0 ? 1 : (along < 0 ? -1 : 0);
  };
  const int sa = side(nB, a1, a2, Tolerance(nB, s, b1, b2));
  const int sb = side(nA, b1, b2, Tolerance(nA, s, a1, a2));
  return sa != 0 && sa == sb;
}

namespace
{
/// Axis-aligned box of a triangle or of a BVH node: lo[0..2], hi[3..5].
using Box = std::array<double, 6>;

inline bool Overlap(const Box& a, const Box& b)
{
  return !(a[3] < b[0] || b[3] < a[0] || a[4] < b[1] || b[4] < a[1] || a[5] < b[2] || b[5] < a[2]);
}

/// Bounding-volume hierarchy over triangle boxes, split at the median centroid of the
/// widest axis. Unlike a uniform grid its size does not depend on how the triangle
/// sizes are mixed: n triangles give < 2n/LeafSize nodes whatever their extent.
class TriangleBVH
{
public:
  static constexpr int LeafSize = 8;
  struct Node
  {
    Box Bounds;
    int First = 0, Count = 0; ///< range of Order / Boxes (leaves only)
    int Left = -1, Right = -1;
    bool IsLeaf() const { return this->Left < 0; }
  };

  TriangleBVH(const std::vector<Box>& triBoxes)
  {
    const int n = static_cast<int>(triBoxes.size());
    // Centres and ids together, so the median splits move contiguous data.
    std::vector<Item> items(n);
    for (int t = 0; t < n; ++t)
    {
      const Box& b = triBoxes[t];
      items[t] = { { 0.5 * (b[0] + b[3]), 0.5 * (b[1] + b[4]), 0.5 * (b[2] + b[5]) }, t };
    }
    this->Nodes.reserve(2 * (n / LeafSize + 1));
    this->Build(items, 0, n);
    this->Order.resize(n);
    this->Boxes.resize(n);
    for (int k = 0; k < n; ++k)
    {
      this->Order[k] = items[k].Id;
      this->Boxes[k] = triBoxes[items[k].Id];
    }
    this->Fit(0);
  }

  std::vector<Node> Nodes; ///< Nodes[0] is the root
  std::vector<int> Order;  ///< triangle ids in leaf order
  std::vector<Box> Boxes;  ///< their boxes, same order

private:
  struct Item
  {
    double Center[3];
    int Id;
  };

  int Build(std::vector<Item>& items, int begin, int end)
  {
    const int id = static_cast<int>(this->Nodes.size());
    this->Nodes.emplace_back();
    if (end - begin <= LeafSize)
    {
      this->Nodes[id].First = begin;
      this->Nodes[id].Count = end - begin;
      return id;
    }
    double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
    for (int k = begin; k < end; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], items[k].Center[a]);
        hi[a] = std::max(hi[a], items[k].Center[a]);
      }
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      if (hi[a] - lo[a] > hi[axis] - lo[axis])
      {
        axis = a;
      }
    }
    // The median by position keeps the depth at log2(n / LeafSize) even when all
    // centres coincide.
    const int mid = begin + (end - begin) / 2;
    std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
      [axis](const Item& x, const Item& y) { return x.Center[axis] < y.Center[axis]; });
    const int left = this->Build(items, begin, mid);
    const int right = this->Build(items, mid, end);
    this->Nodes[id].Left = left;
    this->Nodes[id].Right = right;
    return id;
  }

  /// Bounds bottom-up: leaves from their triangles, inner nodes from their children.
  const Box& Fit(int id)
  {
    Node& nd = this->Nodes[id];
    Box bounds = { 1e300, 1e300, 1e300, -1e300, -1e300, -1e300 };
    auto grow = [&bounds](const Box& b)
    {
      for (int a = 0; a < 3; ++a)
      {
        bounds[a] = std::min(bounds[a], b[a]);
        bounds[a + 3] = std::max(bounds[a + 3], b[a + 3]);
      }
    };
    if (nd.IsLeaf())
    {
      for (int k = nd.First; k < nd.First + nd.Count; ++k)
      {
        grow(this->Boxes[k]);
      }
    }
    else
    {
      const int left = nd.Left, right = nd.Right;
      grow(this->Fit(left));
      grow(this->Fit(right));
    }
    this->Nodes[id].Bounds = bounds;
    return this->Nodes[id].Bounds;
  }
};

/// Visits every pair of triangles whose boxes overlap exactly once (Test(t1, t2)):
/// pairs inside a node are those inside each child plus those across the children,
/// and a cross pair of nodes is descended only while the nodes' boxes overlap.
template <typename PairTest>
class SelfTraversal
{
public:
  SelfTraversal(const TriangleBVH& bvh, PairTest& test)
    : Bvh(bvh)
    , Test(test)
  {
  }

  void Self(int node)
  {
    const auto& nd = this->Bvh.Nodes[node];
    if (nd.IsLeaf())
    {
      for (int x = nd.First; x < nd.First + nd.Count; ++x)
      {
        for (int y = x + 1; y < nd.First + nd.Count; ++y)
        {
          if (Overlap(this->Bvh.Boxes[x], this->Bvh.Boxes[y]))
          {
            this->Test(this->Bvh.Order[x], this->Bvh.Order[y]);
          }
        }
      }
      return;
    }
    this->Self(nd.Left);
    this->Self(nd.Right);
    this->Cross(nd.Left, nd.Right);
  }

  void Cross(int a, int b)
  {
    const auto &na = this->Bvh.Nodes[a], &nb = this->Bvh.Nodes[b];
    if (!Overlap(na.Bounds, nb.Bounds))
    {
      return;
    }
    if (na.IsLeaf() && nb.IsLeaf())
    {
      for (int x = na.First; x < na.First + na.Count; ++x)
      {
        // A big triangle makes its leaf's box big: check each box against the other
        // leaf first so its small neighbours in the leaf stay cheap.
        const Box& bx = this->Bvh.Boxes[x];
        if (!Overlap(bx, nb.Bounds))
        {
          continue;
        }
        for (int y = nb.First; y < nb.First + nb.Count; ++y)
        {
          if (Overlap(bx, this->Bvh.Boxes[y]))
          {
            this->Test(this->Bvh.Order[x], this->Bvh.Order[y]);
          }
        }
      }
      return;
    }
    // Descend the larger node (a leaf cannot be split).
    if (nb.IsLeaf() || (!na.IsLeaf() && Size(na.Bounds) >= Size(nb.Bounds)))
    {
      this->Cross(na.Left, b);
      this->Cross(na.Right, b);
    }
    else
    {
      this->Cross(a, nb.Left);
      this->Cross(a, nb.Right);
    }
  }

private:
  static double Size(const Box& b) { return (b[3] - b[0]) + (b[4] - b[1]) + (b[5] - b[2]); }

  const TriangleBVH& Bvh;
  PairTest& Test;
};
} // namespace

int CountSelfIntersections(const TriangleMesh& mesh, std::vector<std::pair<int, int>>* pairs)
{
  const int nTri = mesh.NumberOfTriangles();
  if (pairs)
  {
    pairs->clear();
  }
  if (nTri < 2)
  {
    return 0;
  }
  const auto& P = mesh.Points;
  std::vector<Box> boxes(nTri);
  for (int t = 0; t < nTri; ++t)
  {
    auto& b = boxes[t];
    const auto& tri = mesh.Triangles[t];
    for (int a = 0; a < 3; ++a)
    {
      b[a] = std::min({ P[tri[0]][a], P[tri[1]][a], P[tri[2]][a] });
      b[a + 3] = std::max({ P[tri[0]][a], P[tri[1]][a], P[tri[2]][a] });
    }
  }
  // A BVH rather than a uniform grid: a grid sized for the typical triangle puts one
  // huge triangle into (size/cell)^3 cells, and a grid sized for the extent puts a
  // small dense part into one cell; the BVH is O(n) memory and near O(n log n) time for
  // any mix of sizes (more only when many boxes really overlap).
  const TriangleBVH bvh(boxes);

  int count = 0;
  auto test = [&](int t1, int t2)
  {
    const auto &A = mesh.Triangles[t1], &B = mesh.Triangles[t2];
    int shared = 0, sa = -1, sb = -1;
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        if (A[i] == B[j])
        {
          ++shared;
          sa = i;
          sb = j;
        }
      }
    }
    bool hit = false;
    if (shared == 0)
    {
      hit = TrianglesIntersect(P[A[0]], P[A[1]], P[A[2]], P[B[0]], P[B[1]], P[B[2]]);
    }
    else if (shared == 1)
    {
      hit = SharedVertexTrianglesOverlap(
        P[A[sa]], P[A[(sa + 1) % 3]], P[A[(sa + 2) % 3]], P[B[(sb + 1) % 3]], P[B[(sb + 2) % 3]]);
    }
    if (hit)
    {
      ++count;
      if (pairs)
      {
        pairs->emplace_back(std::min(t1, t2), std::max(t1, t2));
      }
    }
  };
  SelfTraversal<decltype(test)> traversal(bvh, test);
  traversal.Self(0);
  if (pairs)
  {
    std::sort(pairs->begin(), pairs->end());
  }
  return count;
}
} // namespace dsurf
