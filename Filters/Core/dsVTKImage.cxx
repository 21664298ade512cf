#include "dsVTKImage.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"

#include <algorithm>

namespace dsurf
{
namespace
{
struct ToFloat
{
  template <typename ArrayT>
  void operator()(ArrayT* array, std::vector<float>& out) const
  {
    const auto values = vtk::DataArrayValueRange<1>(array);
    out.resize(values.size());
    std::transform(values.cbegin(), values.cend(), out.begin(),
      [](typename decltype(values)::ValueType v) { return static_cast<float>(v); });
  }
};
} // namespace

bool GetImageVolume(vtkImageData* image, vtkDataArray* scalars, ImageVolume& volume, std::string& error)
{
  if (!image || image->GetNumberOfPoints() <= 0)
  {
    error = "The input image is empty";
    return false;
  }
  ImageGeometry& g = volume.Geometry;
  image->GetDimensions(g.Dimensions);
  if (g.Dimensions[0] < 2 || g.Dimensions[1] < 2 || g.Dimensions[2] < 2)
  {
    error = "A 3-D image is needed (at least 2 voxels along every axis); got " +
      std::to_string(g.Dimensions[0]) + "x" + std::to_string(g.Dimensions[1]) + "x" +
      std::to_string(g.Dimensions[2]);
    return false;
  }
  if (!scalars)
  {
    error = "No point scalars to process: choose a point array (Scalars)";
    return false;
  }
  if (scalars->GetNumberOfComponents() != 1 || scalars->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    error = std::string("The array '") + (scalars->GetName() ? scalars->GetName() : "(unnamed)") +
      "' must be a point array with one component";
    return false;
  }
  image->GetSpacing(g.Spacing);
  const int* extent = image->GetExtent();
  image->TransformIndexToPhysicalPoint(extent[0], extent[2], extent[4], g.Origin);
  std::copy(image->GetDirectionMatrix()->GetData(), image->GetDirectionMatrix()->GetData() + 9, g.Direction);

  volume.Storage.clear();
  if (vtkFloatArray* asFloat = vtkFloatArray::FastDownCast(scalars))
  {
    volume.Values = asFloat->GetPointer(0);
  }
  else
  {
    if (!vtkArrayDispatch::Dispatch::Execute(scalars, ToFloat{}, volume.Storage))
    {
      ToFloat{}(scalars, volume.Storage);
    }
    volume.Values = volume.Storage.data();
  }
  return true;
}
} // namespace dsurf
