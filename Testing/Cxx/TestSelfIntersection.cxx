// Unit test of the self-intersection count (dsSelfIntersection): the tri-tri test on
// hand-made pairs, a clean icosphere, an icosphere with one vertex pushed through the
// opposite side, a fold at a shared vertex, and the grid against brute force.
#include "DSTestHelpers.h"
#include "TestSolverMeshes.h"

#include "dsSelfIntersection.h"

#include <random>

using namespace dsurf;

int TestSelfIntersection(int, char*[])
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
    DS_CHECK(!TrianglesIntersect({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 0.1 }, { 1, 0, 0.1 },
               { 0, 1, 0.1 }),
      "parallel triangles do not intersect");
    // Coplanar, overlapping: 1; coplanar, apart: 0.
    DS_CHECK(TrianglesIntersect({ 0, 0, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, { 0.5, 0.5, 0 }, { 3, 0.5, 0 },
               { 0.5, 3, 0 }),
      "overlapping coplanar triangles intersect");
    DS_CHECK(!TrianglesIntersect({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 2, 2, 0 }, { 3, 2, 0 },
               { 2, 3, 0 }),
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
    DS_CHECK(!SharedVertexTrianglesOverlap(s, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { -1, 1, 0.2 }),
      "neighbouring fan triangles do not overlap");
    // B's plane crosses A's interior beyond s on the same side: a fold.
    DS_CHECK(SharedVertexTrianglesOverlap(s, { 2, -1, 0 }, { 2, 1, 0 }, { 1, 0, -1 }, { 1, 0.2, 1 }),
      "a triangle folded through its neighbour at a shared vertex");
    DS_CHECK(!SharedVertexTrianglesOverlap(s, { 2, -1, 0 }, { 2, 1, 0 }, { -1, 0, -1 }, { -1, 0.2, 1 }),
      "the same triangle on the other side of s");
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
    std::vector<std::pair<int, int>> brute;
    for (int a = 0; a < m.NumberOfTriangles(); ++a)
    {
      for (int b = a + 1; b < m.NumberOfTriangles(); ++b)
      {
        const auto &A = m.Triangles[a], &B = m.Triangles[b];
        int shared = 0, sa = -1, sb = -1;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            if (A[i] == B[j])
            {
              ++shared;
              sa = i;
              sb = j;
            }
        const auto& P = m.Points;
        bool hit = false;
        if (shared == 0)
        {
          hit = TrianglesIntersect(P[A[0]], P[A[1]], P[A[2]], P[B[0]], P[B[1]], P[B[2]]);
        }
        else if (shared == 1)
        {
          hit = SharedVertexTrianglesOverlap(P[A[sa]], P[A[(sa + 1) % 3]], P[A[(sa + 2) % 3]],
            P[B[(sb + 1) % 3]], P[B[(sb + 2) % 3]]);
        }
        if (hit)
        {
          brute.emplace_back(a, b);
        }
      }
    }
    std::cout << "  grid pairs " << pairs.size() << ", brute-force pairs " << brute.size() << std::endl;
    DS_CHECK(pairs == brute, "grid search finds exactly the brute-force pairs");
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
    int brute = 0;
    for (int a = 0; a < 600; ++a)
      for (int b = a + 1; b < 600; ++b)
        brute += TrianglesIntersect(m.Points[3 * a], m.Points[3 * a + 1], m.Points[3 * a + 2],
          m.Points[3 * b], m.Points[3 * b + 1], m.Points[3 * b + 2]);
    const int grid = CountSelfIntersections(m);
    std::cout << "  soup: grid " << grid << ", brute force " << brute << std::endl;
    DS_CHECK(grid == brute && brute > 0, "grid count equals brute force on a random soup");
  }

  return dstest::Result("TestSelfIntersection");
}

int main(int argc, char* argv[])
{
  return TestSelfIntersection(argc, argv);
}
