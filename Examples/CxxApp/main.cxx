// SPDX-License-Identifier: BSD-3-Clause
// A C++ program linking DeformableSurface::Filters from an installed package
// (find_package(DeformableSurface)): a binary ball in a 64^3 volume, the box around
// the volume as the start, vtkDeformableSurfaceFilter with its defaults. Prints the
// result and fails when the surface is not on the ball.
#include <vtkCubeSource.h>
#include <vtkDataArray.h>
#include <vtkDeformableSurfaceFilter.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTable.h>

#include <cmath>
#include <cstdio>

int main()
{
  const int n = 64;
  const double c = 0.5 * (n - 1), radius = 16.0;
  vtkNew<vtkImageData> image;
  image->SetDimensions(n, n, n);
  image->AllocateScalars(VTK_FLOAT, 1);
  float* v = static_cast<float*>(image->GetScalarPointer());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        *v++ =
          ((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c) < radius * radius) ? 1.f : 0.f;

  vtkNew<vtkCubeSource> box;
  box->SetBounds(image->GetBounds());

  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceConnection(box->GetOutputPort());
  filter->Update();
  vtkPolyData* surface = filter->GetOutput();
  if (surface->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "no surface\n");
    return 1;
  }
  double sum = 0;
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double p[3];
    surface->GetPoint(i, p);
    sum += std::abs(
      std::sqrt((p[0] - c) * (p[0] - c) + (p[1] - c) * (p[1] - c) + (p[2] - c) * (p[2] - c)) -
      radius);
  }
  const double mean = sum / surface->GetNumberOfPoints();
  std::printf("%lld points, %lld triangles, %lld sweeps, mean |distance| to the ball %.3f voxel\n",
    static_cast<long long>(surface->GetNumberOfPoints()),
    static_cast<long long>(surface->GetNumberOfPolys()),
    static_cast<long long>(filter->GetConvergenceTable()->GetNumberOfRows()), mean);
  return mean < 0.5 ? 0 : 1;
}
