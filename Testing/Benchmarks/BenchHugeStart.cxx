// SPDX-License-Identifier: BSD-3-Clause
// A dense start surface, as a user gets by starting from an iso-surface: spheres of growing
// resolution 3 voxels around a soft ball of radius 32 in 128^3, through vtkDeformableSurfaceFilter
// with MaxLevels 10 and every other default (a start of more than 100 000 triangles much finer
// than sigma_0 begins on a coarse copy: docs/METHOD.md §9.5), beside vtkFlyingEdges3D on the
// same volume in the same run.
// Usage: BenchHugeStart [sphere resolutions...]   (default 100 400 800; 800 = 1.28 M triangles)
#include "../Cxx/SoftBallImage.h"

#include "vtkDeformableSurfaceFilter.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

using Clock = std::chrono::steady_clock;

namespace
{
double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

double MeanDistance(vtkPolyData* surface, double c, double r)
{
  double sum = 0;
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double p[3];
    surface->GetPoint(i, p);
    sum += std::abs(
      std::sqrt((p[0] - c) * (p[0] - c) + (p[1] - c) * (p[1] - c) + (p[2] - c) * (p[2] - c)) - r);
  }
  return sum / std::max<vtkIdType>(1, surface->GetNumberOfPoints());
}
}

int main(int argc, char* argv[])
{
  std::vector<int> resolutions;
  for (int i = 1; i < argc; ++i)
  {
    resolutions.push_back(std::atoi(argv[i]));
  }
  if (resolutions.empty())
  {
    resolutions = { 100, 400, 800 };
  }
  const int n = 128;
  const double c = 63.5, r = 32.0;
  auto image = dstest::SoftBallImage(n, c, r);

  vtkNew<vtkFlyingEdges3D> iso;
  iso->SetInputData(image);
  iso->SetValue(0, 0.5);
  auto t0 = Clock::now();
  iso->Update();
  const double isoSeconds = Seconds(t0, Clock::now());

  std::printf("| start triangles | time s | levels | sweeps | output vertices | mean d (voxels) | "
              "vtkFlyingEdges3D s | ratio |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (int res : resolutions)
  {
    vtkNew<vtkSphereSource> start;
    start->SetCenter(c, c, c);
    start->SetRadius(r + 3.0);
    start->SetThetaResolution(res);
    start->SetPhiResolution(res);
    start->Update();
    vtkNew<vtkDeformableSurfaceFilter> filter;
    filter->SetInputData(0, image);
    filter->SetInitialSurfaceData(start->GetOutput());
    filter->SetMaxLevels(10);
    t0 = Clock::now();
    filter->Update();
    const double seconds = Seconds(t0, Clock::now());
    vtkPolyData* out = filter->GetOutput();
    vtkFieldData* fd = out->GetFieldData();
    std::printf("| %lld | %.2f | %.0f | %.0f | %lld | %.3f | %.3f | %.0f |\n",
      static_cast<long long>(start->GetOutput()->GetNumberOfPolys()), seconds,
      fd->GetArray("Levels")->GetTuple1(0), fd->GetArray("Sweeps")->GetTuple1(0),
      static_cast<long long>(out->GetNumberOfPoints()), MeanDistance(out, c, r), isoSeconds,
      seconds / isoSeconds);
  }
  return 0;
}
