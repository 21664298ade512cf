// SPDX-License-Identifier: BSD-3-Clause
// The methods the benchmark tables compare, each run on a phantom image and measured alike
// (BenchMeasure.h). Each returns the row's cells from "time s" on, or "failed: ..." for a
// method that failed:
// Times are wall-clock with the CPU time of the process beside them (Stopwatch).
// - our filter: vtkDeformableSurfaceFilter, every parameter default, started from the box
//   enclosing the volume (vtkCubeSource, 12 triangles, half a voxel inside the border: the
//   paper's cube test), or from a sphere near the object, one click or a sphere a few voxels
//   around the object (RunOursNear, RunOursClick, RunOursTightSphere); the time is its Update();
// - vtkFlyingEdges3D at the value halfway between background and object; the time is its
//   Update().
#ifndef BenchMethods_h
#define BenchMethods_h

#include "BenchMeasure.h"
#include "BenchVolumes.h"

#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDeformableSurfaceFilter.h"
#include "vtkDelaunaySeedSurface.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>

namespace dsbench
{
/// Wall-clock and CPU time (all threads of the process) since construction. On a machine shared
/// with other jobs the wall time grows with the load; the CPU time much less.
class Stopwatch
{
public:
  Stopwatch()
    : Wall0(std::chrono::steady_clock::now())
    , Cpu0(ProcessCpuSeconds())
  {
  }
  double Wall() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Wall0).count();
  }
  double Cpu() const { return ProcessCpuSeconds() - this->Cpu0; }
  /// "wall (cpu c)", the table's time cell.
  std::string Cell() const
  {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.3f (cpu %.2f)", this->Wall(), this->Cpu());
    return buf;
  }

private:
  static double ProcessCpuSeconds()
  {
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
      1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  }
  std::chrono::steady_clock::time_point Wall0;
  double Cpu0;
};

/// The row's cells from the time on: time | measures | notes (the largest piece first, when the
/// surface has several, then `notes`).
inline std::string TimeAndMeasures(
  const std::string& timeCell, vtkPolyData* surface, const Phantom& ph, const std::string& notes)
{
  std::string piece;
  const std::string cells = MeasureCells(Measure(surface, Distance(ph)), &piece);
  return timeCell + " | " + cells + " | " + piece + notes;
}

inline int FieldInt(vtkPolyData* surface, const char* name)
{
  vtkDataArray* a = surface->GetFieldData()->GetArray(name);
  return a && a->GetNumberOfTuples() > 0 ? static_cast<int>(a->GetTuple1(0)) : -1;
}

/// Our filter from `start` with every default but NumberOfThreads (0 = all cores) and what
/// `configure` sets; the time is the filter's Update() alone.
inline std::string RunOursFrom(vtkImageData* image, const Phantom& ph, int threads,
  vtkPolyData* start, const std::function<void(vtkDeformableSurfaceFilter*)>& configure = nullptr)
{
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceData(start);
  filter->SetNumberOfThreads(threads);
  if (configure)
    configure(filter);
  const Stopwatch clock;
  filter->Update();
  const std::string time = clock.Cell();
  vtkPolyData* out = filter->GetOutput();
  if (out->GetNumberOfCells() == 0)
    return "failed: empty output (see the error above)";
  vtkDataArray* sigma0 = out->GetFieldData()->GetArray("InitialSigma");
  char notes[96];
  std::snprintf(notes, sizeof notes, "%d levels, %d sweeps, sigma_0 %.1f", FieldInt(out, "Levels"),
    FieldInt(out, "Sweeps"), sigma0 && sigma0->GetNumberOfTuples() ? sigma0->GetTuple1(0) : -1.0);
  return TimeAndMeasures(time, out, ph, notes);
}

/// Our filter from the box enclosing the volume (half a voxel inside the border).
inline std::string RunOurs(vtkImageData* image, const Phantom& ph, int threads,
  const std::function<void(vtkDeformableSurfaceFilter*)>& configure = nullptr)
{
  const double n = ph.N;
  vtkNew<vtkCubeSource> box;
  box->SetBounds(0.5, n - 1.5, 0.5, n - 1.5, 0.5, n - 1.5);
  box->Update();
  return RunOursFrom(image, ph, threads, box->GetOutput(), configure);
}

/// Sets the local edge normalisation (EdgeNormalization Local, docs/METHOD.md §9.2).
inline void LocalEdges(vtkDeformableSurfaceFilter* f)
{
  f->SetEdgeNormalization(vtkDeformableSurfaceFilter::LOCAL);
}

/// Our filter from a sphere near the object: ParaView's Sphere (24 x 24) of radius 0.3 n at
/// the volume's centre, around the ball of radius n/4 (BenchScale's near start).
inline std::string RunOursNear(vtkImageData* image, const Phantom& ph, int threads)
{
  const double c = 0.5 * (ph.N - 1);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(c, c, c);
  sphere->SetRadius(0.3 * ph.N);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(24);
  sphere->Update();
  return RunOursFrom(image, ph, threads, sphere->GetOutput());
}

/// Our filter from one click at the volume's centre (inside the ball): vtkDelaunaySeedSurface
/// of that point, every default, then RegionWeight 1 (BenchScale's one-click start).
inline std::string RunOursClick(vtkImageData* image, const Phantom& ph, int threads)
{
  const double c = 0.5 * (ph.N - 1);
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(c, c, c);
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkDelaunaySeedSurface> seed;
  seed->SetInputData(cloud);
  seed->Update();
  return RunOursFrom(image, ph, threads, seed->GetOutput(),
    [](vtkDeformableSurfaceFilter* f) { f->SetRegionWeight(1.0); });
}

/// Our filter from a sphere `gap` voxels outside the ball, at its centre (48 x 48), every
/// default: sigma_0 from so tight a start is a few voxels, so the first level runs on the
/// image's own grid (as for picks a few voxels outside an object; docs/METHOD.md §9.7).
inline std::string RunOursTightSphere(vtkImageData* image, const Phantom& ph, int threads,
  double gap, const std::function<void(vtkDeformableSurfaceFilter*)>& configure = nullptr)
{
  const double c = 0.5 * (ph.N - 1);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(c, c, c);
  sphere->SetRadius(ph.Size + gap);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  sphere->Update();
  return RunOursFrom(image, ph, threads, sphere->GetOutput(), configure);
}

/// vtkFlyingEdges3D at the phantom's mid value, all cores (vtkSMPTools).
inline std::string RunFlyingEdges(vtkImageData* image, const Phantom& ph)
{
  vtkNew<vtkFlyingEdges3D> iso;
  iso->SetInputData(image);
  iso->SetValue(0, ph.MidValue());
  iso->ComputeNormalsOff();
  iso->ComputeGradientsOff();
  iso->ComputeScalarsOff();
  const Stopwatch clock;
  iso->Update();
  const std::string time = clock.Cell();
  char notes[64];
  std::snprintf(notes, sizeof notes, "iso %g", ph.MidValue());
  return TimeAndMeasures(time, iso->GetOutput(), ph, notes);
}
} // namespace dsbench

#endif
