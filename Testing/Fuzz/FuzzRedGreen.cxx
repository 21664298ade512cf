// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: red-green refinement (dsurf::RedGreenRefiner, docs/METHOD.md §6.3-6.4).
//
// The input picks a small closed mesh (tetrahedron, cube, icosahedron, a torus of
// n x m quads, two disjoint tetrahedra), scrambles its connectivity by random edge flips (each
// keeps a closed 2-manifold) and jitters its points; or, in one case of eight, it lists
// triangles of its own over up to 12 points (often non-manifold: Initialize() must say so).
// Then up to six rounds of random marks, each with butterfly or linear prolongation and the
// points moved between rounds, as the solver does. After every step the refiner's promises:
// the step succeeds; the topology invariants of the start hold (closed stays closed, manifold,
// oriented, Euler characteristic unchanged); no T-vertex; the labels follow the greens; old
// points keep index and position; new points are finite.
#include "FuzzCheck.h"
#include "TestSolverMeshes.h"
#include "dsRedGreen.h"

#include <fuzzer/FuzzedDataProvider.h>

#include <set>

using dsurf::TriangleMesh;
using dsurf::Vec3;

namespace
{
TriangleMesh Tetrahedron(double shift)
{
  TriangleMesh m;
  m.Points = { { shift, 0, 0 }, { shift + 1, 0, 0 }, { shift, 1, 0 }, { shift, 0, 1 } };
  m.Triangles = { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } };
  return m;
}

/// A torus of n x m quads (n, m >= 3), each split in two (Euler characteristic 0).
TriangleMesh Torus(int n, int m)
{
  TriangleMesh t;
  for (int j = 0; j < m; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      t.Points.push_back(
        { (2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v) });
    }
  }
  auto id = [n, m](int i, int j) { return (j % m) * n + (i % n); };
  for (int j = 0; j < m; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      t.Triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      t.Triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  }
  return t;
}

TriangleMesh ClosedMesh(FuzzedDataProvider& in)
{
  switch (in.ConsumeIntegralInRange(0, 4))
  {
    case 0:
      return Tetrahedron(0);
    case 1:
      return dstest::MakeCubeSurface(in.ConsumeIntegralInRange(0, 1), 1.0, { 0, 0, 0 });
    case 2:
      return dstest::MakeIcosphere(0, 1.0, { 0, 0, 0 });
    case 3:
      return Torus(in.ConsumeIntegralInRange(3, 6), in.ConsumeIntegralInRange(3, 6));
    default:
    {
      TriangleMesh a = Tetrahedron(0), b = Tetrahedron(3);
      for (auto tri : b.Triangles)
      {
        a.Triangles.push_back({ tri[0] + 4, tri[1] + 4, tri[2] + 4 });
      }
      a.Points.insert(a.Points.end(), b.Points.begin(), b.Points.end());
      return a;
    }
  }
}

/// Flips the edge shared by triangles (a, b, c) and (b, a, d) into (a, d, c), (d, b, c) when c-d is
/// not an edge yet: the mesh stays a closed, oriented 2-manifold.
void FlipEdges(TriangleMesh& m, FuzzedDataProvider& in)
{
  const int flips = in.ConsumeIntegralInRange(0, 12);
  for (int f = 0; f < flips; ++f)
  {
    std::string error;
    if (!m.BuildTopology(&error))
    {
      return;
    }
    const int e = in.ConsumeIntegralInRange(0, static_cast<int>(m.Edges.size()) - 1);
    const int t0 = m.EdgeTriangles[e][0], t1 = m.EdgeTriangles[e][1];
    if (t0 < 0 || t1 < 0)
    {
      continue;
    }
    // Rotate t0 so that it reads (a, b, c) with (a, b) the edge; t1 then reads (b, a, d).
    std::array<int, 3> A = m.Triangles[t0], B = m.Triangles[t1];
    const int ea = m.Edges[e][0], eb = m.Edges[e][1];
    while (!((A[0] == ea && A[1] == eb) || (A[0] == eb && A[1] == ea)))
    {
      A = { A[1], A[2], A[0] };
    }
    const int a = A[0], b = A[1], c = A[2];
    int d = -1;
    for (int v : B)
    {
      d = (v != a && v != b) ? v : d;
    }
    if (d < 0 || c == d || m.FindEdge(c, d) >= 0)
    {
      continue;
    }
    m.Triangles[t0] = { a, d, c };
    m.Triangles[t1] = { d, b, c };
  }
}

/// Triangles of the input's own over up to 12 points: any connectivity at all.
TriangleMesh ListedMesh(FuzzedDataProvider& in)
{
  TriangleMesh m;
  const int nPoints = in.ConsumeIntegralInRange(3, 12);
  for (int i = 0; i < nPoints; ++i)
  {
    m.Points.push_back({ std::cos(i * 1.3), std::sin(i * 0.7), std::cos(i * 2.1) });
  }
  const int nTriangles = in.ConsumeIntegralInRange(1, 24);
  for (int t = 0; t < nTriangles; ++t)
  {
    std::array<int, 3> tri;
    for (int& v : tri)
    {
      v = in.ConsumeIntegralInRange(0, nPoints - 1);
    }
    m.Triangles.push_back(tri);
  }
  return m;
}

void Jitter(std::vector<Vec3>& points, FuzzedDataProvider& in, double amount)
{
  for (auto& p : points)
  {
    for (double& x : p)
    {
      x += amount * (in.ConsumeProbability<double>() - 0.5);
    }
  }
}

/// The labels rederived from the refiner's green pairs: M over C over D over N.
void CheckLabels(const dsurf::RedGreenRefiner& rg, const TriangleMesh& m)
{
  std::vector<unsigned char> expect(m.Points.size(), dsurf::LabelN);
  auto raise = [&expect](int v, unsigned char label)
  {
    static const int rank[4] = { 0, 2, 3, 1 }; // N, C, M, D
    if (rank[label] > rank[expect[v]])
    {
      expect[v] = label;
    }
  };
  for (int t = 0; t < m.NumberOfTriangles(); ++t)
  {
    std::array<int, 3> parent;
    int corner, mid;
    if (rg.GetGreen(t, parent, corner, mid))
    {
      raise(mid, dsurf::LabelM);
      raise(parent[corner], dsurf::LabelC);
      raise(parent[(corner + 1) % 3], dsurf::LabelC);
      raise(parent[(corner + 2) % 3], dsurf::LabelD);
    }
  }
  FUZZ_CHECK(m.Labels == expect, "the labels follow the green pairs");
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzedDataProvider in(data, size);
  const bool listed = in.ConsumeIntegralInRange(0, 7) == 0;
  TriangleMesh mesh;
  if (listed)
  {
    mesh = ListedMesh(in);
  }
  else
  {
    mesh = ClosedMesh(in);
    FlipEdges(mesh, in);
    Jitter(mesh.Points, in, 0.3);
  }

  dsurf::RedGreenRefiner rg;
  std::string error;
  if (!rg.Initialize(mesh, &error))
  {
    FUZZ_CHECK(listed, "a closed 2-manifold is accepted: " + error);
    FUZZ_CHECK(!error.empty(), "a rejected mesh comes with a message");
    return 0;
  }
  // What the start is, the refinement must keep (CheckTopologyInvariants, docs/METHOD.md §6.3).
  const int euler = mesh.EulerCharacteristic();
  const bool closed = mesh.IsClosed();
  const bool wellFormed = dsurf::CheckTopologyInvariants(mesh, euler, closed, &error);
  FUZZ_CHECK(listed || (wellFormed && closed), "the start is a closed 2-manifold: " + error);

  const int rounds = in.ConsumeIntegralInRange(1, 6);
  for (int round = 0; round < rounds && mesh.NumberOfTriangles() < 4000; ++round)
  {
    std::vector<char> marks(mesh.Triangles.size(), 0);
    const double density = in.ConsumeProbability<double>();
    for (auto& mark : marks)
    {
      mark = in.ConsumeProbability<double>() < density ? 1 : 0;
    }
    const auto mode =
      in.ConsumeBool() ? dsurf::Prolongation::Butterfly : dsurf::Prolongation::Linear;
    const std::vector<Vec3> before = mesh.Points;
    const dsurf::RefinementCounts counts = rg.Refine(mesh, marks, mode);
    FUZZ_CHECK(counts.Ok, "the step succeeds: " + counts.Error);
    FUZZ_CHECK(rg.CountTVertices(mesh) == 0, "no T-vertex");
    FUZZ_CHECK(mesh.Labels.size() == mesh.Points.size() && mesh.Levels.size() == mesh.Points.size(),
      "one label and level per point");
    CheckLabels(rg, mesh);
    FUZZ_CHECK(std::equal(before.begin(), before.end(), mesh.Points.begin()),
      "old points keep their index and position");
    FUZZ_CHECK(counts.NewVertices == mesh.NumberOfPoints() - static_cast<int>(before.size()),
      "NewVertices counts the appended points");
    FUZZ_CHECK(fuzzcheck::AllFinite(mesh), "new points are finite");
    if (wellFormed)
    {
      FUZZ_CHECK(dsurf::CheckTopologyInvariants(mesh, euler, closed, &error), error);
    }
    Jitter(mesh.Points, in, 0.05); // the solver moves points between refinements
  }
  return 0;
}
