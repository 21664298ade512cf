// SPDX-License-Identifier: BSD-3-Clause
// Unit test of the self-intersection count (dsSelfIntersectionCount): the tri-tri test on
// hand-made pairs, a clean icosphere, an icosphere with one vertex pushed through the
// opposite side, a fold at a shared vertex (also flat, and nearly flat neighbours), a random fan at
// one vertex, and the BVH search and classification against an independent brute-force oracle
// (orientation signs, below), also on meshes mixing tiny and huge triangles (which once made a
// uniform grid run out of memory).
#include "DSTestHelpers.h"
#include "TestSolverMeshes.h"

#include "dsSelfIntersectionCount.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <random>
#include <vector>

using namespace dsurf;

namespace
{
// The oracle is independent of the library's classification (Moeller's interval test,
// SharedVertexTrianglesOverlap, and its index loop that finds the shared corners): it finds
// the shared corners as a set intersection and decides each pair by orientation signs.
// Two closed triangles meet iff an edge of one meets the other triangle (their intersection is
// convex, so its boundary lies on an edge). The test data are generic: no exact touching, so
// the library's tolerance for touching does not matter.

/// Sign of the volume of (a, b, c, d): which side of plane abc d lies on (0: on it).
int Orient3(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  const long double v = static_cast<long double>(Dot(b - a, Cross(c - a, d - a)));
  return (v > 0) - (v < 0);
}

/// Sign of the 2-D orientation of (a, b, c) in the coordinate plane (i, j).
int Orient2(const Vec3& a, const Vec3& b, const Vec3& c, int i, int j)
{
  const long double v =
    static_cast<long double>((b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i]));
  return (v > 0) - (v < 0);
}

/// Segment pq against triangle abc, both in one plane: projected onto the coordinate plane
/// the normal is most orthogonal to, either an end lies in the triangle or pq crosses an edge.
bool CoplanarSegmentTriangle(
  const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 n = Cross(b - a, c - a);
  const int drop = std::abs(n[0]) > std::abs(n[1]) ? (std::abs(n[0]) > std::abs(n[2]) ? 0 : 2)
                                                   : (std::abs(n[1]) > std::abs(n[2]) ? 1 : 2);
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  const Vec3 tri[3] = { a, b, c };
  const int turn = Orient2(a, b, c, i, j);
  const auto inside = [&](const Vec3& x)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (Orient2(tri[k], tri[(k + 1) % 3], x, i, j) * turn < 0)
      {
        return false;
      }
    }
    return true;
  };
  if (inside(p) || inside(q))
  {
    return true;
  }
  for (int k = 0; k < 3; ++k)
  {
    const Vec3& e0 = tri[k];
    const Vec3& e1 = tri[(k + 1) % 3];
    if (Orient2(p, q, e0, i, j) * Orient2(p, q, e1, i, j) <= 0 &&
      Orient2(e0, e1, p, i, j) * Orient2(e0, e1, q, i, j) <= 0)
    {
      return true;
    }
  }
  return false;
}

/// Closed segment pq against closed triangle abc.
bool SegmentMeetsTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const int sp = Orient3(a, b, c, p), sq = Orient3(a, b, c, q);
  if (sp == 0 && sq == 0)
  {
    return CoplanarSegmentTriangle(p, q, a, b, c);
  }
  if (sp * sq > 0)
  {
    return false; // both ends on one side of the plane
  }
  // The line pq passes abc's edges all on one side (or touches one).
  const int s0 = Orient3(p, q, a, b), s1 = Orient3(p, q, b, c), s2 = Orient3(p, q, c, a);
  return !((s0 < 0 || s1 < 0 || s2 < 0) && (s0 > 0 || s1 > 0 || s2 > 0));
}

bool OracleTrianglesMeet(const Vec3* A, const Vec3* B)
{
  for (int k = 0; k < 3; ++k)
  {
    if (SegmentMeetsTriangle(A[k], A[(k + 1) % 3], B[0], B[1], B[2]) ||
      SegmentMeetsTriangle(B[k], B[(k + 1) % 3], A[0], A[1], A[2]))
    {
      return true;
    }
  }
  return false;
}

/// Whether direction d points into the wedge of triangle (s, e1 + s, e2 + s) at s
/// (strictly: d = alpha e1 + beta e2 with alpha, beta > 0).
bool InWedge(const Vec3& d, const Vec3& e1, const Vec3& e2)
{
  const Vec3 n = Cross(e1, e2);
  return Dot(Cross(d, e2), n) > 0 && Dot(Cross(e1, d), n) > 0;
}

/// Triangles (s, a1, a2) and (s, b1, b2) in different planes meet along a segment of the
/// planes' common line through s; they overlap beyond s iff one direction of that line
/// enters both wedges at s. In one plane they overlap iff a direction enters both wedges:
/// an edge of one inside the other, or (equal wedges) a bisector.
bool OracleOverlapBeyondVertex(
  const Vec3& s, const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2)
{
  const Vec3 d = Cross(Cross(a1 - s, a2 - s), Cross(b1 - s, b2 - s));
  if (Dot(d, d) == 0)
  {
    const Vec3 ea1 = a1 - s, ea2 = a2 - s, eb1 = b1 - s, eb2 = b2 - s;
    const Vec3 bisA = (1 / Norm(ea1)) * ea1 + (1 / Norm(ea2)) * ea2;
    const Vec3 bisB = (1 / Norm(eb1)) * eb1 + (1 / Norm(eb2)) * eb2;
    return InWedge(eb1, ea1, ea2) || InWedge(eb2, ea1, ea2) || InWedge(ea1, eb1, eb2) ||
      InWedge(ea2, eb1, eb2) || InWedge(bisA, eb1, eb2) || InWedge(bisB, ea1, ea2);
  }
  const Vec3 minusD = -1.0 * d;
  return (InWedge(d, a1 - s, a2 - s) && InWedge(d, b1 - s, b2 - s)) ||
    (InWedge(minusD, a1 - s, a2 - s) && InWedge(minusD, b1 - s, b2 - s));
}

/// The point ids two triangles share, as a set intersection of their sorted corners.
std::vector<int> SharedCorners(std::array<int, 3> a, std::array<int, 3> b)
{
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::vector<int> common;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
  return common;
}

/// The two corners of triangle t other than point s (the wedge test ignores their order).
std::array<int, 2> OtherCorners(const std::array<int, 3>& t, int s)
{
  std::array<int, 2> other{ -1, -1 };
  std::copy_if(t.begin(), t.end(), other.begin(), [s](int v) { return v != s; });
  return other;
}

/// All intersecting pairs (a < b) by the oracle, testing every pair: pairs sharing an edge
/// are skipped, pairs sharing one vertex count when they overlap beyond it. With
/// `skipDisjointBoxes` pairs whose bounding boxes are apart are skipped first (exact, and
/// fast enough for 20k triangles).
std::vector<std::pair<int, int>> BruteForcePairs(const TriangleMesh& m, bool skipDisjointBoxes)
{
  const auto& P = m.Points;
  const int n = m.NumberOfTriangles();
  std::vector<std::array<double, 6>> box(n);
  for (int t = 0; t < n; ++t)
  {
    for (int a = 0; a < 3; ++a)
    {
      box[t][a] =
        std::min({ P[m.Triangles[t][0]][a], P[m.Triangles[t][1]][a], P[m.Triangles[t][2]][a] });
      box[t][a + 3] =
        std::max({ P[m.Triangles[t][0]][a], P[m.Triangles[t][1]][a], P[m.Triangles[t][2]][a] });
    }
  }
  std::vector<std::pair<int, int>> brute;
  for (int a = 0; a < n; ++a)
  {
    for (int b = a + 1; b < n; ++b)
    {
      if (skipDisjointBoxes &&
        (box[a][3] < box[b][0] || box[b][3] < box[a][0] || box[a][4] < box[b][1] ||
          box[b][4] < box[a][1] || box[a][5] < box[b][2] || box[b][5] < box[a][2]))
      {
        continue;
      }
      const auto &A = m.Triangles[a], &B = m.Triangles[b];
      const std::vector<int> common = SharedCorners(A, B);
      bool hit = false;
      if (common.empty())
      {
        const Vec3 pa[3] = { P[A[0]], P[A[1]], P[A[2]] }, pb[3] = { P[B[0]], P[B[1]], P[B[2]] };
        hit = OracleTrianglesMeet(pa, pb);
      }
      else if (common.size() == 1)
      {
        const std::array<int, 2> oa = OtherCorners(A, common[0]), ob = OtherCorners(B, common[0]);
        hit = OracleOverlapBeyondVertex(P[common[0]], P[oa[0]], P[oa[1]], P[ob[0]], P[ob[1]]);
      }
      if (hit)
      {
        brute.emplace_back(a, b);
      }
    }
  }
  return brute;
}

void AddTriangle(TriangleMesh& m, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const int base = m.NumberOfPoints();
  m.Points.push_back(a);
  m.Points.push_back(b);
  m.Points.push_back(c);
  m.Triangles.push_back({ base, base + 1, base + 2 });
}
} // namespace

int TestSelfIntersectionCount(int, char*[])
{
  // --- pairs ---
  {
    // Two triangles crossing like links of a chain.
    TriangleMesh m;
    m.Points = { { 0, 0, 0 }, { 2, 0, 0 }, { 1, 2, 0 }, { 1, 1, -1 }, { 1, 1, 1 }, { 1, 3, 0 } };
    m.Triangles = { { 0, 1, 2 }, { 3, 4, 5 } };
    DS_CHECK(CountSelfIntersections(m) == 1, "two crossing triangles: 1 pair");
    // Move the second one away: 0.
    for (int i = 3; i < 6; ++i)
    {
      m.Points[i][0] += 5;
    }
    DS_CHECK(CountSelfIntersections(m) == 0, "two separated triangles: 0 pairs");
    // Parallel planes, overlapping in x/y: 0.
    DS_CHECK(!TrianglesIntersect(
               { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 0.1 }, { 1, 0, 0.1 }, { 0, 1, 0.1 }),
      "parallel triangles do not intersect");
    // Coplanar, overlapping: 1; coplanar, apart: 0.
    DS_CHECK(TrianglesIntersect({ 0, 0, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, { 0.5, 0.5, 0 },
               { 3, 0.5, 0 }, { 0.5, 3, 0 }),
      "overlapping coplanar triangles intersect");
    DS_CHECK(!TrianglesIntersect(
               { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 2, 2, 0 }, { 3, 2, 0 }, { 2, 3, 0 }),
      "separated coplanar triangles do not intersect");
    // A triangle piercing another near its edge, and one just missing it.
    DS_CHECK(TrianglesIntersect({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0.49, 0.49, -1 },
               { 0.49, 0.49, 1 }, { 5, 5, 0.5 }),
      "piercing near the hypotenuse");
    DS_CHECK(!TrianglesIntersect({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0.51, 0.51, -1 },
               { 0.51, 0.51, 1 }, { 5, 5, 0.5 }),
      "missing just beyond the hypotenuse");
  }

  // --- shared vertex: a fold through the neighbour counts, a normal fan does not ---
  {
    const Vec3 s{ 0, 0, 0 };
    DS_CHECK(
      !SharedVertexTrianglesOverlap(s, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { -1, 1, 0.2 }),
      "neighbouring fan triangles do not overlap");
    // B's plane crosses A's interior beyond s on the same side: a fold.
    DS_CHECK(
      SharedVertexTrianglesOverlap(s, { 2, -1, 0 }, { 2, 1, 0 }, { 1, 0, -1 }, { 1, 0.2, 1 }),
      "a triangle folded through its neighbour at a shared vertex");
    DS_CHECK(
      !SharedVertexTrianglesOverlap(s, { 2, -1, 0 }, { 2, 1, 0 }, { -1, 0, -1 }, { -1, 0.2, 1 }),
      "the same triangle on the other side of s");
    // In one plane: a triangle folded flat onto its neighbour overlaps it.
    DS_CHECK(
      SharedVertexTrianglesOverlap(s, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 0.2, 0 }, { 0.2, 1, 0 }),
      "a triangle folded flat onto its neighbour (coplanar)");
    // Two triangles side by side on a flat box face whose shared vertex one Gauss-Seidel sweep
    // moved by 2e-12 voxel (off the face plane x = 0.5 too): the 3-D test placed the common line
    // of the nearly parallel planes anywhere and called them a fold.
    const Vec3 moved{ 0.49999999999801792, 18.218749999998018, 10.343749999998018 };
    DS_CHECK(!SharedVertexTrianglesOverlap(moved, { 0.5, 18.21875, 8.375 }, { 0.5, 16.25, 8.375 },
               { 0.5, 16.25, 10.34375 }, { 0.5, 18.21875, 12.3125 }),
      "neighbours on a flat face, shared vertex moved 2e-12 off the plane");
  }

  // --- icosphere: clean, then one vertex pushed through the opposite side ---
  {
    TriangleMesh m = dstest::MakeIcosphere(4, 10, { 0, 0, 0 });
    std::string err;
    DS_CHECK(m.BuildTopology(&err), err);
    const int clean = CountSelfIntersections(m);
    DS_CHECK_LE(clean, 0, "self-intersections of an icosphere (5120 triangles)");
    // The vertex with the largest z goes to z = -15, beyond the south pole.
    int top = 0;
    for (int v = 0; v < m.NumberOfPoints(); ++v)
    {
      if (m.Points[v][2] > m.Points[top][2])
      {
        top = v;
      }
    }
    m.Points[top] = { 0.01, 0.02, -15 };
    std::vector<std::pair<int, int>> pairs;
    const int pushed = CountSelfIntersections(m, &pairs);
    DS_CHECK_GE(pushed, 5, "self-intersections after pushing one vertex through the sphere");

    // Brute force over all pairs gives the same set.
    const std::vector<std::pair<int, int>> brute = BruteForcePairs(m, false);
    std::cout << "  BVH pairs " << pairs.size() << ", brute-force pairs " << brute.size()
              << std::endl;
    DS_CHECK(pairs == brute, "BVH search finds exactly the brute-force pairs");
  }

  // --- random fan: triangles that all share one vertex, so every pair is decided by the
  // shared-vertex rule; some fold through each other, most do not ---
  {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    TriangleMesh m;
    m.Points.push_back({ 0, 0, 0 });
    for (int t = 0; t < 150; ++t)
    {
      m.Points.push_back({ u(rng), u(rng), u(rng) });
      m.Points.push_back({ u(rng), u(rng), u(rng) });
      m.Triangles.push_back({ 0, 2 * t + 1, 2 * t + 2 });
    }
    std::vector<std::pair<int, int>> pairs;
    const int found = CountSelfIntersections(m, &pairs);
    const std::vector<std::pair<int, int>> brute = BruteForcePairs(m, false);
    const int all = 150 * 149 / 2;
    std::cout << "  fan of 150 triangles at one vertex: BVH " << found << ", oracle "
              << brute.size() << " of " << all << " pairs" << std::endl;
    DS_CHECK(pairs == brute, "BVH pairs equal the oracle on a random fan at one shared vertex");
    DS_CHECK(found > 0 && found < all, "the fan has overlapping and separate pairs");
  }

  // --- random triangle soup: grid = brute force ---
  {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 10), d(-0.7, 0.7);
    TriangleMesh m;
    for (int t = 0; t < 600; ++t)
    {
      const Vec3 c{ u(rng), u(rng), u(rng) };
      for (int k = 0; k < 3; ++k)
      {
        m.Points.push_back({ c[0] + d(rng), c[1] + d(rng), c[2] + d(rng) });
      }
      m.Triangles.push_back({ 3 * t, 3 * t + 1, 3 * t + 2 });
    }
    const int brute = static_cast<int>(BruteForcePairs(m, false).size());
    const int found = CountSelfIntersections(m);
    std::cout << "  soup: BVH " << found << ", brute force " << brute << std::endl;
    DS_CHECK(found == brute && brute > 0, "BVH count equals brute force on a random soup");
  }

  // --- a fine sphere and a few huge slanted triangles: exact, and no blow-up ---
  // (A uniform grid with cells of the typical triangle size put each huge triangle into
  // ~(size/cell)^3 cells: 100 s for one triangle of size 50, std::bad_alloc for three.)
  {
    TriangleMesh m = dstest::MakeIcosphere(5, 1, { 0, 0, 0 }); // 20480 triangles, edge ~0.03
    const int nSphere = m.NumberOfTriangles();
    // Through the centre (centroid at the origin): crosses the sphere along a great circle.
    AddTriangle(m, { -25, -20, -25 }, { 25, -5, 20 }, { 0, 25, 5 });
    // Size 100, also through the centre, slanted the other way: crosses the sphere and
    // the first one.
    AddTriangle(m, { -60, 10, 40 }, { 50, -45, -20 }, { 10, 35, -20 });
    // Size 100 in the plane x + y + z = 6 (3.5 from the centre): its box holds the whole
    // sphere, but it misses it.
    AddTriangle(m, { -50, 30, 26 }, { 50, -50, 6 }, { 10, 50, -54 });
    // A long needle of length 160 through the sphere near its axis.
    AddTriangle(m, { -80, 0.1, 0.05 }, { 80, -0.1, 0.02 }, { 80, 0.1, -0.03 });
    // Huge and far away: overlaps nothing.
    AddTriangle(m, { 300, 300, 300 }, { 400, 320, 310 }, { 350, 420, 390 });

    std::vector<std::pair<int, int>> pairs;
    const int found = CountSelfIntersections(m, &pairs);
    const std::vector<std::pair<int, int>> brute = BruteForcePairs(m, true);
    int hugeHuge = 0, missing = 0, needle = 0;
    for (const auto& pr : brute)
    {
      hugeHuge += pr.first >= nSphere;
      missing += pr.first == nSphere + 2 || pr.second == nSphere + 2;
      needle += pr.first < nSphere && pr.second == nSphere + 3;
    }
    std::cout << "  sphere + huge triangles: BVH " << found << ", brute force " << brute.size()
              << " (huge-huge " << hugeHuge << ", needle-sphere " << needle
              << ", with the missing plane " << missing << ")" << std::endl;
    DS_CHECK(pairs == brute, "BVH pairs equal brute force on a sphere with huge triangles");
    DS_CHECK(found == static_cast<int>(brute.size()), "count equals the number of pairs");
    // The two triangles through the centre cross each other, and the needle (which
    // pierces both); each great circle crosses a few hundred sphere triangles.
    DS_CHECK_GE(hugeHuge, 3, "pairs among the huge triangles");
    DS_CHECK_GE(needle, 2, "sphere triangles pierced by the needle");
    DS_CHECK_GE(static_cast<int>(brute.size()), 400, "pairs on the sphere with huge triangles");
  }

  // --- random soup of tiny and huge triangles, plus a dense far cluster: = brute force ---
  {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0, 10), unit(-1, 1), logSize(-3, 1.6);
    TriangleMesh m;
    for (int t = 0; t < 1500; ++t)
    {
      // Sizes from 0.001 to 40 (log-uniform): most tiny, a few spanning everything.
      const double size = std::pow(10.0, logSize(rng));
      const Vec3 c{ u(rng), u(rng), u(rng) };
      Vec3 v[3];
      for (int k = 0; k < 3; ++k)
      {
        v[k] = { c[0] + size * unit(rng), c[1] + size * unit(rng), c[2] + size * unit(rng) };
      }
      AddTriangle(m, v[0], v[1], v[2]);
    }
    // 300 triangles of size 0.01 packed into a 0.02 cube far away (they cross a lot).
    for (int t = 0; t < 300; ++t)
    {
      const Vec3 c{ 1000 + 0.01 * unit(rng), 1000 + 0.01 * unit(rng), 1000 + 0.01 * unit(rng) };
      Vec3 v[3];
      for (int k = 0; k < 3; ++k)
      {
        v[k] = { c[0] + 0.01 * unit(rng), c[1] + 0.01 * unit(rng), c[2] + 0.01 * unit(rng) };
      }
      AddTriangle(m, v[0], v[1], v[2]);
    }
    std::vector<std::pair<int, int>> pairs;
    const int found = CountSelfIntersections(m, &pairs);
    const std::vector<std::pair<int, int>> brute = BruteForcePairs(m, false);
    int cluster = 0;
    for (const auto& pr : brute)
    {
      cluster += pr.first >= 1500;
    }
    std::cout << "  mixed soup: BVH " << found << ", brute force " << brute.size()
              << " (in the far cluster " << cluster << ")" << std::endl;
    DS_CHECK(pairs == brute, "BVH pairs equal brute force on a soup of tiny and huge triangles");
    DS_CHECK(cluster > 0 && static_cast<int>(brute.size()) > cluster,
      "the mixed soup has crossings in both parts");
  }

  return dstest::Result("TestSelfIntersectionCount");
}

int main(int argc, char* argv[])
{
  return TestSelfIntersectionCount(argc, argv);
}
