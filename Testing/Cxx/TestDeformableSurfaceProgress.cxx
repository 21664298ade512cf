// SPDX-License-Identifier: BSD-3-Clause
// The progress bar and Abort, as ParaView drives them: ProgressEvent values rise
// from 0 to 1 during the solve, and setting AbortExecute from a progress observer
// stops the solve early with a valid closed surface (fewer sweeps than the full run).
#include "DSSurfaceInvariants.h"
#include "HierarchyPhantoms.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDeformableSurfaceFilter.h"
#include "vtkFeatureEdges.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <vector>

namespace
{
struct ProgressLog
{
  std::vector<double> Values;
  double AbortAt = 2.0; // > 1: never
  vtkAlgorithm* Algorithm = nullptr;
};

void OnProgress(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* log = static_cast<ProgressLog*>(clientData);
  const double p = *static_cast<double*>(callData);
  log->Values.push_back(p);
  if (p >= log->AbortAt)
  {
    log->Algorithm->SetAbortExecute(1);
  }
}

int OpenOrNonManifoldEdges(vtkPolyData* pd)
{
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(pd);
  edges->BoundaryEdgesOn();
  edges->NonManifoldEdgesOn();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->Update();
  return static_cast<int>(edges->GetOutput()->GetNumberOfCells());
}
}

int TestDeformableSurfaceProgress(int, char*[])
{
  const int n = 64;
  const std::vector<float> sphere = dsphantom::Sphere(n, 16.0);
  vtkNew<vtkImageData> image;
  image->SetDimensions(n, n, n);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(static_cast<vtkIdType>(sphere.size()));
  std::copy(sphere.begin(), sphere.end(), values->GetPointer(0));
  image->GetPointData()->SetScalars(values);
  vtkNew<vtkCubeSource> box;
  box->SetBounds(0.5, n - 1.5, 0.5, n - 1.5, 0.5, n - 1.5);

  int fullSweeps = 0;
  for (int abort = 0; abort < 2; ++abort)
  {
    vtkNew<vtkDeformableSurfaceFilter> filter;
    filter->SetInputData(0, image);
    filter->SetInitialSurfaceConnection(box->GetOutputPort());
    ProgressLog log;
    log.Algorithm = filter;
    log.AbortAt = abort ? 0.3 : 2.0;
    vtkNew<vtkCallbackCommand> cb;
    cb->SetCallback(OnProgress);
    cb->SetClientData(&log);
    filter->AddObserver(vtkCommand::ProgressEvent, cb);
    const std::string name = abort ? "aborted at 0.3" : "full run";
    dstest::UpdateAndCheckSurface(filter, name);
    vtkPolyData* out = filter->GetOutput();

    bool monotone = true;
    for (size_t i = 1; i < log.Values.size(); ++i)
    {
      monotone = monotone && log.Values[i] >= log.Values[i - 1];
    }
    std::cout << name << ": " << log.Values.size() << " progress events" << std::endl;
    DS_CHECK(monotone, name + ": progress never goes back");
    vtkDataArray* sweepsArray = out->GetFieldData()->GetArray("Sweeps");
    DS_CHECK(sweepsArray != nullptr, name + ": Sweeps field data");
    const int sweeps = sweepsArray ? static_cast<int>(sweepsArray->GetTuple1(0)) : 0;
    std::cout << name << ": " << sweeps << " sweeps, " << out->GetNumberOfPoints() << " points"
              << std::endl;
    if (!abort)
    {
      fullSweeps = sweeps;
      DS_CHECK_GE(static_cast<double>(log.Values.size()), 10, "progress events in a full solve");
      DS_CHECK(!log.Values.empty() && log.Values.back() == 1.0, "progress ends at 1");
    }
    else
    {
      DS_CHECK(
        !log.Values.empty() && log.Values.back() < 1.0 + 1e-12, "progress stays within [0, 1]");
      DS_CHECK_LE(sweeps, 0.8 * fullSweeps, "sweeps of the aborted run vs 0.8 x the full run");
      DS_CHECK_GE(sweeps, 1, "the aborted run did some sweeps");
    }
    // Aborted or not, the output is a usable closed surface.
    DS_CHECK(out->GetNumberOfPolys() > 0, name + ": a surface came out");
    DS_CHECK(OpenOrNonManifoldEdges(out) == 0, name + ": closed and manifold");
  }
  return dstest::Result("TestDeformableSurfaceProgress");
}

int main(int argc, char* argv[])
{
  return TestDeformableSurfaceProgress(argc, argv);
}
