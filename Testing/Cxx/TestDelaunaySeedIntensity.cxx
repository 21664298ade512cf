// SPDX-License-Identifier: BSD-3-Clause
// IntensityRange on a phantom: a bright ball (100, radius 20) in a dark volume (0), seed points
// on a sphere of radius 18 inside it and on a box around it. [50, 1000] must keep exactly the
// tetrahedra inside the ball (a bright object); [-10, 50] the shell between ball and box (a dark
// region around a bright one: two closed surfaces, the inner one oriented into the ball).
#include "TestDelaunaySeedUtils.h"
#include "vtkDelaunaySeedSurface.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

#include <cmath>

namespace
{
const double c[3] = { 32.0, 30.0, 33.0 };
// The user picks points just inside the visible edge of the object (radius 20): picks on the
// edge itself would give slivers whose centroids sit on the partial-volume boundary, where the
// image value is anyone's guess.
const double objectRadius = 20.0, ballRadius = 18.0, boxHalf = 29.0;
double Radius(const double x[3])
{
  return std::sqrt(vtkMath::Distance2BetweenPoints(x, c));
}
}

int main()
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(64, 64, 64);
  image->SetSpacing(1.0, 1.0, 1.0);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(64 * 64 * 64);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    double x[3];
    image->GetPoint(i, x);
    values->SetValue(i, Radius(x) <= objectRadius ? 100.0f : 0.0f);
  }
  image->GetPointData()->SetScalars(values);

  vtkNew<vtkPoints> points;
  const int nBall = 400; // Fibonacci sphere
  for (int i = 0; i < nBall; ++i)
  {
    const double z = 1.0 - (2.0 * i + 1.0) / nBall, rho = std::sqrt(1.0 - z * z);
    const double phi = i * vtkMath::Pi() * (3.0 - std::sqrt(5.0));
    points->InsertNextPoint(c[0] + ballRadius * rho * std::cos(phi),
      c[1] + ballRadius * rho * std::sin(phi), c[2] + ballRadius * z);
  }
  const int nb = 7; // box faces, slightly perturbed so the grid is not co-spherical
  for (int i = 0; i <= nb; ++i)
    for (int j = 0; j <= nb; ++j)
      for (int k = 0; k <= nb; ++k)
      {
        if (i != 0 && i != nb && j != 0 && j != nb && k != 0 && k != nb)
        {
          continue;
        }
        const double t = 0.013 * ((i * 7 + j * 3 + k * 5) % 11);
        points->InsertNextPoint(c[0] - boxHalf + 2 * boxHalf * i / nb + t,
          c[1] - boxHalf + 2 * boxHalf * j / nb - t,
          c[2] - boxHalf + 2 * boxHalf * k / nb + 0.5 * t);
      }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  const double ballVolume = 4.0 / 3.0 * vtkMath::Pi() * std::pow(ballRadius, 3);
  const double boxVolume = std::pow(2 * boxHalf, 3);

  vtkNew<vtkDelaunaySeedSurface> seed;
  vtkNew<dsseedtest::MessageCounter> messages;
  seed->AddObserver(vtkCommand::ErrorEvent, messages);
  seed->AddObserver(vtkCommand::WarningEvent, messages);
  seed->SetInputData(cloud);
  seed->SetImageData(image);
  seed->UseIntensityRangeOn();
  seed->SetIntensityRange(50.0, 1000.0);
  dstest::UpdateWithInputsUnchanged(seed, "seed");

  std::cout << "Bright ball, IntensityRange [50, 1000]:" << std::endl;
  const auto ball = dsseedtest::Measure(seed->GetOutput());
  dsseedtest::CheckClosedManifold(ball, seed->GetOutput()->GetNumberOfPoints(), 2);
  DS_CHECK_LE(ball.MassVolume / ballVolume, 1.0, "surface volume / ball volume");
  DS_CHECK_GE(ball.MassVolume / ballVolume, 0.95, "surface volume / ball volume");
  double maxOff = 0.0;
  for (vtkIdType p = 0; p < seed->GetOutput()->GetNumberOfPoints(); ++p)
  {
    double x[3];
    seed->GetOutput()->GetPoint(p, x);
    maxOff = std::max(maxOff, std::abs(Radius(x) - ballRadius));
  }
  DS_CHECK_LE(maxOff, 1e-4, "max |radius - 18| of surface points (no box point used; float input)");

  // Per tetrahedron: kept <=> all four corners on the ball.
  vtkUnstructuredGrid* tets = seed->GetTetrahedra();
  vtkDataArray* removed = tets->GetCellData()->GetArray("Removed");
  vtkDataArray* centroidValue = tets->GetCellData()->GetArray("CentroidValue");
  DS_CHECK(centroidValue != nullptr, "CentroidValue array present");
  vtkIdType keptWithBoxCorner = 0, removedInside = 0, kept = 0;
  for (vtkIdType t = 0; t < tets->GetNumberOfCells(); ++t)
  {
    vtkIdType npts;
    const vtkIdType* pts;
    tets->GetCellPoints(t, npts, pts);
    bool allOnBall = true;
    for (int k = 0; k < 4; ++k)
    {
      allOnBall = allOnBall && pts[k] < nBall;
    }
    const int flag = static_cast<int>(removed->GetTuple1(t));
    kept += flag == 0 ? 1 : 0;
    keptWithBoxCorner += (flag == 0 && !allOnBall) ? 1 : 0;
    removedInside += (flag == 3 && allOnBall) ? 1 : 0;
  }
  std::cout << "  " << tets->GetNumberOfCells() << " tetrahedra, " << kept
            << " kept; kept with a box corner " << keptWithBoxCorner
            << ", removed with all corners on the ball " << removedInside << std::endl;
  DS_CHECK(keptWithBoxCorner == 0, "no kept tetrahedron reaches the box");
  DS_CHECK(removedInside == 0, "no tetrahedron inside the ball removed");

  std::cout << "Dark shell, IntensityRange [-10, 50]:" << std::endl;
  seed->SetIntensityRange(-10.0, 50.0);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  const auto shell = dsseedtest::Measure(seed->GetOutput());
  // Box surface and ball surface: two spheres topologically, Euler 4.
  dsseedtest::CheckClosedManifold(shell, seed->GetOutput()->GetNumberOfPoints(), 4);
  DS_CHECK_LE(std::abs(shell.MassVolume / (boxVolume - ball.MassVolume) - 1.0), 0.02,
    "shell volume vs box - ball surface volume");
  DS_CHECK(messages->Errors == 0, "no errors");
  return dstest::Result("TestDelaunaySeedIntensity");
}
