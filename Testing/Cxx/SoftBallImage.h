// A soft ball phantom as vtkImageData, shared by the filter-level tests: value
// height / (1 + exp(2 (|x - c| - radius))) on an n^3 grid (unit spacing, origin 0), centre c
// on every axis, float point array "density" as the active scalars.
#ifndef SoftBallImage_h
#define SoftBallImage_h

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <cmath>

namespace dstest
{
inline vtkSmartPointer<vtkImageData> SoftBallImage(
  int n, double c, double radius, double height = 1.0)
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
        const double d = std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c));
        values->SetValue(i + n * (j + n * static_cast<vtkIdType>(k)),
          static_cast<float>(height / (1.0 + std::exp(2.0 * (d - radius)))));
      }
  image->GetPointData()->SetScalars(values);
  return image;
}
} // namespace dstest

#endif
