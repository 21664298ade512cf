// SPDX-License-Identifier: BSD-3-Clause
// The README's one-click workflow through the public filters only, as a user runs it: one
// clicked point -> vtkDelaunaySeedSurface (a seed sphere of SeedRadius around it) ->
// vtkDeformableSurfaceFilter on the image, every filter default unless the caller sets
// RegionWeight or IntensityRange. Shared by TestOneClickObjects and BenchObjects.
#ifndef OneClick_h
#define OneClick_h

#include "vtkDeformableSurfaceFilter.h"
#include "vtkDelaunaySeedSurface.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <array>
#include <chrono>

namespace dsobjects
{
/// What the user sets for a click: the seed sphere's radius (world units; the seed filter's
/// default 5), and the filter's RegionWeight and IntensityRange (negative weight, lo >= hi:
/// left at the filter's defaults).
struct ClickSettings
{
  double SeedRadius = 5.0;
  double RegionWeight = -1.0;
  double IntensityRange[2] = { 0.0, 0.0 };
  int MaxSweepsPerLevel = 0; ///< 0: the filter's default
};

struct ClickResult
{
  vtkSmartPointer<vtkPolyData> Surface;
  double Seconds = 0;             ///< the deformable surface's solve (the seed outside the clock)
  double UsedRange[2] = { 0, 0 }; ///< the output's IntensityRange field (0, 0 when absent)
  bool HasRange = false;
};

inline vtkSmartPointer<vtkPolyData> SeedFromClick(
  const std::array<double, 3>& click, double seedRadius)
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(click.data());
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkDelaunaySeedSurface> seed;
  seed->SetInputData(cloud);
  seed->SetSeedRadius(seedRadius);
  seed->Update();
  return seed->GetOutput();
}

inline ClickResult RunOneClick(
  vtkImageData* image, const std::array<double, 3>& click, const ClickSettings& settings)
{
  vtkSmartPointer<vtkPolyData> seed = SeedFromClick(click, settings.SeedRadius);
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceData(seed);
  if (settings.RegionWeight >= 0)
    filter->SetRegionWeight(settings.RegionWeight);
  if (settings.IntensityRange[0] < settings.IntensityRange[1])
    filter->SetIntensityRange(settings.IntensityRange[0], settings.IntensityRange[1]);
  if (settings.MaxSweepsPerLevel > 0)
    filter->SetMaxSweepsPerLevel(settings.MaxSweepsPerLevel);
  const auto t0 = std::chrono::steady_clock::now();
  filter->Update();
  ClickResult r;
  r.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.Surface = vtkSmartPointer<vtkPolyData>::New();
  r.Surface->ShallowCopy(filter->GetOutput());
  if (vtkDataArray* range = r.Surface->GetFieldData()->GetArray("IntensityRange"))
  {
    range->GetTuple(0, r.UsedRange);
    r.HasRange = range->GetNumberOfComponents() == 2;
  }
  return r;
}
} // namespace dsobjects

#endif
