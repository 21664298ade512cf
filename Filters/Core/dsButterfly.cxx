#include "dsButterfly.h"

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

/// The triangle on the other side of edge (p, q) from t, -1 on a boundary.
int Across(const TriangleMesh& mesh, int t, int p, int q)
{
  const int e = mesh.FindEdge(p, q);
  if (e < 0)
  {
    return -1;
  }
  const auto& et = mesh.EdgeTriangles[e];
  return et[0] == t ? et[1] : et[0];
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

bool ZorinPoint(
  const TriangleMesh& mesh, int e, int other, const std::vector<char>* flags, Vec3& out)
{
  const std::vector<int> ring = CyclicRing(mesh, e, other, flags);
  if (ring.empty())
  {
    return false;
  }
  const std::vector<double> s = ZorinWeights(static_cast<int>(ring.size()));
  out = 0.75 * mesh.Points[e];
  for (size_t j = 0; j < ring.size(); ++j)
  {
    out = out + s[j] * mesh.Points[ring[j]];
  }
  return true;
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
  const std::vector<char>* irregularTriangles, ButterflyRule* rule)
{
  const int a = mesh.Edges[edge][0], b = mesh.Edges[edge][1];
  const Vec3& pa = mesh.Points[a];
  const Vec3& pb = mesh.Points[b];
  const Vec3 mid = 0.5 * (pa + pb);
  auto result = [rule](ButterflyRule r, const Vec3& p)
  {
    if (rule)
    {
      *rule = r;
    }
    return p;
  };
  const int t1 = mesh.EdgeTriangles[edge][0], t2 = mesh.EdgeTriangles[edge][1];

  if (t2 < 0)
  {
    // Open boundary: refine the boundary curve by the 4-point scheme.
    const int a2 = NextBoundaryVertex(mesh, a, b), b2 = NextBoundaryVertex(mesh, b, a);
    if (a2 < 0 || b2 < 0 || a2 == b2 || Flagged(irregularTriangles, t1))
    {
      return result(ButterflyRule::Midpoint, mid);
    }
    return result(ButterflyRule::Boundary,
      (9.0 / 16.0) * (pa + pb) - (1.0 / 16.0) * (mesh.Points[a2] + mesh.Points[b2]));
  }
  if (mesh.BoundaryVertex[a] || mesh.BoundaryVertex[b] || Flagged(irregularTriangles, t1) ||
    Flagged(irregularTriangles, t2))
  {
    return result(ButterflyRule::Midpoint, mid);
  }

  const int ka = Valence(mesh, a), kb = Valence(mesh, b);
  if (ka == 6 && kb == 6)
  {
    const int b1 = Opposite(mesh, t1, a, b), b2 = Opposite(mesh, t2, a, b);
    // The four wings: across (a,b1), (b,b1), (a,b2), (b,b2).
    const int wingT[4] = { Across(mesh, t1, a, b1), Across(mesh, t1, b, b1),
      Across(mesh, t2, a, b2), Across(mesh, t2, b, b2) };
    const int wingP[4][2] = { { a, b1 }, { b, b1 }, { a, b2 }, { b, b2 } };
    Vec3 cSum{ 0, 0, 0 };
    for (int i = 0; i < 4; ++i)
    {
      if (wingT[i] < 0 || Flagged(irregularTriangles, wingT[i]))
      {
        return result(ButterflyRule::Midpoint, mid);
      }
      cSum = cSum + mesh.Points[Opposite(mesh, wingT[i], wingP[i][0], wingP[i][1])];
    }
    const double w = 1.0 / 16.0;
    return result(
      ButterflyRule::Regular, mid + (2.0 * w) * (mesh.Points[b1] + mesh.Points[b2]) - w * cSum);
  }

  Vec3 qa, qb;
  if (ka != 6 && kb == 6)
  {
    return ZorinPoint(mesh, a, b, irregularTriangles, qa) ? result(ButterflyRule::Extraordinary, qa)
                                                          : result(ButterflyRule::Midpoint, mid);
  }
  if (kb != 6 && ka == 6)
  {
    return ZorinPoint(mesh, b, a, irregularTriangles, qb) ? result(ButterflyRule::Extraordinary, qb)
                                                          : result(ButterflyRule::Midpoint, mid);
  }
  if (ZorinPoint(mesh, a, b, irregularTriangles, qa) &&
    ZorinPoint(mesh, b, a, irregularTriangles, qb))
  {
    return result(ButterflyRule::BothExtraordinary, 0.5 * (qa + qb));
  }
  return result(ButterflyRule::Midpoint, mid);
}
} // namespace dsurf
