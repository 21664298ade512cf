// The methods the benchmark tables compare, each run on a phantom image and measured alike
// (BenchMeasure.h). Each returns the row's cells from "time s" on, or "failed: ..." for a
// method that failed:
// - our filter: vtkDeformableSurfaceFilter, every parameter default, started from the box
//   enclosing the volume (vtkCubeSource, 12 triangles, half a voxel inside the border: the
//   paper's cube test); the time is its Update();
// - vtkFlyingEdges3D at the value halfway between background and object; the time is its
//   Update().
#ifndef BenchMethods_h
#define BenchMethods_h

#include "BenchMeasure.h"
#include "BenchVolumes.h"

#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDeformableSurfaceFilter.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkNew.h"

#include <chrono>
#include <cstdio>
#include <string>

namespace dsbench
{
inline double SecondsSince(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

inline std::string TimeAndMeasures(double seconds, vtkPolyData* surface, const Phantom& ph)
{
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f | ", seconds);
  return buf + MeasureCells(Measure(surface, Distance(ph)));
}

inline int FieldInt(vtkPolyData* surface, const char* name)
{
  vtkDataArray* a = surface->GetFieldData()->GetArray(name);
  return a && a->GetNumberOfTuples() > 0 ? static_cast<int>(a->GetTuple1(0)) : -1;
}

/// Our filter with every default but NumberOfThreads (0 = all cores).
inline std::string RunOurs(vtkImageData* image, const Phantom& ph, int threads)
{
  const double n = ph.N;
  vtkNew<vtkCubeSource> box;
  box->SetBounds(0.5, n - 1.5, 0.5, n - 1.5, 0.5, n - 1.5);
  box->Update();
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceData(box->GetOutput());
  filter->SetNumberOfThreads(threads);
  const auto t0 = std::chrono::steady_clock::now();
  filter->Update();
  const double seconds = SecondsSince(t0);
  vtkPolyData* out = filter->GetOutput();
  if (out->GetNumberOfCells() == 0)
    return "failed: empty output (see the error above)";
  char notes[96];
  std::snprintf(notes, sizeof notes, " | %d levels, %d sweeps", FieldInt(out, "Levels"),
    FieldInt(out, "Sweeps"));
  return TimeAndMeasures(seconds, out, ph) + notes;
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
  const auto t0 = std::chrono::steady_clock::now();
  iso->Update();
  const double seconds = SecondsSince(t0);
  char notes[64];
  std::snprintf(notes, sizeof notes, " | iso %g", ph.MidValue());
  return TimeAndMeasures(seconds, iso->GetOutput(), ph) + notes;
}
} // namespace dsbench

#endif
