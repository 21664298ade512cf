// SPDX-License-Identifier: BSD-3-Clause
// ContinueFromLastResult (the paper's interactive tuning): after a change of the filter's own
// parameters the next update starts from the last output; a change of an input starts over.
// On a soft ball of radius 16 (64^3) from a sphere of radius 22: a cold run with Tau 0.1, then
// Tau 0.15 warm must take far fewer sweeps than Tau 0.15 cold and end on the same surface
// (mean |d| to the sphere within 0.05 voxel of the cold run's, both <= 0.2); a new start
// surface (another radius) makes the next run cold again.
#include "DSSurfaceInvariants.h"
#include "SoftBallImage.h"

#include "vtkDataArray.h"
#include "vtkDeformableSurfaceFilter.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"

#include <cmath>

namespace
{
const int N = 64;
const double C = 31.5, R = 16.0;

struct Run
{
  int Sweeps = 0, Warm = -1;
  double Mean = 0;
};

Run Measure(vtkDeformableSurfaceFilter* f)
{
  dstest::UpdateAndCheckSurface(f, "warm-start run");
  vtkPolyData* out = f->GetOutput();
  Run r;
  r.Sweeps = static_cast<int>(out->GetFieldData()->GetArray("Sweeps")->GetTuple1(0));
  r.Warm = static_cast<int>(out->GetFieldData()->GetArray("WarmStart")->GetTuple1(0));
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    r.Mean += std::abs(
      std::sqrt((p[0] - C) * (p[0] - C) + (p[1] - C) * (p[1] - C) + (p[2] - C) * (p[2] - C)) - R);
  }
  r.Mean /= std::max<vtkIdType>(1, out->GetNumberOfPoints());
  std::cout << "  " << (r.Warm ? "warm" : "cold") << ": " << r.Sweeps << " sweeps, "
            << out->GetNumberOfPoints() << " points, mean |d| " << r.Mean << std::endl;
  return r;
}
} // namespace

int TestWarmStart(int, char*[])
{
  auto image = dstest::SoftBallImage(N, C, R);
  vtkNew<vtkSphereSource> start;
  start->SetCenter(C, C, C);
  start->SetRadius(22.0);
  start->SetThetaResolution(24);
  start->SetPhiResolution(24);

  vtkNew<vtkDeformableSurfaceFilter> tuned;
  tuned->SetInputData(0, image);
  tuned->SetInitialSurfaceConnection(start->GetOutputPort());
  tuned->ContinueFromLastResultOn();
  const Run first = Measure(tuned);
  tuned->SetTau(0.15);
  const Run warm = Measure(tuned);

  vtkNew<vtkDeformableSurfaceFilter> cold;
  cold->SetInputData(0, image);
  cold->SetInitialSurfaceConnection(start->GetOutputPort());
  cold->SetTau(0.15);
  const Run reference = Measure(cold);

  DS_CHECK(first.Warm == 0 && warm.Warm == 1 && reference.Warm == 0,
    "the second run of the tuned filter is warm");
  DS_CHECK_LE(warm.Sweeps, 0.5 * reference.Sweeps, "warm start: sweeps (<= half the cold run's)");
  DS_CHECK_LE(
    std::abs(warm.Mean - reference.Mean), 0.05, "warm vs cold: mean |d| difference (voxels)");
  DS_CHECK_LE(warm.Mean, 0.2, "warm: mean |d| to the sphere (voxels)");
  std::cout << "  sweeps saved: " << reference.Sweeps - warm.Sweeps << " of " << reference.Sweeps
            << std::endl;

  start->SetRadius(21.0); // a new input: start over
  const Run again = Measure(tuned);
  DS_CHECK(again.Warm == 0, "a changed start surface: cold again");
  tuned->SetGamma(0.08);
  DS_CHECK(Measure(tuned).Warm == 1, "then a parameter change: warm");
  image->Modified(); // a new image: start over
  DS_CHECK(Measure(tuned).Warm == 0, "a changed image: cold again");
  return dstest::Result("TestWarmStart");
}

int main(int argc, char* argv[])
{
  return TestWarmStart(argc, argv);
}
