// SPDX-License-Identifier: BSD-3-Clause
// Phantom builders shared by the TestScaleSpace*.cxx tests.
#ifndef ScaleSpaceTestUtils_h
#define ScaleSpaceTestUtils_h

#include "dsScaleSpace.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <functional>
#include <vector>

namespace sstest
{
/// value(world point) at every voxel of the core's geometry g (x fastest).
inline std::vector<float> SampleOnGrid(
  const dsurf::ImageGeometry& g, const std::function<double(const double*)>& value)
{
  std::vector<float> values(static_cast<std::size_t>(g.NumberOfVoxels()));
  for (int k = 0; k < g.Dimensions[2]; ++k)
    for (int j = 0; j < g.Dimensions[1]; ++j)
      for (int i = 0; i < g.Dimensions[0]; ++i)
      {
        const double ijk[3] = { double(i), double(j), double(k) };
        double x[3];
        g.IndexToWorld(ijk, x);
        values[i + g.Dimensions[0] * (j + static_cast<std::size_t>(g.Dimensions[1]) * k)] =
          static_cast<float>(value(x));
      }
  return values;
}

/// A ball of radius r around world point c with a soft edge (width ~1 voxel): the value
/// 1 / (1 + exp(2 (|x - c| - r))) at every voxel of g.
inline std::vector<float> SoftBall(const dsurf::ImageGeometry& g, const double c[3], double r)
{
  return SampleOnGrid(g,
    [&](const double* x)
    {
      const double d = std::sqrt((x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) +
        (x[2] - c[2]) * (x[2] - c[2]));
      return 1.0 / (1.0 + std::exp(2.0 * (d - r)));
    });
}

/// A float image whose point scalars "f" are value(world point) at every voxel.
inline vtkSmartPointer<vtkImageData> MakeImage(const int extent[6], const double spacing[3],
  const double origin[3], const double direction[9],
  const std::function<double(const double*)>& value)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetExtent(const_cast<int*>(extent));
  image->SetSpacing(spacing[0], spacing[1], spacing[2]);
  image->SetOrigin(origin[0], origin[1], origin[2]);
  image->SetDirectionMatrix(direction);
  vtkNew<vtkFloatArray> f;
  f->SetName("f");
  f->SetNumberOfTuples(image->GetNumberOfPoints());
  vtkIdType id = 0;
  for (int k = extent[4]; k <= extent[5]; ++k)
  {
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      for (int i = extent[0]; i <= extent[1]; ++i, ++id)
      {
        double x[3];
        image->TransformIndexToPhysicalPoint(i, j, k, x);
        f->SetValue(id, static_cast<float>(value(x)));
      }
    }
  }
  image->GetPointData()->SetScalars(f);
  return image;
}

/// Row-major rotation: about z by a, then about x by b (R = Rx(b) Rz(a)).
inline void Rotation(double a, double b, double R[9])
{
  const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b);
  const double Rz[9] = { ca, -sa, 0, sa, ca, 0, 0, 0, 1 };
  const double Rx[9] = { 1, 0, 0, 0, cb, -sb, 0, sb, cb };
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      R[3 * r + c] = 0;
      for (int m = 0; m < 3; ++m)
      {
        R[3 * r + c] += Rx[3 * r + m] * Rz[3 * m + c];
      }
    }
  }
}
} // namespace sstest

#endif
