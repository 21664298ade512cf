// SPDX-License-Identifier: BSD-3-Clause
// Points sampled on a torus surface (R = 32, r = 12.8 voxels). The Delaunay complex fills the
// convex hull (genus 0); removing the tetrahedra of the hole -- by ID, the way a user picks
// them in output 1, or by Alpha -- must give a closed genus-1 surface (Euler characteristic 0)
// close to the torus volume.
#include "TestDelaunaySeedUtils.h"
#include "vtkDelaunaySeedSurface.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkMath.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

#include <cmath>
#include <cstdint>

namespace
{
const double R = 32.0, r = 12.8;
const double centre[3] = { 64.0, 64.0, 64.0 };

// Deterministic jitter in [-0.5, 0.5): breaks the co-circular point sets of a regular grid.
double Jitter(std::uint32_t& state)
{
  state = state * 1664525u + 1013904223u;
  return (state >> 8) / double(1u << 24) - 0.5;
}

// Signed distance to the torus surface: < 0 inside the solid torus.
double TorusDistance(const double x[3])
{
  const double dx = x[0] - centre[0], dy = x[1] - centre[1], dz = x[2] - centre[2];
  const double rho = std::sqrt(dx * dx + dy * dy);
  return std::sqrt((rho - R) * (rho - R) + dz * dz) - r;
}
} // namespace

int main()
{
  const int nu = 56, nv = 22; // about 3.6 x 3.7 voxels between samples
  vtkNew<vtkPoints> points;
  std::uint32_t state = 12345u;
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      const double u = 2.0 * vtkMath::Pi() * (i + 0.3 * Jitter(state)) / nu;
      const double v = 2.0 * vtkMath::Pi() * (j + 0.3 * Jitter(state)) / nv;
      points->InsertNextPoint(centre[0] + (R + r * std::cos(v)) * std::cos(u),
        centre[1] + (R + r * std::cos(v)) * std::sin(u), centre[2] + r * std::sin(v));
    }
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  const double torusVolume = 2.0 * vtkMath::Pi() * vtkMath::Pi() * R * r * r;
  std::cout << "torus volume " << torusVolume << ", " << points->GetNumberOfPoints() << " points"
            << std::endl;

  vtkNew<vtkDelaunaySeedSurface> seed;
  vtkNew<dsseedtest::MessageCounter> messages;
  seed->AddObserver(vtkCommand::ErrorEvent, messages);
  seed->AddObserver(vtkCommand::WarningEvent, messages);
  seed->SetInputData(cloud);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  std::cout << "All tetrahedra (convex hull):" << std::endl;
  const auto hull = dsseedtest::Measure(seed->GetOutput());
  dsseedtest::CheckClosedManifold(hull, seed->GetOutput()->GetNumberOfPoints(), 2);

  // The user's picks: tetrahedra whose centroid lies outside the solid torus.
  vtkUnstructuredGrid* tets = seed->GetTetrahedra();
  vtkDataArray* ids = tets->GetCellData()->GetArray("TetraId");
  vtkDataArray* radius = tets->GetCellData()->GetArray("Circumradius");
  double maxInside = 0.0, minOutside = VTK_DOUBLE_MAX;
  vtkIdType picked = 0;
  for (vtkIdType c = 0; c < tets->GetNumberOfCells(); ++c)
  {
    double centroid[3] = { 0, 0, 0 };
    vtkIdType npts;
    const vtkIdType* pts;
    tets->GetCellPoints(c, npts, pts);
    for (int k = 0; k < 4; ++k)
    {
      double x[3];
      tets->GetPoint(pts[k], x);
      for (int d = 0; d < 3; ++d)
      {
        centroid[d] += 0.25 * x[d];
      }
    }
    if (TorusDistance(centroid) > 0)
    {
      seed->AddRemovedTetrahedron(static_cast<vtkIdType>(ids->GetTuple1(c)));
      ++picked;
      minOutside = std::min(minOutside, radius->GetTuple1(c));
    }
    else
    {
      maxInside = std::max(maxInside, radius->GetTuple1(c));
    }
  }
  std::cout << tets->GetNumberOfCells() << " tetrahedra, " << picked
            << " picked (centroid outside the torus); circumradius: max inside " << maxInside
            << ", min outside " << minOutside << std::endl;

  std::cout << "Hole removed by ID:" << std::endl;
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  const auto byId = dsseedtest::Measure(seed->GetOutput());
  dsseedtest::CheckClosedManifold(byId, seed->GetOutput()->GetNumberOfPoints(), 0);
  DS_CHECK_LE(std::abs(byId.MassVolume / torusVolume - 1.0), 0.10, "relative volume error (IDs)");
  vtkDataArray* removed = seed->GetTetrahedra()->GetCellData()->GetArray("Removed");
  vtkIdType flaggedById = 0;
  for (vtkIdType c = 0; c < removed->GetNumberOfTuples(); ++c)
  {
    flaggedById += removed->GetTuple1(c) == 1 ? 1 : 0;
  }
  DS_CHECK(flaggedById == picked, "every picked tetrahedron flagged Removed = 1");

  // Alpha alone: the tube's tetrahedra have circumradius about r, the hole's much more.
  std::cout << "Hole removed by Alpha = 1.25 r:" << std::endl;
  seed->RemoveAllRemovedTetrahedra();
  seed->SetAlpha(1.25 * r);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  const auto byAlpha = dsseedtest::Measure(seed->GetOutput());
  dsseedtest::CheckClosedManifold(byAlpha, seed->GetOutput()->GetNumberOfPoints(), 0);
  DS_CHECK_LE(
    std::abs(byAlpha.MassVolume / torusVolume - 1.0), 0.10, "relative volume error (Alpha)");

  // Every surface point lies on (the sampled) torus: no hull points left in the hole.
  double worst = 0.0;
  for (vtkIdType p = 0; p < seed->GetOutput()->GetNumberOfPoints(); ++p)
  {
    double x[3];
    seed->GetOutput()->GetPoint(p, x);
    worst = std::max(worst, std::abs(TorusDistance(x)));
  }
  DS_CHECK_LE(worst, 0.05, "max distance of a surface point from the torus");
  DS_CHECK(messages->Errors == 0, "no errors");
  return dstest::Result("TestDelaunaySeedTorus");
}
