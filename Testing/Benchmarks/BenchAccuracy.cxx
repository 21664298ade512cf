// SPDX-License-Identifier: BSD-3-Clause
// The accuracy table: the phantoms of the hierarchy's accuracy goals, each solved from the box
// enclosing the volume with every default by our filter, beside vtkFlyingEdges3D and ITK's
// GeodesicActiveContourLevelSetImageFilter (when CMake found ITK; the column is skipped with a
// line saying so otherwise). Every case runs in a child process of its own (peak RSS per case);
// a case is started only when its memory estimate fits, and stopped at the time limit.
// Usage: BenchAccuracy [--time-limit CPU seconds (default 300)] [--only TEXT (only the rows whose
//                      "phantom method" contains TEXT; repeatable, every TEXT must be in it)]
//                      [sizes... (default 128 256 512)]
#include "BenchRow.h"
#ifdef DS_BENCH_WITH_ITK
#include "ItkGeodesicActiveContour.h"
#endif

#include "vtkFlyingEdges3D.h"

#include <cstdlib>
#include <set>
#include <vector>

namespace
{
using namespace dsbench;

std::vector<Phantom> GoalPhantoms()
{
  // name, n, shape, size (radius or half side), noise (of the contrast), CT-like uint16
  return {
    { "sphere r32 128^3", 128, Shape::Sphere, 32, 0, false },
    { "sphere r32 + noise 0.3", 128, Shape::Sphere, 32, 0.3, false },
    { "cube 16 128^3", 128, Shape::Cube, 16, 0, false },
    { "cube 16 + noise 0.3", 128, Shape::Cube, 16, 0.3, false },
    { "sphere r64 256^3", 256, Shape::Sphere, 64, 0, false },
    { "ball r128 512^3 uint16 + noise 0.1", 512, Shape::Sphere, 128, 0.1, true },
  };
}

#ifdef DS_BENCH_WITH_ITK
/// ITK's geodesic active contour from a sphere of half the object's size at its centre
/// (ItkGeodesicActiveContour.h); the surface is the zero level through vtkFlyingEdges3D. The
/// time covers the float copy, the feature image, the level set and the iso-surface.
std::string RunGac(vtkImageData* image, const Phantom& ph)
{
  const Stopwatch clock;
  vtkDataArray* values = image->GetPointData()->GetScalars();
  std::vector<float> volume(static_cast<size_t>(values->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    volume[i] = static_cast<float>(values->GetTuple1(i));
  GacSettings settings;
  settings.StartCenter[0] = settings.StartCenter[1] = settings.StartCenter[2] = 0.5 * (ph.N - 1);
  settings.StartRadius = 0.5 * ph.Size;
  GacResult result;
  if (!RunGeodesicActiveContour(volume.data(), ph.N, settings, result))
    return "failed: " + result.Error;
  volume = std::vector<float>();
  vtkNew<vtkImageData> levelSet;
  levelSet->SetDimensions(ph.N, ph.N, ph.N);
  vtkNew<vtkFloatArray> phi;
  phi->SetName("phi");
  phi->SetArray(result.LevelSet.data(), static_cast<vtkIdType>(result.LevelSet.size()), 1);
  levelSet->GetPointData()->SetScalars(phi);
  vtkNew<vtkFlyingEdges3D> iso;
  iso->SetInputData(levelSet);
  iso->SetValue(0, 0.0);
  iso->ComputeNormalsOff();
  iso->ComputeGradientsOff();
  iso->ComputeScalarsOff();
  iso->Update();
  const std::string time = clock.Cell();
  char notes[96];
  std::snprintf(
    notes, sizeof notes, "%d iterations, RMS change %.3g", result.Iterations, result.RMSChange);
  return TimeAndMeasures(time, iso->GetOutput(), ph, notes);
}
#endif
} // namespace

int main(int argc, char* argv[])
{
  double timeLimit = 300;
  std::set<int> sizes;
  std::vector<std::string> only;
  for (int i = 1; i < argc; ++i)
  {
    if (std::string(argv[i]) == "--time-limit" && i + 1 < argc)
      timeLimit = std::atof(argv[++i]);
    else if (std::string(argv[i]) == "--only" && i + 1 < argc)
      only.emplace_back(argv[++i]);
    else
      sizes.insert(std::atoi(argv[i]));
  }
  if (sizes.empty())
    sizes = { 128, 256, 512 };
#ifndef DS_BENCH_WITH_ITK
  std::printf(
    "ITK GeodesicActiveContour: skipped, this build did not find ITK (install "
    "libinsighttoolkit5-dev and reconfigure; scripts/benchmark.sh Accuracy does both)\n\n");
#endif
  PrintHeader();
  // Priors of the peak per voxel, input included, until a smaller case of the method was
  // measured: ours keeps a float copy, Potential and Force (4 floats); ITK's filter the speed
  // image, its advection vectors (3 floats), the float input, the start and the output.
  CaseRunner runner(2.0 * GiB, timeLimit);
  runner.SetOnly(only);
  for (const Phantom& ph : GoalPhantoms())
  {
    if (!sizes.count(ph.N))
      continue;
    const std::vector<Method> methods = {
      { "ours (defaults, from the box)", 24,
        [&](vtkImageData* image) { return RunOurs(image, ph, 0); } },
      { "vtkFlyingEdges3D", 8, [&](vtkImageData* image) { return RunFlyingEdges(image, ph); } },
#ifdef DS_BENCH_WITH_ITK
      { "ITK GeodesicActiveContour", 48, [&](vtkImageData* image) { return RunGac(image, ph); } },
#endif
    };
    for (const auto& m : methods)
      runner.Run(ph, m, false);
  }
  return 0;
}
