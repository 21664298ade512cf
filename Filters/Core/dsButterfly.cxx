// SPDX-License-Identifier: BSD-3-Clause
#include "dsButterfly.h"

#include <algorithm>
#include <cmath>

namespace dsurf
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

int Valence(const TriangleMesh& mesh, int v)
{
  return mesh.NeighborOffsets[v + 1] - mesh.NeighborOffsets[v];
}

bool Flagged(const std::vector<char>* flags, int t)
{
  return flags && t >= 0 && t < static_cast<int>(flags->size()) && (*flags)[t];
}

/// The corner of triangle t that is neither p nor q.
int Opposite(const TriangleMesh& mesh, int t, int p, int q)
{
  for (int v : mesh.Triangles[t])
  {
    if (v != p && v != q)
    {
      return v;
    }
  }
  return -1;
}

/// Ring of interior vertex v in cyclic order starting at `start`; empty when the fan is
/// not one closed cycle or touches a flagged triangle.
std::vector<int> CyclicRing(
  const TriangleMesh& mesh, int v, int start, const std::vector<char>* flags)
{
  const int k = Valence(mesh, v);
  std::vector<int> nextFrom, nextTo;
  nextFrom.reserve(k);
  nextTo.reserve(k);
  for (int i = mesh.VertexTriangleOffsets[v]; i < mesh.VertexTriangleOffsets[v + 1]; ++i)
  {
    const int t = mesh.VertexTriangles[i];
    if (Flagged(flags, t))
    {
      return {};
    }
    const auto& tri = mesh.Triangles[t];
    for (int c = 0; c < 3; ++c)
    {
      if (tri[c] == v)
      {
        nextFrom.push_back(tri[(c + 1) % 3]);
        nextTo.push_back(tri[(c + 2) % 3]);
      }
    }
  }
  if (static_cast<int>(nextFrom.size()) != k)
  {
    return {};
  }
  std::vector<int> ring{ start };
  int current = start;
  for (int step = 1; step < k; ++step)
  {
    int next = -1;
    for (int i = 0; i < k; ++i)
    {
      if (nextFrom[i] == current)
      {
        next = nextTo[i];
        break;
      }
    }
    if (next < 0 || next == start)
    {
      return {};
    }
    ring.push_back(next);
    current = next;
  }
  // The cycle must close back at the start.
  for (int i = 0; i < k; ++i)
  {
    if (nextFrom[i] == current)
    {
      return nextTo[i] == start ? ring : std::vector<int>{};
    }
  }
  return {};
}

/// q, a neighbour of v, as a vertex of v's ring at depth `level` (docs/METHOD.md §6.5); -1 when
/// it has no place there. In a red split every vertex deeper than a neighbour is the midpoint
/// of an edge of that neighbour (a corner child), so a deeper q stands for its edge's far end,
/// repeatedly, until it is no deeper than the level. A deeper q whose edge does not end at v is
/// a green's midpoint seen across the green's cut from its opposite corner: the green's
/// parent, in whose ring v lies, has no such vertex.
int AtLevel(const ButterflyHierarchy& h, int v, int q, int level)
{
  const std::vector<int>& depth = *h.Depths;
  while (depth[q] > depth[v])
  {
    const std::array<int, 2>& pe = (*h.ParentEdges)[q];
    const int far = pe[0] == v ? pe[1] : (pe[1] == v ? pe[0] : -1);
    if (far < 0)
    {
      return -1;
    }
    if (depth[q] <= level)
    {
      return q;
    }
    q = far;
  }
  return q;
}

/// The corner o opposite edge (a, b) at `level`, seen from a or, for a green's midpoint whose
/// edge ends at b, from b.
int OppositeAtLevel(const ButterflyHierarchy& h, int a, int b, int o, int level)
{
  const int fromA = AtLevel(h, a, o, level);
  return fromA >= 0 ? fromA : AtLevel(h, b, o, level);
}

/// Whether r may be a neighbour of v in a ring at depth `level`: every edge of that ring joins
/// v to a vertex such that the deeper end is at the level (a shallower one means that side of
/// v is not refined so far), and a midpoint's shallower neighbours are its edge's ends (any
/// other is a green's opposite corner across the green's cut: on that side the green's
/// coarser parent has no vertices of the midpoint's depth).
bool InRingAt(const ButterflyHierarchy& h, int v, int r, int level)
{
  const std::vector<int>& depth = *h.Depths;
  const std::array<int, 2>& pe = (*h.ParentEdges)[v];
  if (depth[r] < depth[v] && r != pe[0] && r != pe[1])
  {
    return false;
  }
  return std::max(depth[v], depth[r]) == level;
}

/// The ring of interior vertex v in cyclic order from `start`, read at depth `level` when the
/// hierarchy is known (AtLevel, InRingAt); empty when it is not one closed cycle of at least
/// three distinct vertices of that level.
std::vector<int> RingAt(const TriangleMesh& mesh, int v, int start, const std::vector<char>* flags,
  const ButterflyHierarchy& h, int level)
{
  std::vector<int> ring = CyclicRing(mesh, v, start, flags);
  if (!h.ParentEdges || ring.empty())
  {
    return ring;
  }
  std::vector<int> atLevel;
  atLevel.reserve(ring.size());
  for (int q : ring)
  {
    const int r = AtLevel(h, v, q, level);
    if (r < 0)
    {
      continue;
    }
    if (!InRingAt(h, v, r, level) || std::find(atLevel.begin(), atLevel.end(), r) != atLevel.end())
    {
      return {};
    }
    atLevel.push_back(r);
  }
  return atLevel.size() >= 3 ? atLevel : std::vector<int>{};
}

void ZorinPoint(const TriangleMesh& mesh, int e, const std::vector<int>& ring, Vec3& out)
{
  const std::vector<double> s = ZorinWeights(static_cast<int>(ring.size()));
  out = 0.75 * mesh.Points[e];
  for (size_t j = 0; j < ring.size(); ++j)
  {
    out = out + s[j] * mesh.Points[ring[j]];
  }
}

/// The far corner of the triangle across edge (v, x) from the triangle (v, x, near): the ring
/// neighbour of v after x on the side away from `near` (ring of valence 6 from the edge's
/// other end); -1 when x is not next to the ring's start.
int Wing(const std::vector<int>& ring, int x)
{
  return ring[1] == x ? ring[2] : (ring[5] == x ? ring[4] : -1);
}

/// The boundary neighbour of a other than b (exactly one, else -1).
int NextBoundaryVertex(const TriangleMesh& mesh, int a, int b)
{
  int found = -1;
  for (int i = mesh.NeighborOffsets[a]; i < mesh.NeighborOffsets[a + 1]; ++i)
  {
    const int x = mesh.Neighbors[i];
    if (x == b)
    {
      continue;
    }
    const int e = mesh.FindEdge(a, x);
    if (e >= 0 && mesh.EdgeTriangles[e][1] == -1)
    {
      if (found >= 0)
      {
        return -1; // branching boundary: the curve is ambiguous
      }
      found = x;
    }
  }
  return found;
}
/// The boundary edge (a, b) of triangle t1 by the 4-point curve scheme; false when the curve
/// does not go on at both ends (at the edge's level) or t1 is flagged.
bool BoundaryPoint(const TriangleMesh& mesh, int a, int b, int t1, const std::vector<char>* flags,
  const ButterflyHierarchy& h, int level, Vec3& out)
{
  int a2 = NextBoundaryVertex(mesh, a, b), b2 = NextBoundaryVertex(mesh, b, a);
  if (h.ParentEdges)
  {
    a2 = a2 < 0 ? -1 : AtLevel(h, a, a2, level);
    b2 = b2 < 0 ? -1 : AtLevel(h, b, b2, level);
  }
  if (a2 < 0 || b2 < 0 || a2 == b2 || Flagged(flags, t1))
  {
    return false;
  }
  out = (9.0 / 16.0) * (mesh.Points[a] + mesh.Points[b]) -
    (1.0 / 16.0) * (mesh.Points[a2] + mesh.Points[b2]);
  return true;
}

/// The 8-point butterfly on edge (a, b) of triangles t1, t2, both ends of valence 6 at the
/// edge's level (ringA from b, ringB from a); false when the rings do not share the corners
/// opposite the edge.
bool RegularPoint(const TriangleMesh& mesh, int a, int b, int t1, int t2,
  const std::vector<int>& ringA, const std::vector<int>& ringB, const ButterflyHierarchy& h,
  int level, Vec3& out)
{
  // b1, b2: the corners opposite the edge (of t1, t2 at the edge's level); the four wings
  // lie across (a, b1), (b, b1), (a, b2), (b, b2).
  int b1 = Opposite(mesh, t1, a, b), b2 = Opposite(mesh, t2, a, b);
  if (h.ParentEdges)
  {
    b1 = OppositeAtLevel(h, a, b, b1, level);
    b2 = OppositeAtLevel(h, a, b, b2, level);
  }
  if (b1 < 0 || b2 < 0 || b1 == b2)
  {
    return false;
  }
  const int wing[4] = { Wing(ringA, b1), Wing(ringB, b1), Wing(ringA, b2), Wing(ringB, b2) };
  if (*std::min_element(wing, wing + 4) < 0)
  {
    return false;
  }
  Vec3 cSum{ 0, 0, 0 };
  for (int c : wing)
  {
    cSum = cSum + mesh.Points[c];
  }
  const double w = 1.0 / 16.0;
  out = 0.5 * (mesh.Points[a] + mesh.Points[b]) + (2.0 * w) * (mesh.Points[b1] + mesh.Points[b2]) -
    w * cSum;
  return true;
}
} // namespace

std::vector<double> ZorinWeights(int k)
{
  std::vector<double> s(k, 0.0);
  if (k == 3)
  {
    s = { 5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0 };
  }
  else if (k == 4)
  {
    s = { 3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0 };
  }
  else if (k >= 5)
  {
    for (int j = 0; j < k; ++j)
    {
      s[j] = (0.25 + std::cos(2.0 * kPi * j / k) + 0.5 * std::cos(4.0 * kPi * j / k)) / k;
    }
  }
  return s;
}

Vec3 ButterflyEdgePoint(const TriangleMesh& mesh, int edge,
  const std::vector<char>* irregularTriangles, ButterflyRule* rule,
  const ButterflyHierarchy& hierarchy)
{
  const int a = mesh.Edges[edge][0], b = mesh.Edges[edge][1];
  const Vec3 mid = 0.5 * (mesh.Points[a] + mesh.Points[b]);
  auto result = [rule](ButterflyRule r, const Vec3& p)
  {
    if (rule)
    {
      *rule = r;
    }
    return p;
  };
  ButterflyHierarchy h = hierarchy;
  if (!h.ParentEdges || !h.Depths || h.ParentEdges->size() != mesh.Points.size() ||
    h.Depths->size() != mesh.Points.size())
  {
    h = ButterflyHierarchy(); // none, or not this mesh's: read the stencils as they are
  }
  // The edge's level: every triangle of depth k has an edge end of depth k on each edge, so an
  // edge belongs to the level of its deeper end, where the rings of both ends are read.
  const int level = h.ParentEdges ? std::max((*h.Depths)[a], (*h.Depths)[b]) : 0;
  const int t1 = mesh.EdgeTriangles[edge][0], t2 = mesh.EdgeTriangles[edge][1];
  Vec3 p;
  if (t2 < 0)
  {
    // Open boundary: refine the boundary curve by itself.
    return BoundaryPoint(mesh, a, b, t1, irregularTriangles, h, level, p)
      ? result(ButterflyRule::Boundary, p)
      : result(ButterflyRule::Midpoint, mid);
  }
  if (mesh.BoundaryVertex[a] || mesh.BoundaryVertex[b] || Flagged(irregularTriangles, t1) ||
    Flagged(irregularTriangles, t2))
  {
    return result(ButterflyRule::Midpoint, mid);
  }
  const std::vector<int> ringA = RingAt(mesh, a, b, irregularTriangles, h, level);
  const std::vector<int> ringB = RingAt(mesh, b, a, irregularTriangles, h, level);
  const int ka = static_cast<int>(ringA.size()), kb = static_cast<int>(ringB.size());
  if (ka == 6 && kb == 6)
  {
    return RegularPoint(mesh, a, b, t1, t2, ringA, ringB, h, level, p)
      ? result(ButterflyRule::Regular, p)
      : result(ButterflyRule::Midpoint, mid);
  }
  if (ka == 0 || kb == 0)
  {
    return result(ButterflyRule::Midpoint, mid);
  }
  Vec3 qa, qb;
  if (ka != 6 && kb == 6)
  {
    ZorinPoint(mesh, a, ringA, qa);
    return result(ButterflyRule::Extraordinary, qa);
  }
  if (kb != 6 && ka == 6)
  {
    ZorinPoint(mesh, b, ringB, qb);
    return result(ButterflyRule::Extraordinary, qb);
  }
  ZorinPoint(mesh, a, ringA, qa);
  ZorinPoint(mesh, b, ringB, qb);
  return result(ButterflyRule::BothExtraordinary, 0.5 * (qa + qb));
}
} // namespace dsurf
