// SPDX-License-Identifier: BSD-3-Clause
// vtkDeformableSurfaceFilter on a binary sphere phantom (128^3, radius 32 voxels),
// starting from an icosphere of radius 36, sigma 2 voxels constant: the surface must
// land on the sphere (mean |d| <= 0.15 voxel, max <= 0.4, no self-intersections),
// with spacing 1 and again with spacing 0.5 and a shifted origin (physical units
// honoured), and bit-identically for 1 and 2 threads.
#include "DSSurfaceInvariants.h"
#include "TestSolverMeshes.h"

#include "vtkDeformableSurfaceFilter.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"

#include <chrono>

namespace
{
vtkSmartPointer<vtkImageData> SpherePhantom(
  int n, double radiusVoxels, double spacing, const double origin[3])
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(spacing, spacing, spacing);
  image->SetOrigin(origin[0], origin[1], origin[2]);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  const double c = 0.5 * n - 0.5; // the sphere centre in index units
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double r = std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c));
        values->SetValue(i + static_cast<vtkIdType>(n) * (j + static_cast<vtkIdType>(n) * k),
          r <= radiusVoxels ? 1.0f : 0.0f);
      }
  image->GetPointData()->SetScalars(values);
  return image;
}

struct Run
{
  vtkSmartPointer<vtkPolyData> Surface;
  vtkSmartPointer<vtkTable> Table;
  double Seconds = 0;
};

Run Deform(vtkImageData* image, vtkPolyData* start, double sigma, int threads)
{
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceData(start);
  filter->SetSigma(sigma);
  filter->SetMaxLevels(0); // single level: this test is about the solver, not the hierarchy
  filter->SetMaxSweepsPerLevel(3000);
  filter->SetConvergenceTolerance(1e-4);
  filter->SetNumberOfThreads(threads);
  const auto t0 = std::chrono::steady_clock::now();
  dstest::UpdateAndCheckSurface(
    filter, "sphere phantom, " + std::to_string(threads) + " thread(s)");
  Run run;
  run.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  run.Surface = filter->GetOutput();
  run.Table = filter->GetConvergenceTable();
  return run;
}

/// Checks the distance of every vertex to the true sphere, in voxels.
void CheckSphere(
  const Run& run, const double centre[3], double radius, double spacing, const std::string& label)
{
  vtkPolyData* out = run.Surface;
  const vtkIdType n = out->GetNumberOfPoints();
  double sum = 0, maxD = 0, signedSum = 0, minSigned = 1e300, maxSigned = -1e300;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double x[3];
    out->GetPoint(i, x);
    const double r = std::sqrt((x[0] - centre[0]) * (x[0] - centre[0]) +
      (x[1] - centre[1]) * (x[1] - centre[1]) + (x[2] - centre[2]) * (x[2] - centre[2]));
    const double d = std::abs(r - radius) / spacing;
    signedSum += (r - radius) / spacing;
    minSigned = std::min(minSigned, (r - radius) / spacing);
    maxSigned = std::max(maxSigned, (r - radius) / spacing);
    sum += d;
    maxD = std::max(maxD, d);
  }
  const int sweeps = out->GetFieldData()->GetArray("Sweeps")->GetTuple1(0);
  const int selfIntersections = out->GetFieldData()->GetArray("SelfIntersections")->GetTuple1(0);
  std::cout << label << ": " << n << " vertices, " << sweeps << " sweeps, " << run.Seconds << " s"
            << std::endl;
  std::cout << "  signed distance: mean " << signedSum / std::max<vtkIdType>(n, 1) << ", range ["
            << minSigned << ", " << maxSigned << "]" << std::endl;
  DS_CHECK(n > 0, label + ": output has points");
  DS_CHECK_LE(
    sum / std::max<vtkIdType>(n, 1), 0.15, label + ": mean |distance| to the sphere (voxels)");
  DS_CHECK_LE(maxD, 0.4, label + ": max |distance| to the sphere (voxels)");
  DS_CHECK_LE(selfIntersections, 0, label + ": self-intersections");
  DS_CHECK(run.Table->GetNumberOfRows() == sweeps, label + ": one table row per sweep");
  DS_CHECK(out->GetPointData()->GetArray("Displacement") &&
      out->GetPointData()->GetArray("ExternalForce") &&
      out->GetPointData()->GetArray("ErrorIndicator") && out->GetPointData()->GetNormals(),
    label + ": point arrays present");
}
} // namespace

int TestDeformableSurfaceSphere(int, char*[])
{
  const int n = 128;
  // Spacing 1, origin 0.
  {
    const double origin[3] = { 0, 0, 0 };
    auto image = SpherePhantom(n, 32, 1.0, origin);
    const double centre[3] = { 63.5, 63.5, 63.5 };
    auto start = dstest::ToPolyData(dstest::MakeIcosphere(4, 36, { 63.5, 63.5, 63.5 }));
    const Run one = Deform(image, start, 2.0, 1);
    CheckSphere(one, centre, 32, 1.0, "spacing 1");
    const Run two = Deform(image, start, 2.0, 2);
    std::cout << "  1 thread " << one.Seconds << " s, 2 threads " << two.Seconds << " s"
              << std::endl;
    int differing = 0;
    for (vtkIdType i = 0; i < one.Surface->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      one.Surface->GetPoint(i, a);
      two.Surface->GetPoint(i, b);
      differing += (a[0] != b[0] || a[1] != b[1] || a[2] != b[2]);
    }
    DS_CHECK(
      one.Surface->GetNumberOfPoints() == two.Surface->GetNumberOfPoints(), "same point count");
    DS_CHECK_LE(differing, 0, "points differing between 1 and 2 threads");
  }
  // Spacing 0.5 and a shifted origin: the same accuracy in voxels.
  {
    const double origin[3] = { -20.25, 7.5, 103.0 };
    const double s = 0.5;
    auto image = SpherePhantom(n, 32, s, origin);
    const double centre[3] = { origin[0] + 63.5 * s, origin[1] + 63.5 * s, origin[2] + 63.5 * s };
    auto start =
      dstest::ToPolyData(dstest::MakeIcosphere(4, 36 * s, { centre[0], centre[1], centre[2] }));
    const Run run = Deform(image, start, 2.0 * s, 0);
    CheckSphere(run, centre, 32 * s, s, "spacing 0.5, shifted origin");
  }
  return dstest::Result("TestDeformableSurfaceSphere");
}

int main(int argc, char* argv[])
{
  return TestDeformableSurfaceSphere(argc, argv);
}
