// SPDX-License-Identifier: BSD-3-Clause
// Bad input must give a clear error or warning and an empty (or still valid) output, never a
// crash: no points, 3 points (now a sphere around each: one click), collinear, coplanar,
// duplicates, NaN, out-of-range IDs, every tetrahedron removed, the intensity rule without an
// image.
#include "TestDelaunaySeedUtils.h"
#include "vtkDelaunaySeedSurface.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

#include <cmath>
#include <functional>
#include <limits>

namespace
{
struct Outcome
{
  int Errors, Warnings;
  vtkIdType Triangles, Tetrahedra;
};

Outcome Run(vtkPoints* points,
  const std::function<void(vtkDelaunaySeedSurface*)>& configure = nullptr, long expectedEuler = 2)
{
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkDelaunaySeedSurface> seed;
  vtkNew<dsseedtest::MessageCounter> messages;
  seed->AddObserver(vtkCommand::ErrorEvent, messages);
  seed->AddObserver(vtkCommand::WarningEvent, messages);
  seed->SetInputData(cloud);
  if (configure)
  {
    configure(seed);
  }
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  Outcome o{ messages->Errors, messages->Warnings, seed->GetOutput()->GetNumberOfCells(),
    seed->GetTetrahedra()->GetNumberOfCells() };
  std::cout << "  -> " << o.Errors << " error(s), " << o.Warnings << " warning(s), " << o.Triangles
            << " triangles, " << o.Tetrahedra << " tetrahedra" << std::endl;
  if (o.Triangles > 0)
  {
    const auto f = dsseedtest::Measure(seed->GetOutput());
    dsseedtest::CheckClosedManifold(f, seed->GetOutput()->GetNumberOfPoints(), expectedEuler);
  }
  return o;
}

void AddCube(vtkPoints* points)
{
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        points->InsertNextPoint(10.0 * i, 10.0 * j, 10.0 * k);
}
} // namespace

int main()
{
  std::cout << "No points:" << std::endl;
  vtkNew<vtkPoints> none;
  auto o = Run(none);
  DS_CHECK(o.Errors == 1 && o.Triangles == 0 && o.Tetrahedra == 0, "no points -> error, empty");

  std::cout << "3 points:" << std::endl;
  vtkNew<vtkPoints> three;
  three->InsertNextPoint(0, 0, 0);
  three->InsertNextPoint(1, 0, 0);
  three->InsertNextPoint(0, 1, 0);
  o = Run(
    three, [](vtkDelaunaySeedSurface* s) { s->SetSeedRadius(0.4); }, 6);
  DS_CHECK(o.Errors == 0 && o.Warnings == 0 && o.Triangles == 3 * 320 && o.Tetrahedra == 0,
    "3 points -> three seed spheres (320 triangles each), no tetrahedra");
  o = Run(three, nullptr, 6); // SeedRadius 5 around points 1 apart: the spheres overlap
  DS_CHECK(o.Errors == 0 && o.Warnings == 3 && o.Triangles == 3 * 320,
    "3 close points -> a warning per overlap");

  std::cout << "The same click twice, and four picks of which two coincide:" << std::endl;
  vtkNew<vtkPoints> twice;
  twice->InsertNextPoint(5, 5, 5);
  twice->InsertNextPoint(5, 5, 5);
  o = Run(twice, nullptr, 2);
  DS_CHECK(o.Errors == 0 && o.Triangles == 320, "a repeated click -> one seed sphere");
  vtkNew<vtkPoints> fourWithRepeat;
  fourWithRepeat->InsertNextPoint(0, 0, 0);
  fourWithRepeat->InsertNextPoint(20, 0, 0);
  fourWithRepeat->InsertNextPoint(0, 20, 0);
  fourWithRepeat->InsertNextPoint(20, 0, 0);
  o = Run(fourWithRepeat, nullptr, 6);
  DS_CHECK(
    o.Errors == 0 && o.Triangles == 3 * 320, "four picks, three distinct -> three seed spheres");

  std::cout << "Collinear:" << std::endl;
  vtkNew<vtkPoints> line;
  for (int i = 0; i < 10; ++i)
  {
    line->InsertNextPoint(i, 2.0 * i, -i);
  }
  o = Run(line);
  DS_CHECK(o.Errors == 1 && o.Triangles == 0, "collinear -> error, empty");

  std::cout << "Coplanar (tilted plane):" << std::endl;
  vtkNew<vtkPoints> plane;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
    {
      const double u = i + 0.1 * ((i * 7 + j * 3) % 5), v = j + 0.1 * ((i * 2 + j * 5) % 7);
      plane->InsertNextPoint(u, v, 0.5 * u - 0.25 * v + 3.0);
    }
  o = Run(plane);
  DS_CHECK(o.Errors == 1 && o.Triangles == 0, "coplanar -> error, empty");

  std::cout << "Four identical points:" << std::endl;
  vtkNew<vtkPoints> same;
  for (int i = 0; i < 4; ++i)
  {
    same->InsertNextPoint(5, 5, 5);
  }
  o = Run(same);
  DS_CHECK(o.Errors == 0 && o.Triangles == 320,
    "four coincident points -> one seed sphere (a repeated click)");

  std::cout << "Cube corners, each twice, plus a NaN and an infinite point:" << std::endl;
  vtkNew<vtkPoints> dup;
  AddCube(dup);
  dup->InsertNextPoint(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  AddCube(dup);
  dup->InsertNextPoint(0, std::numeric_limits<double>::infinity(), 0);
  o = Run(dup);
  DS_CHECK(o.Errors == 0 && o.Warnings == 1, "non-finite points -> one warning");
  DS_CHECK(o.Triangles == 12, "duplicates merged: the cube's 12 triangles");

  std::cout << "Every tetrahedron removed by ID, plus an out-of-range ID:" << std::endl;
  vtkNew<vtkPoints> cube;
  AddCube(cube);
  o = Run(cube,
    [](vtkDelaunaySeedSurface* s)
    {
      for (vtkIdType id = 0; id < 6; ++id)
      {
        s->AddRemovedTetrahedron(id);
      }
      s->AddRemovedTetrahedron(1000);
    });
  DS_CHECK(o.Errors == 0 && o.Warnings >= 2, "warnings for empty surface and bad ID");
  DS_CHECK(o.Triangles == 0 && o.Tetrahedra > 0, "empty surface, tetrahedra still shown");

  std::cout << "UseIntensityRange without an image:" << std::endl;
  o = Run(cube, [](vtkDelaunaySeedSurface* s) { s->UseIntensityRangeOn(); });
  DS_CHECK(o.Errors == 0 && o.Warnings == 1 && o.Triangles == 12, "warning, rule skipped");

  std::cout << "One click at the largest coordinates (the seed sphere would overflow):"
            << std::endl;
  vtkNew<vtkPoints> huge;
  huge->SetDataTypeToDouble();
  huge->InsertNextPoint(-std::numeric_limits<double>::max(), 0, 0);
  o = Run(huge);
  DS_CHECK(o.Errors == 1 && o.Triangles == 0,
    "overflowing coordinates -> error, empty (no infinite points)");

  std::cout << "Cube corners plus a point at z = 1.7e308 (vtkDelaunay3D's bounds would overflow):"
            << std::endl;
  vtkNew<vtkPoints> far;
  far->SetDataTypeToDouble();
  AddCube(far);
  far->InsertNextPoint(2, 6, 1.7e308);
  o = Run(far);
  DS_CHECK(o.Errors == 0 && o.Warnings == 1 && o.Triangles == 12,
    "out-of-range point dropped with a warning: the cube");

  // The input is never modified in place.
  DS_CHECK(dup->GetNumberOfPoints() == 18, "input untouched");
  return dstest::Result("TestDelaunaySeedBadInput");
}
