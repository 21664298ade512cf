// SPDX-License-Identifier: BSD-3-Clause
#include "dsVTKAnimation.h"

#include "dsTriangleMesh.h"
#include "dsVTKMesh.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTable.h"

#include <algorithm>
#include <cmath>

namespace dsurf
{
namespace
{
/// At most this many snapshots (the time steps reported) and this much memory in them; later
/// steps show the final surface.
constexpr std::size_t MaxSnapshots = 1001;
constexpr double MaxSnapshotBytes = 512.0 * 1024 * 1024;

/// Memory of one snapshot: double points, 64-bit connectivity and offsets.
double SnapshotBytes(const TriangleMesh& mesh)
{
  return 24.0 * mesh.NumberOfPoints() + 32.0 * mesh.NumberOfTriangles();
}

/// The mesh's points and triangles as vtkPolyData with field data Sweeps (a time step).
vtkSmartPointer<vtkPolyData> MeshSnapshot(const TriangleMesh& mesh, int sweeps)
{
  auto snapshot = vtkSmartPointer<vtkPolyData>::New();
  SetPolyDataGeometry(mesh, snapshot);
  vtkNew<vtkIntArray> count;
  count->SetName("Sweeps");
  count->InsertNextValue(sweeps);
  snapshot->GetFieldData()->AddArray(count);
  return snapshot;
}
} // namespace

void SweepAnimation::ReportTimeSteps(long long maxSweeps, vtkInformation* outInfo) const
{
  const long long S = this->SweepsPerTimeStep;
  const long long steps =
    std::min<long long>(static_cast<long long>(MaxSnapshots) - 1, (maxSweeps + S - 1) / S);
  std::vector<double> times(static_cast<std::size_t>(steps + 1));
  for (long long k = 0; k <= steps; ++k)
  {
    times[static_cast<std::size_t>(k)] = static_cast<double>(k * S);
  }
  outInfo->Set(
    vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
  const double range[2] = { 0.0, times.back() };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
}

void SweepAnimation::Begin(const TriangleMesh& start)
{
  this->Snapshots.clear();
  this->Result = nullptr;
  if (this->AnimateSweeps)
  {
    this->Snapshots.push_back(MeshSnapshot(start, 0));
  }
}

void SweepAnimation::Record(int sweeps, const TriangleMesh& mesh)
{
  if (this->AnimateSweeps && sweeps % this->SweepsPerTimeStep == 0 &&
    this->Snapshots.size() < MaxSnapshots &&
    static_cast<double>(this->Snapshots.size() + 1) * SnapshotBytes(mesh) <= MaxSnapshotBytes)
  {
    this->Snapshots.push_back(MeshSnapshot(mesh, sweeps));
  }
}

void SweepAnimation::ServeTimeStep(double t, vtkPolyData* output) const
{
  const double k = t < 0 ? -1.0 : std::floor(t / this->SweepsPerTimeStep + 1e-9);
  const bool snapshot = k >= 0 && k < static_cast<double>(this->Snapshots.size());
  output->ShallowCopy(
    snapshot ? this->Snapshots[static_cast<std::size_t>(k)].Get() : this->Result.Get());
  if (t >= 0)
  {
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  }
}

bool SweepAnimation::Serve(vtkImageData* image, vtkPolyData* surface, const vtkMTimeType key[3],
  double t, vtkPolyData* output, vtkTable* table) const
{
  if (!this->AnimateSweeps || !this->Result || this->Inputs[0] != image ||
    this->Inputs[1] != surface || !std::equal(key, key + 3, this->Key))
  {
    return false;
  }
  this->ServeTimeStep(t, output);
  table->ShallowCopy(this->Table);
  return true;
}

void SweepAnimation::Keep(vtkImageData* image, vtkPolyData* surface, const vtkMTimeType key[3],
  bool complete, vtkPolyData* output, vtkTable* table)
{
  if (!this->AnimateSweeps)
  {
    return;
  }
  this->Result = vtkSmartPointer<vtkPolyData>::New();
  this->Result->DeepCopy(output);
  this->Table = vtkSmartPointer<vtkTable>::New();
  this->Table->DeepCopy(table);
  std::copy(key, key + 3, this->Key);
  this->Inputs[0] = complete ? image : nullptr; // an incomplete run is never a hit
  this->Inputs[1] = complete ? surface : nullptr;
}
} // namespace dsurf
