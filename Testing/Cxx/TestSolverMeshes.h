// SPDX-License-Identifier: BSD-3-Clause
// Meshes shared by the solver tests and the solver benchmark: an icosphere, a
// subdivided cube surface (the paper's 12 288 / 49 152 triangle test meshes), a flat
// equilateral sheet and a height field over a regular grid.
#ifndef TestSolverMeshes_h
#define TestSolverMeshes_h

#include "dsSolver.h"
#include "dsTriangleMesh.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <utility>
#include <vector>

namespace dstest
{
using dsurf::Vec3;
using dsurf::operator+;
using dsurf::operator-;
using dsurf::operator*;

/// Split every triangle into four; new points by `place(a, b)`.
template <typename Place>
inline void Subdivide(std::vector<Vec3>& p, std::vector<std::array<int, 3>>& f, Place place)
{
  std::map<std::pair<int, int>, int> mid;
  auto midpoint = [&](int a, int b)
  {
    auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = mid.find(key);
    if (it != mid.end())
    {
      return it->second;
    }
    p.push_back(place(p[a], p[b]));
    mid[key] = static_cast<int>(p.size()) - 1;
    return static_cast<int>(p.size()) - 1;
  };
  std::vector<std::array<int, 3>> g;
  g.reserve(f.size() * 4);
  for (auto& tri : f)
  {
    const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]),
              d = midpoint(tri[2], tri[0]);
    g.push_back({ tri[0], a, d });
    g.push_back({ tri[1], b, a });
    g.push_back({ tri[2], d, b });
    g.push_back({ a, b, d });
  }
  f.swap(g);
}

/// Icosphere of the given radius around c, `levels` midpoint subdivisions, outward.
inline dsurf::TriangleMesh MakeIcosphere(int levels, double radius, const Vec3& c)
{
  dsurf::TriangleMesh m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> p = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t },
    { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 },
    { -t, 0, 1 } };
  std::vector<std::array<int, 3>> f = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 },
    { 0, 10, 11 }, { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 },
    { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 },
    { 8, 6, 7 }, { 9, 8, 1 } };
  for (auto& x : p)
  {
    x = (1.0 / dsurf::Norm(x)) * x;
  }
  for (int l = 0; l < levels; ++l)
  {
    Subdivide(p, f,
      [](const Vec3& a, const Vec3& b)
      {
        const Vec3 x = 0.5 * (a + b);
        return (1.0 / dsurf::Norm(x)) * x;
      });
  }
  for (auto& x : p)
  {
    m.Points.push_back(c + radius * x);
  }
  m.Triangles = f;
  return m;
}

/// The surface of the axis-aligned cube [c - s, c + s]^3: 12 outward triangles, then
/// `levels` midpoint subdivisions (5 -> 12 288 triangles, 6 -> 49 152).
inline dsurf::TriangleMesh MakeCubeSurface(int levels, double s, const Vec3& c)
{
  std::vector<Vec3> p;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        p.push_back({ c[0] + (i ? s : -s), c[1] + (j ? s : -s), c[2] + (k ? s : -s) });
  // Quads (outward, counter-clockwise seen from outside), two triangles each.
  const int quads[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  std::vector<std::array<int, 3>> f;
  for (const auto& q : quads)
  {
    f.push_back({ q[0], q[1], q[2] });
    f.push_back({ q[0], q[2], q[3] });
  }
  for (int l = 0; l < levels; ++l)
  {
    Subdivide(p, f, [](const Vec3& a, const Vec3& b) { return 0.5 * (a + b); });
  }
  dsurf::TriangleMesh m;
  m.Points = p;
  m.Triangles = f;
  return m;
}
/// Regular grid of n x n unit squares, each split by its diagonal (i,j)-(i+1,j+1) (interior
/// valence 6), z = height(x, y); flipped(i, j) true takes the other diagonal in that square
/// (valences 4, 5, 7, 8 appear). An open disc; topology not built.
inline dsurf::TriangleMesh HeightGrid(int n, const std::function<double(double, double)>& height,
  const std::function<bool(int, int)>& flipped = nullptr)
{
  dsurf::TriangleMesh m;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      m.Points.push_back({ double(i), double(j), height(i, j) });
    }
  }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      if (flipped && flipped(i, j))
      {
        m.Triangles.push_back({ id(i, j), id(i + 1, j), id(i, j + 1) });
        m.Triangles.push_back({ id(i + 1, j), id(i + 1, j + 1), id(i, j + 1) });
      }
      else
      {
        m.Triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
        m.Triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
      }
    }
  }
  return m;
}

/// Equilateral triangle grid (n x n points, unit edges), a flat open sheet.
inline dsurf::TriangleMesh EquilateralSheet(int n)
{
  dsurf::TriangleMesh m;
  const double s = std::sqrt(3.0) / 2.0;
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      m.Points.push_back({ i + 0.5 * (j % 2), j * s, 0.0 });
    }
  }
  auto id = [n](int i, int j) { return j * n + i; };
  for (int j = 0; j + 1 < n; ++j)
  {
    for (int i = 0; i + 1 < n; ++i)
    {
      if (j % 2 == 0)
      {
        m.Triangles.push_back({ id(i, j), id(i + 1, j), id(i, j + 1) });
        m.Triangles.push_back({ id(i + 1, j), id(i + 1, j + 1), id(i, j + 1) });
      }
      else
      {
        m.Triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
        m.Triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      }
    }
  }
  return m;
}

/// `sweeps` solver sweeps on m with no external force (a flat sheet has nowhere to go: every
/// movement is drift), with the docs/METHOD.md §6.4 weights or all weights 1.
inline void SweepWithoutForce(dsurf::TriangleMesh& m, bool useLabelWeights, int sweeps)
{
  dsurf::Solver solver;
  dsurf::SolverParameters sp;
  sp.UseLabelWeights = useLabelWeights;
  solver.SetParameters(sp);
  solver.SetMesh(&m);
  solver.SetForceField(nullptr, 0.0);
  solver.Sweeps(sweeps, [](const dsurf::SweepStatistics&) { return true; });
}

/// The triangles of a polydata as a mesh (ids as they are); no topology built.
inline dsurf::TriangleMesh FromPolyData(vtkPolyData* polyData)
{
  dsurf::TriangleMesh m;
  for (vtkIdType i = 0; i < polyData->GetNumberOfPoints(); ++i)
  {
    dsurf::Vec3 x;
    polyData->GetPoint(i, x.data());
    m.Points.push_back(x);
  }
  vtkCellArray* polys = polyData->GetPolys();
  polys->InitTraversal();
  vtkIdType n;
  const vtkIdType* ids;
  while (polys->GetNextCell(n, ids))
  {
    m.Triangles.push_back(
      { static_cast<int>(ids[0]), static_cast<int>(ids[1]), static_cast<int>(ids[2]) });
  }
  return m;
}

/// The core mesh as a vtkPolyData of triangles (a filter's initial surface).
inline vtkSmartPointer<vtkPolyData> ToPolyData(const dsurf::TriangleMesh& m)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  for (const auto& x : m.Points)
  {
    pts->InsertNextPoint(x.data());
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& t : m.Triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    polys->InsertNextCell(3, ids);
  }
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  return pd;
}

/// Three triangles on one edge from `corner` to corner + (4, 0, 0): a non-manifold fin, the
/// start surface the filter must refuse.
inline vtkSmartPointer<vtkPolyData> MakeFin(const dsurf::Vec3& corner)
{
  dsurf::TriangleMesh m;
  for (const dsurf::Vec3& d : { dsurf::Vec3{ 0, 0, 0 }, dsurf::Vec3{ 4, 0, 0 },
         dsurf::Vec3{ 2, 4, 0 }, dsurf::Vec3{ 2, -4, 0 }, dsurf::Vec3{ 2, 0, 4 } })
  {
    m.Points.push_back(corner + d);
  }
  m.Triangles = { { 0, 1, 2 }, { 0, 1, 3 }, { 0, 1, 4 } };
  return ToPolyData(m);
}
} // namespace dstest

#endif
