// SPDX-License-Identifier: BSD-3-Clause
// Butterfly prolongation (docs/METHOD.md §6.5): polynomial reproduction on a regular patch, the
// plane stays planar under every rule, the boundary 4-point rule, Zorin's extraordinary
// weights, the fallback next to green triangles, and better start values than the
// midpoint on a sphere.
#include "DSSurfaceInvariants.h"
#include "DSTestHelpers.h"
#include "TestSolverMeshes.h"
#include "dsButterfly.h"
#include "dsRedGreen.h"

#include <functional>
#include <map>
#include <random>

using namespace dsurf;

namespace
{
constexpr double kPi = 3.14159265358979323846;

/// dstest::HeightGrid with its topology built.
TriangleMesh Grid(int n, const std::function<double(double, double)>& f,
  const std::function<bool(int, int)>& flipped = nullptr)
{
  TriangleMesh m = dstest::HeightGrid(n, f, flipped);
  std::string err;
  m.BuildTopology(&err);
  return m;
}

TriangleMesh Icosahedron()
{
  TriangleMesh m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  m.Points = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t }, { 0, 1, t },
    { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 }, { -t, 0, 1 } };
  for (auto& p : m.Points)
  {
    p = (1.0 / Norm(p)) * p;
  }
  m.Triangles = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 }, { 1, 5, 9 },
    { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 },
    { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 } };
  return m;
}
} // namespace

int TestButterfly(int, char*[])
{
  // --- Regular patch: the 8-point butterfly reproduces quadrics and cubics exactly;
  // the midpoint does not.
  {
    auto quad = [](double x, double y)
    { return 0.05 * x * x - 0.03 * x * y + 0.02 * y * y + 0.1 * x + 1; };
    auto cubic = [](double x, double y)
    { return 0.01 * x * x * x - 0.004 * x * y * y + 0.02 * y * y + x; };
    for (int which = 0; which < 2; ++which)
    {
      auto f = which == 0 ? std::function<double(double, double)>(quad)
                          : std::function<double(double, double)>(cubic);
      TriangleMesh m = Grid(8, f);
      int regular = 0;
      double maxErr = 0, maxLinearErr = 0;
      for (int e = 0; e < static_cast<int>(m.Edges.size()); ++e)
      {
        ButterflyRule rule;
        const Vec3 p = ButterflyEdgePoint(m, e, nullptr, &rule);
        if (rule != ButterflyRule::Regular)
        {
          continue;
        }
        ++regular;
        const Vec3 mid = 0.5 * (m.Points[m.Edges[e][0]] + m.Points[m.Edges[e][1]]);
        maxErr = std::max(maxErr, std::abs(p[2] - f(p[0], p[1])));
        maxErr = std::max(maxErr, std::max(std::abs(p[0] - mid[0]), std::abs(p[1] - mid[1])));
        maxLinearErr = std::max(maxLinearErr, std::abs(mid[2] - f(mid[0], mid[1])));
      }
      const std::string name = which == 0 ? "quadric" : "cubic";
      DS_CHECK_GE(regular, 100, name + ": edges with the regular 8-point stencil");
      DS_CHECK_LE(maxErr, 1e-12, name + ": max butterfly error");
      DS_CHECK_GE(maxLinearErr, 1e-3, name + ": max midpoint error (the butterfly is better)");
    }
  }

  // --- Boundary: the 4-point rule reproduces a cubic along a straight boundary; interior
  // edges with a boundary end fall back to the midpoint.
  {
    auto f = [](double x, double y) { return 0.01 * x * x * x - 0.1 * x * x + 0.5 * y; };
    const int n = 8;
    TriangleMesh m = Grid(n, f);
    int boundaryRule = 0, midpointRule = 0;
    double maxErr = 0;
    for (int e = 0; e < static_cast<int>(m.Edges.size()); ++e)
    {
      ButterflyRule rule;
      const Vec3 p = ButterflyEdgePoint(m, e, nullptr, &rule);
      const Vec3& a = m.Points[m.Edges[e][0]];
      const Vec3& b = m.Points[m.Edges[e][1]];
      const bool onBottom = a[1] == 0 && b[1] == 0;
      const bool awayFromCorners = std::min(a[0], b[0]) >= 1 && std::max(a[0], b[0]) <= n - 1;
      if (onBottom && awayFromCorners)
      {
        DS_CHECK(rule == ButterflyRule::Boundary, "a bottom boundary edge uses the 4-point rule");
        ++boundaryRule;
        maxErr = std::max(maxErr, std::abs(p[2] - f(p[0], p[1])));
      }
      const bool interiorEdge = m.EdgeTriangles[e][1] >= 0;
      if (interiorEdge && (m.BoundaryVertex[m.Edges[e][0]] || m.BoundaryVertex[m.Edges[e][1]]))
      {
        midpointRule += rule == ButterflyRule::Midpoint ? 1 : 0;
        DS_CHECK(Norm(p - 0.5 * (a + b)) < 1e-15, "interior edge with a boundary end: midpoint");
      }
    }
    DS_CHECK(boundaryRule == n - 2, "boundary edges away from corners on the bottom row");
    DS_CHECK_LE(maxErr, 1e-12, "max 4-point error on the boundary cubic");
    DS_CHECK_GE(midpointRule, 4 * n - 4, "midpoint fallbacks next to the boundary");
  }

  // --- Zorin weights: sum 1/4 (affine with the 3/4 centre), linear precision on a
  // regular ring: sum s_j cos = 1/2, sum s_j sin = 0.
  {
    double worst = 0;
    for (int k = 3; k <= 12; ++k)
    {
      const std::vector<double> s = ZorinWeights(k);
      double sum = 0, c = 0, sn = 0;
      for (int j = 0; j < k; ++j)
      {
        sum += s[j];
        c += s[j] * std::cos(2 * kPi * j / k);
        sn += s[j] * std::sin(2 * kPi * j / k);
      }
      worst = std::max({ worst, std::abs(sum - 0.25), std::abs(c - 0.5), std::abs(sn) });
    }
    DS_CHECK_LE(worst, 1e-14, "Zorin weights: worst deviation from linear precision, k = 3..12");
  }

  // --- A plane stays planar under every rule, on an irregular tilted mesh refined
  // adaptively (greens, Zorin, boundary and midpoint rules all occur).
  {
    std::mt19937 rng(7);
    TriangleMesh m = Grid(
      10, [](double, double) { return 0.0; },
      [](int i, int j) { return (i * 7 + j * 3) % 5 == 0; });
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    for (int v = 0; v < m.NumberOfPoints(); ++v)
    {
      if (!m.BoundaryVertex[v])
      {
        m.Points[v][0] += jitter(rng);
        m.Points[v][1] += jitter(rng);
      }
    }
    auto plane = [](const Vec3& p) { return 0.3 * p[0] - 0.2 * p[1] + 1.0; };
    for (auto& p : m.Points)
    {
      p[2] = plane(p);
    }
    RedGreenRefiner rg;
    std::string err;
    DS_CHECK(rg.Initialize(m, &err), err);
    std::map<ButterflyRule, int> rules;
    for (int level = 0; level < 3; ++level)
    {
      std::vector<char> marks(m.NumberOfTriangles(), 0);
      std::uniform_real_distribution<double> u(0, 1);
      for (auto& mk : marks)
      {
        mk = u(rng) < 0.3;
      }
      const std::vector<char> greens = rg.GreenFlags();
      for (int e = 0; e < static_cast<int>(m.Edges.size()); ++e)
      {
        ButterflyRule r;
        ButterflyEdgePoint(m, e, &greens, &r);
        ++rules[r];
      }
      DS_CHECK(rg.Refine(m, marks, Prolongation::Butterfly).Ok, "refine");
    }
    double maxOff = 0;
    for (const auto& p : m.Points)
    {
      maxOff = std::max(maxOff, std::abs(p[2] - plane(p)));
    }
    DS_CHECK_LE(maxOff, 1e-12, "max distance of refined points from the plane");
    std::cout << "  rules seen: regular " << rules[ButterflyRule::Regular] << ", extraordinary "
              << rules[ButterflyRule::Extraordinary] << ", both "
              << rules[ButterflyRule::BothExtraordinary] << ", boundary "
              << rules[ButterflyRule::Boundary] << ", midpoint " << rules[ButterflyRule::Midpoint]
              << std::endl;
    DS_CHECK(rules[ButterflyRule::Regular] > 0 && rules[ButterflyRule::Extraordinary] > 0 &&
        rules[ButterflyRule::Boundary] > 0 && rules[ButterflyRule::Midpoint] > 0,
      "every rule was exercised");
  }

  // --- Green triangles in a stencil force the midpoint fallback.
  {
    TriangleMesh m = Grid(8, [](double x, double y) { return 0.05 * x * x + 0.02 * y * y; });
    int e = -1;
    for (int i = 0; i < static_cast<int>(m.Edges.size()) && e < 0; ++i)
    {
      ButterflyRule r;
      ButterflyEdgePoint(m, i, nullptr, &r);
      e = r == ButterflyRule::Regular ? i : -1;
    }
    std::vector<char> flags(m.NumberOfTriangles(), 0);
    flags[m.EdgeTriangles[e][0]] = 1;
    ButterflyRule r;
    const Vec3 p = ButterflyEdgePoint(m, e, &flags, &r);
    DS_CHECK(r == ButterflyRule::Midpoint, "flagged stencil triangle -> midpoint rule");
    DS_CHECK(Norm(p - 0.5 * (m.Points[m.Edges[e][0]] + m.Points[m.Edges[e][1]])) < 1e-15,
      "at the midpoint");
  }

  // --- Sphere: butterfly start values lie closer to the sphere than midpoints.
  {
    double rmsErr[2] = { 0, 0 };
    int counts[2] = { 0, 0 };
    for (int mode = 0; mode < 2; ++mode)
    {
      TriangleMesh m = Icosahedron();
      RedGreenRefiner rg;
      std::string err;
      rg.Initialize(m, &err);
      for (int level = 0; level < 3; ++level)
      {
        const int before = m.NumberOfPoints();
        std::vector<char> all(m.NumberOfTriangles(), 1);
        rg.Refine(m, all, mode == 0 ? Prolongation::Butterfly : Prolongation::Linear);
        dstest::CheckSurfaceInvariants(Icosahedron(), m,
          std::string(mode == 0 ? "butterfly" : "linear") + " sphere, step " +
            std::to_string(level + 1));
        for (int v = before; v < m.NumberOfPoints(); ++v)
        {
          const double d = Norm(m.Points[v]) - 1.0;
          rmsErr[mode] += d * d;
          ++counts[mode];
        }
        // Project onto the sphere so every level starts from the same kind of mesh.
        for (auto& p : m.Points)
        {
          p = (1.0 / Norm(p)) * p;
        }
      }
      rmsErr[mode] = std::sqrt(rmsErr[mode] / counts[mode]);
    }
    std::cout << "  sphere: rms radius error of new points, butterfly " << rmsErr[0] << ", linear "
              << rmsErr[1] << std::endl;
    DS_CHECK_LE(rmsErr[0], 0.25 * rmsErr[1], "butterfly rms radius error (vs 1/4 of linear)");
  }
  return dstest::Result("TestButterfly");
}

int main(int argc, char* argv[])
{
  return TestButterfly(argc, argv);
}
