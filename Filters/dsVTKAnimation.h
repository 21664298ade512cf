// SPDX-License-Identifier: BSD-3-Clause
// AnimateSweeps of vtkDeformableSurfaceFilter: the convergence as time steps. The output reports
// time steps 0, S, 2S, ... (S = SweepsPerTimeStep; the time value is the number of sweeps, at
// most 1000 steps up to the schedule's cap), and the surface at time t is the one after t sweeps
// (the last surface from the end of the solve on; time 0 is the start surface). The first request
// solves the whole schedule once and keeps a snapshot every S sweeps (points and triangles, ~24
// bytes a vertex and 32 a triangle: 25 snapshots of 14 000 vertices ~ 20 MB; at most 1000
// snapshots and 512 MB, later steps show the final surface); every other step, forward or back,
// comes from that cache until a parameter or an input changes. Serial only: a distributed run, or
// an aborted one, is not cached (every step solves again). Snapshots carry the geometry and the
// field data Sweeps; the final step carries every array. The inputs are asked for no particular
// time.
#ifndef dsVTKAnimation_h
#define dsVTKAnimation_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <vector>

class vtkImageData;
class vtkInformation;
class vtkPolyData;
class vtkTable;

namespace dsurf
{
struct TriangleMesh;

class SweepAnimation
{
public:
  // The filter's properties of the same names (their one default).
  bool AnimateSweeps = false;
  int SweepsPerTimeStep = 20;

  /// The time steps 0, S, 2S, ... (the time value is the number of sweeps; S SweepsPerTimeStep)
  /// up to `maxSweeps`, the schedule's cap, at most MaxSnapshots of them, into `outInfo`.
  void ReportTimeSteps(long long maxSweeps, vtkInformation* outInfo) const;
  /// A solve begins on `start`: the snapshots restart (the first at time 0).
  void Begin(const TriangleMesh& start);
  /// After `sweeps` sweeps the mesh is `mesh`: kept when a time step falls there (and the
  /// limits on snapshots and memory allow).
  void Record(int sweeps, const TriangleMesh& mesh);
  /// Time `t` (sweeps; < 0: the final surface) from the cache into `output` and `table` when it
  /// holds these inputs and parameters (`key`: their modification times); false: not cached.
  bool Serve(vtkImageData* image, vtkPolyData* surface, const vtkMTimeType key[3], double t,
    vtkPolyData* output, vtkTable* table) const;
  /// Keeps the solve's final `output` and `table` for these inputs and `key`; an incomplete run
  /// (aborted, or distributed) is kept but never served.
  void Keep(vtkImageData* image, vtkPolyData* surface, const vtkMTimeType key[3], bool complete,
    vtkPolyData* output, vtkTable* table);
  /// The surface at time `t` (sweeps) from the snapshots, or the final one, into `output`.
  void ServeTimeStep(double t, vtkPolyData* output) const;

private:
  std::vector<vtkSmartPointer<vtkPolyData>> Snapshots;
  vtkSmartPointer<vtkPolyData> Result;
  vtkSmartPointer<vtkTable> Table;
  vtkMTimeType Key[3] = { 0, 0, 0 };
  const void* Inputs[2] = { nullptr, nullptr };
};
} // namespace dsurf

#endif
