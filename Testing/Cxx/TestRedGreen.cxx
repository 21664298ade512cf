// SPDX-License-Identifier: BSD-3-Clause
// Red-green refinement (docs/METHOD.md §6.3-6.4): exact counts for one marked triangle, undoing a
// marked green, uniform refinement, random adaptive marks over several levels on closed
// and open meshes, a point-focused cascade; after every step the topology invariants,
// zero T-vertices and the label rules are checked independently of the refiner's code.
#include "DSSurfaceInvariants.h"
#include "DSTestHelpers.h"
#include "TestSolverMeshes.h"
#include "dsRedGreen.h"

#include <map>
#include <random>
#include <set>

using namespace dsurf;

namespace
{
TriangleMesh Octahedron()
{
  TriangleMesh m;
  m.Points = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
  m.Triangles = { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 }, { 2, 0, 5 }, { 1, 2, 5 },
    { 3, 1, 5 }, { 0, 3, 5 } };
  return m;
}

TriangleMesh Icosahedron()
{
  TriangleMesh m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  m.Points = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t }, { 0, 1, t },
    { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 }, { -t, 0, 1 } };
  m.Triangles = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 }, { 1, 5, 9 },
    { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 },
    { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 } };
  return m;
}

/// A flat n x n grid patch in z = 0 (open, a disc: Euler characteristic 1).
TriangleMesh Grid(int n)
{
  return dstest::HeightGrid(n, [](double, double) { return 0.0; });
}

int CountLabel(const TriangleMesh& m, unsigned char label)
{
  int c = 0;
  for (auto l : m.Labels)
  {
    c += l == label ? 1 : 0;
  }
  return c;
}

/// Checks the invariants and the label rules after a step; returns the number of problems.
void CheckStep(const RedGreenRefiner& rg, const TriangleMesh& m, const RefinementCounts& c,
  int euler, bool closed, const std::string& what)
{
  DS_CHECK(c.Ok, what + ": " + c.Error);
  std::string msg;
  DS_CHECK(CheckTopologyInvariants(m, euler, closed, &msg), what + ": " + msg);
  // The shared surface checks (finite, 2-manifold, every point used, no self-intersection);
  // the Euler characteristic and closedness against the start's are the line above's.
  dstest::CheckSurfaceInvariants(m, m, what);
  DS_CHECK(rg.CountTVertices(m) == 0, what + ": no T-vertex");
  DS_CHECK(m.Labels.size() == m.Points.size() && m.Levels.size() == m.Points.size(),
    what + ": per-point arrays");

  // Label rules rederived from the green pairs: M on midpoints, C on split-edge ends,
  // D on opposite corners, N elsewhere; priority M > C > D.
  std::vector<std::set<unsigned char>> roles(m.Points.size());
  std::map<std::array<int, 3>, int> pairHalves;
  for (int t = 0; t < m.NumberOfTriangles(); ++t)
  {
    std::array<int, 3> parent;
    int corner, mid;
    if (!rg.GetGreen(t, parent, corner, mid))
    {
      continue;
    }
    ++pairHalves[parent];
    roles[mid].insert(LabelM);
    roles[parent[corner]].insert(LabelC);
    roles[parent[(corner + 1) % 3]].insert(LabelC);
    roles[parent[(corner + 2) % 3]].insert(LabelD);
    // The halves really are the two halves of the parent.
    const auto& tri = m.Triangles[t];
    int shared = 0;
    for (int v : tri)
    {
      shared += (v == mid || v == parent[0] || v == parent[1] || v == parent[2]) ? 1 : 0;
    }
    DS_CHECK(shared == 3, what + ": green half made of parent corners and M");
  }
  bool pairsOk = true;
  for (const auto& p : pairHalves)
  {
    pairsOk = pairsOk && p.second == 2;
  }
  DS_CHECK(pairsOk, what + ": every green parent has exactly two halves");
  int wrong = 0;
  for (size_t v = 0; v < m.Points.size(); ++v)
  {
    unsigned char expect = LabelN;
    if (roles[v].count(LabelM))
    {
      expect = LabelM;
    }
    else if (roles[v].count(LabelC))
    {
      expect = LabelC;
    }
    else if (roles[v].count(LabelD))
    {
      expect = LabelD;
    }
    wrong += m.Labels[v] == expect ? 0 : 1;
  }
  DS_CHECK(
    wrong == 0, what + ": labels follow the green pairs (" + std::to_string(wrong) + " wrong)");
}
} // namespace

int TestRedGreen(int, char*[])
{
  std::string err;
  // --- One marked triangle on the octahedron: exact counts and labels.
  {
    TriangleMesh m = Octahedron();
    RedGreenRefiner rg;
    DS_CHECK(rg.Initialize(m, &err), err);
    std::vector<char> marks(m.NumberOfTriangles(), 0);
    marks[0] = 1; // (0, 2, 4)
    RefinementCounts c = rg.Refine(m, marks, Prolongation::Linear);
    CheckStep(rg, m, c, 2, true, "one red on the octahedron");
    DS_CHECK(c.RedSplits == 1 && c.Greens == 3 && c.NewVertices == 3 && c.UndoneGreens == 0,
      "1 red, 3 greens, 3 new points");
    DS_CHECK(m.NumberOfTriangles() == 14, "8 - 1 - 3 + 4 + 6 = 14 triangles");
    DS_CHECK(CountLabel(m, LabelM) == 3 && CountLabel(m, LabelC) == 3 && CountLabel(m, LabelD) == 3,
      "3 M, 3 C, 3 D");
    DS_CHECK(m.Labels[0] == LabelC && m.Labels[2] == LabelC && m.Labels[4] == LabelC,
      "corners of the red are C");
    DS_CHECK(m.Labels[1] == LabelD && m.Labels[3] == LabelD && m.Labels[5] == LabelD,
      "opposite corners are D");
    DS_CHECK(m.Levels[6] == 1 && m.Levels[0] == 0, "levels");
    // Linear prolongation: the midpoint of (0, 2) is the first new point.
    DS_CHECK(Norm(m.Points[6] - Vec3{ 0.5, 0.5, 0 }) < 1e-15, "linear midpoint");

    // Mark one half of a green: the green is undone and its parent red-split; the
    // parent's other edges split too, so the closure goes on to neighbours.
    int greenT = -1;
    for (int t = 0; t < m.NumberOfTriangles() && greenT < 0; ++t)
    {
      greenT = rg.IsGreen(t) ? t : -1;
    }
    std::array<int, 3> parent;
    int corner, mid;
    rg.GetGreen(greenT, parent, corner, mid);
    std::vector<char> marks2(m.NumberOfTriangles(), 0);
    marks2[greenT] = 1;
    const int nBefore = m.NumberOfPoints();
    c = rg.Refine(m, marks2, Prolongation::Linear);
    CheckStep(rg, m, c, 2, true, "marked green on the octahedron");
    std::cout << "  marked green: red " << c.RedSplits << " (closure " << c.ClosureRedSplits
              << "), greens " << c.Greens << ", undone " << c.UndoneGreens << ", triangles "
              << m.NumberOfTriangles() << std::endl;
    DS_CHECK(c.UndoneGreens >= 1, "the marked green is undone");
    DS_CHECK(c.RedSplits >= 1, "its parent is red-split");
    // The old M is now an inner vertex of a red split on both sides: valence 6, label N.
    DS_CHECK(m.NeighborOffsets[mid + 1] - m.NeighborOffsets[mid] == 6, "old M has valence 6");
    DS_CHECK(m.Labels[mid] == LabelN || m.Labels[mid] == LabelC || m.Labels[mid] == LabelD,
      "old M is no longer M");
    bool greenParentSplit = true;
    for (int t = 0; t < m.NumberOfTriangles(); ++t)
    {
      const auto& tri = m.Triangles[t];
      // No triangle may still span a parent edge that got split.
      for (int k = 0; k < 3; ++k)
      {
        const int a = tri[k], b = tri[(k + 1) % 3];
        if ((a == parent[0] || a == parent[1] || a == parent[2]) &&
          (b == parent[0] || b == parent[1] || b == parent[2]))
        {
          greenParentSplit = false;
        }
      }
    }
    DS_CHECK(greenParentSplit, "every edge of the undone green's parent is split");
    DS_CHECK(m.NumberOfPoints() > nBefore, "new points appended");
  }

  // --- Uniform refinement: 4x triangles, no greens, all N.
  {
    TriangleMesh m = Icosahedron();
    RedGreenRefiner rg;
    DS_CHECK(rg.Initialize(m, &err), err);
    for (int level = 1; level <= 3; ++level)
    {
      std::vector<char> all(m.NumberOfTriangles(), 1);
      RefinementCounts c = rg.Refine(m, all, Prolongation::Butterfly);
      CheckStep(rg, m, c, 2, true, "uniform level " + std::to_string(level));
      DS_CHECK(c.Greens == 0 && c.ClosureRedSplits == 0, "uniform: no greens, no closure");
      DS_CHECK(CountLabel(m, LabelN) == m.NumberOfPoints(), "uniform: all N");
    }
    DS_CHECK(m.NumberOfTriangles() == 20 * 64, "20 * 4^3 triangles");
    DS_CHECK(m.NumberOfPoints() == 10 * 64 + 2, "10 * 4^3 + 2 points");
  }

  // --- Random adaptive marks over several levels (closed meshes), greens marked too.
  for (int shape = 0; shape < 2; ++shape)
  {
    std::mt19937 rng(1234 + shape);
    TriangleMesh m = shape == 0 ? Octahedron() : Icosahedron();
    RedGreenRefiner rg;
    DS_CHECK(rg.Initialize(m, &err), err);
    int undone = 0, closure = 0, maxGreens = 0, hadAllRoles = 0;
    for (int level = 1; level <= 6; ++level)
    {
      std::uniform_real_distribution<double> u(0.0, 1.0);
      std::vector<char> marks(m.NumberOfTriangles(), 0);
      for (auto& mk : marks)
      {
        mk = u(rng) < 0.15 ? 1 : 0;
      }
      const std::vector<Vec3> oldPoints = m.Points;
      RefinementCounts c = rg.Refine(m, marks, Prolongation::Butterfly);
      const std::string what = (shape == 0 ? "octahedron" : "icosahedron") +
        std::string(" random level ") + std::to_string(level);
      CheckStep(rg, m, c, 2, true, what);
      bool kept = true;
      for (size_t v = 0; v < oldPoints.size(); ++v)
      {
        kept = kept && oldPoints[v] == m.Points[v];
      }
      DS_CHECK(kept, what + ": old points keep their index and position");
      undone += c.UndoneGreens;
      closure += c.ClosureRedSplits;
      maxGreens = std::max(maxGreens, c.Greens);
      hadAllRoles +=
        (CountLabel(m, LabelM) > 0 && CountLabel(m, LabelC) > 0 && CountLabel(m, LabelD) > 0) ? 1
                                                                                              : 0;
      std::cout << "  " << what << ": triangles " << m.NumberOfTriangles() << ", red "
                << c.RedSplits << " (closure " << c.ClosureRedSplits << "), greens " << c.Greens
                << ", undone " << c.UndoneGreens << std::endl;
    }
    DS_CHECK(undone > 0, "random marks exercised undoing greens");
    DS_CHECK(closure > 0, "random marks exercised the red closure");
    DS_CHECK(hadAllRoles > 0, "labels M, C, D all occurred");
  }

  // --- A cascade focused on one point: marks around vertex 0 at every level force the
  // two-level rule (a coarse triangle next to a region refined twice).
  {
    TriangleMesh m = Icosahedron();
    RedGreenRefiner rg;
    DS_CHECK(rg.Initialize(m, &err), err);
    const Vec3 focus = m.Points[0];
    for (int level = 1; level <= 6; ++level)
    {
      std::vector<char> marks(m.NumberOfTriangles(), 0);
      for (int t = 0; t < m.NumberOfTriangles(); ++t)
      {
        for (int v : m.Triangles[t])
        {
          marks[t] = marks[t] || Norm(m.Points[v] - focus) < 1e-9;
        }
      }
      RefinementCounts c = rg.Refine(m, marks, Prolongation::Linear);
      CheckStep(rg, m, c, 2, true, "cascade level " + std::to_string(level));
    }
    // Local refinement stays local: far fewer than the 20 * 4^6 of uniform refinement.
    DS_CHECK_LE(m.NumberOfTriangles(), 2000, "triangles after 6 focused levels");
  }

  // --- Open mesh (a flat disc): invariants without closedness, the plane stays flat,
  // boundary edges split without T-vertices.
  {
    TriangleMesh m = Grid(6);
    RedGreenRefiner rg;
    DS_CHECK(rg.Initialize(m, &err), err);
    std::mt19937 rng(99);
    for (int level = 1; level <= 4; ++level)
    {
      std::uniform_real_distribution<double> u(0.0, 1.0);
      std::vector<char> marks(m.NumberOfTriangles(), 0);
      for (auto& mk : marks)
      {
        mk = u(rng) < 0.25 ? 1 : 0;
      }
      RefinementCounts c = rg.Refine(m, marks, Prolongation::Butterfly);
      CheckStep(rg, m, c, 1, false, "grid level " + std::to_string(level));
    }
    double maxZ = 0;
    for (const auto& p : m.Points)
    {
      maxZ = std::max(maxZ, std::abs(p[2]));
    }
    DS_CHECK_LE(maxZ, 1e-12, "max |z| of the refined plane");
  }

  // --- Bad input.
  {
    // Two triangles on the same three vertices (a closed 2-manifold "pillow", found by the
    // fuzzer): their 1 -> 4 splits would share midpoints and four triangles one edge, so the
    // refiner refuses the mesh up front, with a message.
    TriangleMesh pillow;
    pillow.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
    pillow.Triangles = { { 0, 1, 2 }, { 2, 1, 0 } };
    RedGreenRefiner rg;
    std::string why;
    DS_CHECK(!rg.Initialize(pillow, &why), "a two-triangle pillow is refused");
    DS_CHECK(why.find("same three vertices") != std::string::npos, "the pillow's message: " + why);
  }
  {
    TriangleMesh m = Octahedron();
    RedGreenRefiner rg;
    std::vector<char> marks(8, 1);
    DS_CHECK(!rg.Refine(m, marks).Ok, "refine before Initialize fails");
    DS_CHECK(rg.Initialize(m, &err), err);
    std::vector<char> shortMarks(3, 1);
    DS_CHECK(!rg.Refine(m, shortMarks).Ok, "wrong number of marks fails");
    m.Triangles.pop_back();
    DS_CHECK(!rg.Refine(m, marks).Ok, "connectivity changed behind the refiner fails");
  }
  return dstest::Result("TestRedGreen");
}

int main(int argc, char* argv[])
{
  return TestRedGreen(argc, argv);
}
