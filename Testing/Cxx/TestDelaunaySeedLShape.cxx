// SPDX-License-Identifier: BSD-3-Clause
// An L-shaped prism sampled on its surface: the Delaunay complex fills the convex hull (40%
// more volume than the L); Alpha must carve the notch and give a closed surface of the L's
// volume within 10%.
#include "TestDelaunaySeedUtils.h"
#include "vtkDelaunaySeedSurface.h"

#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace
{
const double armLength = 45.0, armWidth = 15.0, height = 15.0;

double Jitter(std::uint32_t& state)
{
  state = state * 1664525u + 1013904223u;
  return (state >> 8) / double(1u << 24) - 0.5;
}

bool InOpenL(double x, double y)
{
  return (x > 0 && x < armLength && y > 0 && y < armWidth) ||
    (x > 0 && x < armWidth && y > 0 && y < armLength);
}
bool InClosedL(double x, double y)
{
  return (x >= 0 && x <= armLength && y >= 0 && y <= armWidth) ||
    (x >= 0 && x <= armWidth && y >= 0 && y <= armLength);
}
} // namespace

int main(int argc, char* argv[])
{
  const double spacing = 2.5;
  const int n = static_cast<int>(std::lround(armLength / spacing));
  const int nz = static_cast<int>(std::lround(height / spacing));
  vtkNew<vtkPoints> points;
  std::uint32_t state = 777u;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
      {
        const double x = i * spacing, y = j * spacing, z = k * spacing;
        const bool onBoundary = InClosedL(x, y) && (k == 0 || k == nz || !InOpenL(x, y));
        if (onBoundary)
        {
          // In sequence (z, y, x, gcc's order of the arguments before): a call's argument
          // order is unspecified, and clang's differs.
          const double jz = Jitter(state), jy = Jitter(state), jx = Jitter(state);
          points->InsertNextPoint(
            x + 0.3 * spacing * jx, y + 0.3 * spacing * jy, z + 0.3 * spacing * jz);
        }
      }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  const double lVolume = (armLength * armWidth + (armLength - armWidth) * armWidth) * height;
  const double hullVolume =
    (armLength * armLength - 0.5 * (armLength - armWidth) * (armLength - armWidth)) * height;
  std::cout << points->GetNumberOfPoints() << " points; L volume " << lVolume << ", hull volume "
            << hullVolume << std::endl;

  vtkNew<vtkDelaunaySeedSurface> seed;
  vtkNew<dsseedtest::MessageCounter> messages;
  seed->AddObserver(vtkCommand::ErrorEvent, messages);
  seed->AddObserver(vtkCommand::WarningEvent, messages);
  seed->SetInputData(cloud);
  // Optional sweep, for choosing the value below: TestDelaunaySeedLShape alpha...
  for (int a = 1; a < argc; ++a)
  {
    seed->SetAlpha(std::atof(argv[a]));
    dstest::UpdateWithInputsUnchanged(seed, "seed");
    std::cout << "Alpha " << argv[a] << std::endl;
    dsseedtest::Measure(seed->GetOutput());
  }

  std::cout << "No Alpha (convex hull):" << std::endl;
  seed->SetAlpha(0.0);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  const auto hull = dsseedtest::Measure(seed->GetOutput());
  dsseedtest::CheckClosedManifold(hull, seed->GetOutput()->GetNumberOfPoints(), 2);
  DS_CHECK_GE(hull.MassVolume / lVolume, 1.3, "hull volume / L volume");

  // Tetrahedra inside an arm have circumspheres up to about half the arm width (7.5); those
  // spanning the notch are much larger.
  std::cout << "Alpha 9:" << std::endl;
  seed->SetAlpha(9.0);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  const auto carved = dsseedtest::Measure(seed->GetOutput());
  dsseedtest::CheckClosedManifold(carved, seed->GetOutput()->GetNumberOfPoints(), 2);
  DS_CHECK_LE(std::abs(carved.MassVolume / lVolume - 1.0), 0.10, "relative volume error");

  // Alpha too small cuts into the arms: many pinched edges and vertices, which must be
  // resolved into a closed, manifold, oriented surface (of whatever genus), with a warning.
  std::cout << "Alpha 7 (too small, pinches):" << std::endl;
  const int warningsBefore = messages->Warnings;
  seed->SetAlpha(7.0);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  const auto pinched = dsseedtest::Measure(seed->GetOutput());
  dsseedtest::CheckClosedManifold(pinched, seed->GetOutput()->GetNumberOfPoints(), pinched.Euler);
  DS_CHECK(messages->Warnings > warningsBefore, "a warning says how the pinches were resolved");
  DS_CHECK(messages->Errors == 0, "no errors");
  return dstest::Result("TestDelaunaySeedLShape");
}
