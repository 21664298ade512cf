// SPDX-License-Identifier: BSD-3-Clause
// A start far finer than the first sigma (as a user gets by starting from an iso-surface)
// begins the hierarchy on a coarse copy (MultilevelSolver::CoarsenStart, docs/METHOD.md §9.5):
// 1. a sphere of 124 k triangles (mean edge ~0.5 voxel) 3 voxels around a soft ball of radius
//    20: one warning that names the coarsening, the surface on the ball (mean |d| <= 0.1
//    voxel), closed, genus 0, far fewer vertices than the start (the hierarchy refines where
//    the ball is), every invariant of DSSurfaceInvariants.h;
// 2. the same start solved again with AbortExecute set when the progress reaches 10 %: the
//    abort is answered within a sweep batch (no progress event after it but the last), with
//    fewer sweeps than the whole solve and a closed surface;
// 3. a thin torus (tube radius 1 voxel, 150 k triangles) whose coarse copy would lose the tube:
//    the copy is refused (a warning saying the start is solved as given) and the start's genus
//    is kept. MaxSweeps bounds the run; only the decision is checked.
// The time it saves is measured by BenchHugeStart, not here.
#include "DSSurfaceInvariants.h"
#include "SoftBallImage.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDeformableSurfaceFilter.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

#include <cmath>
#include <string>

namespace
{
struct Messages : public vtkCommand
{
  static Messages* New() { return new Messages; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    ++this->Count;
    this->Text += data ? static_cast<const char*>(data) : "";
  }
  int Count = 0;
  std::string Text;
};

const int N = 64;
const double C = 31.5, R = 20.0;

/// The dense start of cases 1 and 2: a sphere of 124 000 triangles 3 voxels around the ball.
vtkSmartPointer<vtkSphereSource> DenseSphere()
{
  auto start = vtkSmartPointer<vtkSphereSource>::New();
  start->SetCenter(C, C, C);
  start->SetRadius(R + 3.0);
  start->SetThetaResolution(250);
  start->SetPhiResolution(250);
  start->Update();
  return start;
}

const double HugeStartTolerance = 1e-4;

int CoarsenedSphere(vtkImageData* image)
{
  auto start = DenseSphere();
  std::cout << "sphere start: " << start->GetOutput()->GetNumberOfPolys() << " triangles"
            << std::endl;

  vtkNew<vtkDeformableSurfaceFilter> filter;
  vtkNew<Messages> warnings;
  filter->AddObserver(vtkCommand::WarningEvent, warnings);
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceConnection(start->GetOutputPort());
  filter->SetMaxLevels(10);
  // Tighter than the default so that a level takes more than one batch of sweeps: the
  // abort below is asked from a progress event, and a level that converges within its first
  // batch reports none.
  filter->SetConvergenceTolerance(HugeStartTolerance);
  const auto facts = dstest::UpdateAndCheckSurface(filter, "coarsened sphere");
  vtkPolyData* out = filter->GetOutput();
  double sum = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    sum += std::abs(
      std::sqrt((p[0] - C) * (p[0] - C) + (p[1] - C) * (p[1] - C) + (p[2] - C) * (p[2] - C)) - R);
  }
  const double mean = sum / std::max<vtkIdType>(1, out->GetNumberOfPoints());
  std::cout << "  " << out->GetNumberOfPoints() << " vertices, mean |d| " << mean
            << " voxel; warnings: " << warnings->Text << std::endl;
  DS_CHECK(warnings->Count == 1, "one warning");
  DS_CHECK(warnings->Text.find("were coarsened to") != std::string::npos,
    "the warning names the coarsening");
  DS_CHECK(facts.Euler == 2, "closed, genus 0");
  DS_CHECK_LE(mean, 0.1, "mean |distance| to the ball (voxels)");
  DS_CHECK_LE(out->GetNumberOfPoints(), 40000, "far fewer vertices than the start's 62 252");
  return static_cast<int>(out->GetFieldData()->GetArray("Sweeps")->GetTuple1(0));
}

void ThinTorusKept(vtkImageData* image)
{
  vtkNew<vtkParametricTorus> torus;
  torus->SetRingRadius(R + 3.0);
  torus->SetCrossSectionRadius(1.0);
  vtkNew<vtkParametricFunctionSource> start;
  start->SetParametricFunction(torus);
  start->SetUResolution(1500);
  start->SetVResolution(50);
  start->GenerateTextureCoordinatesOff();
  vtkNew<vtkTransform> toCentre;
  toCentre->Translate(C, C, C);
  vtkNew<vtkTransformPolyDataFilter> move;
  move->SetInputConnection(start->GetOutputPort());
  move->SetTransform(toCentre);
  move->Update();
  vtkPolyData* poly = move->GetOutput();
  std::cout << "thin torus start: " << poly->GetNumberOfPolys() << " triangles" << std::endl;

  vtkNew<vtkDeformableSurfaceFilter> filter;
  vtkNew<Messages> warnings;
  filter->AddObserver(vtkCommand::WarningEvent, warnings);
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceConnection(move->GetOutputPort());
  filter->SetMaxSweeps(3);
  const auto facts = dstest::UpdateAndCheckSurface(filter, "thin torus");
  vtkPolyData* out = filter->GetOutput();
  std::cout << "  " << out->GetNumberOfPoints() << " vertices, Euler " << facts.Euler
            << "; warnings: " << warnings->Text << std::endl;
  DS_CHECK(warnings->Text.find("would change its topology") != std::string::npos,
    "the coarse copy is refused with a warning");
  DS_CHECK(facts.Euler == 0, "the torus's genus kept");
  // 150 000 parametric triangles, 146 902 once the seams are merged; a coarse copy has hundreds.
  DS_CHECK(out->GetNumberOfPolys() > 100000, "solved as given (its own triangles)");
}
}

/// Progress moves during a solve from a huge start and Abort stops it within a sweep or two,
/// with a valid surface (ParaView's progress bar and its Abort button).
struct AbortLog
{
  int Events = 0, AfterAbort = 0;
  bool Aborted = false;
  vtkAlgorithm* Algorithm = nullptr;
};

void OnProgress(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* log = static_cast<AbortLog*>(clientData);
  const double p = *static_cast<double*>(callData);
  ++log->Events;
  log->AfterAbort += log->Aborted && p < 1.0 ? 1 : 0;
  if (!log->Aborted && p >= 0.1)
  {
    log->Aborted = true;
    log->Algorithm->SetAbortExecute(1);
  }
}

void AbortedSphere(vtkImageData* image, int fullSweeps)
{
  auto start = DenseSphere();
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceConnection(start->GetOutputPort());
  filter->SetMaxLevels(10);
  filter->SetConvergenceTolerance(HugeStartTolerance);
  AbortLog log;
  log.Algorithm = filter;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetCallback(OnProgress);
  cb->SetClientData(&log);
  filter->AddObserver(vtkCommand::ProgressEvent, cb);
  const auto facts = dstest::UpdateAndCheckSurface(filter, "aborted huge start");
  std::cout << "aborted at 10 %: " << log.Events << " progress events, " << log.AfterAbort
            << " after the abort, " << filter->GetOutput()->GetNumberOfPoints() << " vertices"
            << std::endl;
  const int sweeps =
    static_cast<int>(filter->GetOutput()->GetFieldData()->GetArray("Sweeps")->GetTuple1(0));
  std::cout << "  " << sweeps << " sweeps (the whole solve: " << fullSweeps << ")" << std::endl;
  DS_CHECK(log.Aborted, "the progress reached 10 %");
  DS_CHECK(sweeps < fullSweeps, "aborted: fewer sweeps than the whole solve");
  DS_CHECK_GE(
    log.Events - log.AfterAbort, 4, "progress events up to the abort (the start read, levels)");
  DS_CHECK_LE(log.AfterAbort, 2, "progress events after the abort (a sweep batch at most)");
  DS_CHECK(facts.Euler == 2, "aborted: a closed genus-0 surface");
}

int TestHugeStart(int, char*[])
{
  auto image = dstest::SoftBallImage(N, C, R);
  const int fullSweeps = CoarsenedSphere(image);
  ThinTorusKept(image);
  AbortedSphere(image, fullSweeps);
  return dstest::Result("TestHugeStart");
}

int main(int argc, char* argv[])
{
  return TestHugeStart(argc, argv);
}
