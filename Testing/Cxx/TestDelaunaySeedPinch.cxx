// SPDX-License-Identifier: BSD-3-Clause
// Pinch resolution in the core (dsurf::ExtractSeedBoundary) on hand-made complexes:
// two tetrahedra sharing a vertex, two sharing an edge, and a ring of tetrahedra around an
// edge with alternate ones removed. Each must give closed, manifold, outward surfaces with the
// copies of the split vertices moved apart.
#include "TestDelaunaySeedUtils.h"
#include "dsSeedSurface.h"

#include "vtkCellArray.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cmath>

namespace
{
vtkSmartPointer<vtkPolyData> ToPolyData(const dsurf::SeedSurface& s)
{
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  for (const auto& p : s.Points)
  {
    pts->InsertNextPoint(p.data());
  }
  vtkNew<vtkCellArray> tris;
  for (const auto& t : s.Triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    tris->InsertNextCell(3, ids);
  }
  poly->SetPoints(pts);
  poly->SetPolys(tris);
  return poly;
}

double MinCopyDistance(const dsurf::SeedSurface& s)
{
  double best = 1e300;
  for (std::size_t a = 0; a < s.Points.size(); ++a)
    for (std::size_t b = a + 1; b < s.Points.size(); ++b)
      if (s.SourcePoint[a] == s.SourcePoint[b])
      {
        const double d = std::sqrt(std::pow(s.Points[a][0] - s.Points[b][0], 2) +
          std::pow(s.Points[a][1] - s.Points[b][1], 2) +
          std::pow(s.Points[a][2] - s.Points[b][2], 2));
        best = std::min(best, d);
      }
  return best;
}
} // namespace

int main()
{
  {
    std::cout << "Two tetrahedra sharing vertex 0:" << std::endl;
    std::vector<dsurf::Vec3> p = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { -1, 0, 0 },
      { 0, -1, 0 }, { 0, 0, -1 } };
    std::vector<dsurf::SeedTet> t = { { 0, 1, 2, 3 }, { 0, 4, 6, 5 } };
    std::vector<unsigned char> status(2, dsurf::SeedKept);
    dsurf::SeedBoundaryReport report;
    auto s = dsurf::ExtractSeedBoundary(p, t, status, 1e-12, report);
    std::cout << "  " << report.Summary() << std::endl;
    auto poly = ToPolyData(s);
    const auto f = dsseedtest::Measure(poly);
    dsseedtest::CheckClosedManifold(f, poly->GetNumberOfPoints(), 4);
    DS_CHECK(report.PinchedVertices == 1 && report.VertexCopiesAdded == 1, "one vertex split once");
    DS_CHECK(report.Components == 2, "two components");
    DS_CHECK_GE(MinCopyDistance(s), 1e-3, "distance between the copies of the split vertex");
    DS_CHECK_LE(std::abs(f.SignedVolume - 2.0 / 6.0), 0.02, "|volume - 1/3|");
  }
  {
    std::cout << "Two tetrahedra sharing edge 0-1:" << std::endl;
    std::vector<dsurf::Vec3> p = { { 0, 0, 0 }, { 0, 0, 1 }, { 1, 0, 0 }, { 0.5, 1, 0.5 },
      { -1, 0, 0 }, { -0.5, -1, 0.5 } };
    std::vector<dsurf::SeedTet> t = { { 0, 1, 2, 3 }, { 0, 1, 4, 5 } };
    std::vector<unsigned char> status(2, dsurf::SeedKept);
    dsurf::SeedBoundaryReport report;
    auto s = dsurf::ExtractSeedBoundary(p, t, status, 1e-12, report);
    std::cout << "  " << report.Summary() << std::endl;
    auto poly = ToPolyData(s);
    const auto f = dsseedtest::Measure(poly);
    dsseedtest::CheckClosedManifold(f, poly->GetNumberOfPoints(), 4);
    DS_CHECK(
      report.PinchedEdges == 1 && report.PinchedVertices == 2, "one edge, two vertices pinched");
    DS_CHECK(report.PinchTetsRemoved == 0, "resolved without removing tetrahedra");
  }
  {
    // Eight tetrahedra around the z axis (edge 0-1), alternate ones kept: four solid wedges
    // meet along the edge, eight boundary faces use it.
    std::cout << "Four wedges around one edge:" << std::endl;
    std::vector<dsurf::Vec3> p = { { 0, 0, -1 }, { 0, 0, 1 } };
    for (int i = 0; i < 8; ++i)
    {
      const double a = 2.0 * 3.14159265358979 * i / 8;
      p.push_back({ std::cos(a), std::sin(a), 0.0 });
    }
    std::vector<dsurf::SeedTet> t;
    for (int i = 0; i < 8; ++i)
    {
      t.push_back({ 0, 1, 2 + i, 2 + (i + 1) % 8 });
    }
    std::vector<unsigned char> status(8, dsurf::SeedKept);
    for (int i = 1; i < 8; i += 2)
    {
      status[i] = dsurf::SeedRemovedById;
    }
    dsurf::SeedBoundaryReport report;
    auto s = dsurf::ExtractSeedBoundary(p, t, status, 1e-12, report);
    std::cout << "  " << report.Summary() << std::endl;
    auto poly = ToPolyData(s);
    const auto f = dsseedtest::Measure(poly);
    dsseedtest::CheckClosedManifold(f, poly->GetNumberOfPoints(), 8);
    DS_CHECK(report.PinchedEdges == 1, "one pinched edge (8 faces)");
    DS_CHECK(report.Components == 4, "four components");
    // All kept: the octahedron-like double pyramid, no pinch at all.
    std::fill(status.begin(), status.end(), dsurf::SeedKept);
    s = dsurf::ExtractSeedBoundary(p, t, status, 1e-12, report);
    auto whole = ToPolyData(s);
    const auto g = dsseedtest::Measure(whole);
    dsseedtest::CheckClosedManifold(g, whole->GetNumberOfPoints(), 2);
    DS_CHECK(report.Summary().empty(), "nothing to report");
  }
  {
    std::cout << "A flat tetrahedron on top of a solid one is peeled off:" << std::endl;
    std::vector<dsurf::Vec3> p = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, -1 },
      { 1, 1, 0 } };
    std::vector<dsurf::SeedTet> t = { { 0, 1, 2, 3 }, { 0, 1, 2, 4 } };
    std::vector<unsigned char> status(2, dsurf::SeedKept);
    dsurf::SeedBoundaryReport report;
    auto s = dsurf::ExtractSeedBoundary(p, t, status, 1e-12, report);
    auto poly = ToPolyData(s);
    const auto f = dsseedtest::Measure(poly);
    dsseedtest::CheckClosedManifold(f, poly->GetNumberOfPoints(), 2);
    DS_CHECK(status[1] == dsurf::SeedRemovedDegenerate && f.Triangles == 4,
      "flat one removed, 4 triangles");
  }
  return dstest::Result("TestDelaunaySeedPinch");
}
