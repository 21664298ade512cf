// SPDX-License-Identifier: BSD-3-Clause
// A soft ball phantom as vtkImageData, shared by the filter-level tests: value
// height / (1 + exp(2 (|x - c| - radius))) on an n^3 grid (unit spacing, origin 0), centre c
// on every axis, float point array "density" as the active scalars; SoftRadialImage the same
// with a radius that depends on the direction.
#ifndef SoftBallImage_h
#define SoftBallImage_h

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <functional>

namespace dstest
{
/// A soft star-shaped object: height / (1 + exp(2 (|x - c| - radius(x - c)))) with the radius a
/// function of the direction (the offset from the centre).
inline vtkSmartPointer<vtkImageData> SoftRadialImage(
  int n, double c, const std::function<double(double, double, double)>& radius, double height = 1.0)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double x = i - c, y = j - c, z = k - c;
        const double d = std::sqrt(x * x + y * y + z * z) - radius(x, y, z);
        values->SetValue(i + n * (j + n * static_cast<vtkIdType>(k)),
          static_cast<float>(height / (1.0 + std::exp(2.0 * d))));
      }
  image->GetPointData()->SetScalars(values);
  return image;
}

/// A ridged radius for SoftRadialImage: radius + amplitude cos(12 phi) sin(theta)^2 cos(0.6 z),
/// ridges 10-16 voxels apart on a ball of radius 30 (x, y, z: the offset from the centre).
inline double RidgedRadius(double x, double y, double z, double radius, double amplitude)
{
  const double rho = std::sqrt(x * x + y * y + z * z);
  const double s2 = rho > 0 ? (x * x + y * y) / (rho * rho) : 0.0;
  return radius + amplitude * std::cos(12.0 * std::atan2(y, x)) * s2 * std::cos(0.6 * z);
}

inline vtkSmartPointer<vtkImageData> SoftBallImage(
  int n, double c, double radius, double height = 1.0)
{
  return SoftRadialImage(
    n, c, [radius](double, double, double) { return radius; }, height);
}
} // namespace dstest

#endif
