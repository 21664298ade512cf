// SPDX-License-Identifier: BSD-3-Clause
// 8 corners of a cube -> a 12-triangle closed surface with outward normals and the cube's
// volume; output 1 lists the tetrahedra with stable IDs; TargetEdgeLength refines it.
#include "TestDelaunaySeedUtils.h"
#include "vtkDelaunaySeedSurface.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkMath.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTetra.h"
#include "vtkUnstructuredGrid.h"

#include <cmath>

int main()
{
  const double side = 10.0;
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        points->InsertNextPoint(3.0 + side * i, -2.0 + side * j, 1.0 + side * k);
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);

  vtkNew<vtkDelaunaySeedSurface> seed;
  vtkNew<dsseedtest::MessageCounter> messages;
  seed->AddObserver(vtkCommand::ErrorEvent, messages);
  seed->SetInputData(cloud);
  dstest::UpdateWithInputsUnchanged(seed, "seed");

  std::cout << "Cube corners:" << std::endl;
  vtkPolyData* surface = seed->GetOutput();
  const auto f = dsseedtest::Measure(surface);
  dsseedtest::CheckClosedManifold(f, surface->GetNumberOfPoints(), 2);
  DS_CHECK(f.Triangles == 12, "12 triangles, got " + std::to_string(f.Triangles));
  DS_CHECK(f.UsedPoints == 8, "8 points");
  DS_CHECK_LE(std::abs(f.SignedVolume - 1000.0), 1e-6, "|signed volume - 1000|");
  DS_CHECK_LE(std::abs(f.MassVolume - 1000.0), 1e-6, "|mass volume - 1000|");
  DS_CHECK(messages->Errors == 0, "no errors");

  vtkUnstructuredGrid* tets = seed->GetTetrahedra();
  vtkDataArray* ids = tets->GetCellData()->GetArray("TetraId");
  vtkDataArray* removed = tets->GetCellData()->GetArray("Removed");
  DS_CHECK(
    ids && removed && tets->GetCellData()->GetArray("Circumradius"), "output 1 arrays exist");
  std::cout << "  tetrahedra: " << tets->GetNumberOfCells() << std::endl;
  DS_CHECK(tets->GetNumberOfCells() >= 5, "at least 5 tetrahedra");
  double tetVolume = 0.0;
  for (vtkIdType c = 0; ids && removed && c < tets->GetNumberOfCells(); ++c)
  {
    DS_CHECK(ids->GetTuple1(c) == c, "TetraId is the cell index");
    double x[4][3];
    for (int k = 0; k < 4; ++k)
    {
      tets->GetPoint(tets->GetCell(c)->GetPointId(k), x[k]);
    }
    tetVolume +=
      removed->GetTuple1(c) == 0 ? std::abs(vtkTetra::ComputeVolume(x[0], x[1], x[2], x[3])) : 0.0;
  }
  DS_CHECK_LE(std::abs(tetVolume - 1000.0), 1e-6, "|volume of kept tetrahedra - 1000|");

  // The circumradius of every cube tetrahedron is half the space diagonal: Alpha just below
  // it removes all of them (empty surface, a warning), just above keeps all.
  std::cout << "Alpha below the circumradius (expect a warning and an empty surface):" << std::endl;
  vtkNew<dsseedtest::MessageCounter> alphaMessages;
  seed->AddObserver(vtkCommand::WarningEvent, alphaMessages);
  seed->SetAlpha(0.5 * side * std::sqrt(3.0) * 0.99);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  DS_CHECK(seed->GetOutput()->GetNumberOfCells() == 0, "all removed -> empty surface");
  DS_CHECK(alphaMessages->Warnings >= 1, "a warning for the empty surface");
  seed->SetAlpha(0.5 * side * std::sqrt(3.0) * 1.01);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  DS_CHECK(seed->GetOutput()->GetNumberOfCells() == 12, "alpha above circumradius keeps the cube");

  // Subdivision: about 2.5 units per edge, still closed, same volume (faces are planar).
  std::cout << "TargetEdgeLength 2.5:" << std::endl;
  seed->SetAlpha(0.0);
  seed->SetTargetEdgeLength(2.5);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  const auto g = dsseedtest::Measure(seed->GetOutput());
  dsseedtest::CheckClosedManifold(g, seed->GetOutput()->GetNumberOfPoints(), 2);
  double sum = 0.0;
  vtkIdType n = 0;
  vtkNew<vtkIdList> tri;
  auto polys = seed->GetOutput()->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(tri);)
  {
    for (int j = 0; j < 3; ++j)
    {
      double a[3], b[3];
      seed->GetOutput()->GetPoint(tri->GetId(j), a);
      seed->GetOutput()->GetPoint(tri->GetId((j + 1) % 3), b);
      sum += std::sqrt(vtkMath::Distance2BetweenPoints(a, b));
      ++n;
    }
  }
  const double mean = sum / n;
  DS_CHECK_LE(mean, 2.5 * std::sqrt(2.0), "mean edge length after subdivision");
  DS_CHECK_GE(mean, 2.5 / std::sqrt(2.0), "mean edge length after subdivision");
  DS_CHECK_LE(std::abs(g.MassVolume - 1000.0), 1e-6, "|subdivided volume - 1000|");
  return dstest::Result("TestDelaunaySeedCube");
}
