// SPDX-License-Identifier: BSD-3-Clause
#include "dsVTKImage.h"

#include "dsMemory.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkPointData.h"
#include "vtkType.h"

#include <algorithm>
#include <cmath>

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

std::string ArrayName(vtkDataArray* a)
{
  return a && a->GetName() ? a->GetName() : "(unnamed)";
}

/// "'A', 'B'": the point arrays with one component, the ones a user can choose.
std::string ScalarChoices(vtkImageData* image)
{
  std::string names;
  vtkPointData* pd = image->GetPointData();
  for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* a = pd->GetArray(i);
    if (a && a->GetNumberOfComponents() == 1)
    {
      names += (names.empty() ? "'" : ", '") + ArrayName(a) + "'";
    }
  }
  return names.empty() ? std::string("none") : names;
}
} // namespace

vtkDataArray* ChooseImageScalars(vtkImageData* image, vtkDataArray* selected, std::string& how)
{
  how.clear();
  if (selected || !image)
  {
    return selected;
  }
  vtkPointData* pd = image->GetPointData();
  if (vtkDataArray* active = pd->GetScalars())
  {
    how = "no array selected (or the selected one is missing): using the active point scalars '" +
      ArrayName(active) + "'";
    return active;
  }
  if (pd->GetNumberOfArrays() == 1 && pd->GetArray(0))
  {
    how = "no array selected (or the selected one is missing): using the only point array '" +
      ArrayName(pd->GetArray(0)) + "'";
    return pd->GetArray(0);
  }
  how = pd->GetNumberOfArrays() == 0
    ? "The image has no point arrays to process"
    : "No point array selected and the image has no active scalars: choose one of " +
      ScalarChoices(image) + " (Scalars)";
  return nullptr;
}

bool GetImageVolume(vtkImageData* image, vtkDataArray* scalars, double workBytesPerVoxel,
  ImageVolume& volume, std::string& error)
{
  if (!image || image->GetNumberOfPoints() <= 0)
  {
    error = "The input image is empty";
    return false;
  }
  ImageGeometry g;
  image->GetDimensions(g.Dimensions);
  if (g.Dimensions[0] < 2 || g.Dimensions[1] < 2 || g.Dimensions[2] < 2)
  {
    error = "A 3-D image is needed (at least 2 voxels along every axis); got " +
      std::to_string(g.Dimensions[0]) + "x" + std::to_string(g.Dimensions[1]) + "x" +
      std::to_string(g.Dimensions[2]);
    return false;
  }
  std::string how;
  scalars = ChooseImageScalars(image, scalars, how);
  if (!scalars)
  {
    error = how;
    return false;
  }
  volume.Note = how;
  if (scalars->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    error = "The array '" + ArrayName(scalars) + "' is not a point array of the image";
    return false;
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    error = "The array '" + ArrayName(scalars) + "' has " +
      std::to_string(scalars->GetNumberOfComponents()) +
      " components; one is needed (compute one first, e.g. its magnitude with a Calculator). "
      "Point arrays with one component: " +
      ScalarChoices(image);
    return false;
  }
  image->GetSpacing(g.Spacing);
  const int* extent = image->GetExtent();
  image->TransformIndexToPhysicalPoint(extent[0], extent[2], extent[4], g.Origin);
  std::copy(image->GetDirectionMatrix()->GetData(), image->GetDirectionMatrix()->GetData() + 9,
    g.Direction);

  // In place when the array holds its values as one contiguous array of numbers (every
  // vtkAOSDataArrayTemplate: vtkFloatArray, vtkUnsignedShortArray, ...), else a float copy.
  const bool inPlace = scalars->HasStandardMemoryLayout() && scalars->GetDataType() != VTK_BIT;
  const double voxels = static_cast<double>(image->GetNumberOfPoints());
  error = MemoryShortfall(voxels * (workBytesPerVoxel + (inPlace ? 0.0 : sizeof(float))),
    "This image of " + std::to_string(g.Dimensions[0]) + "x" + std::to_string(g.Dimensions[1]) +
      "x" + std::to_string(g.Dimensions[2]) + " voxels");
  if (!error.empty())
  {
    return false;
  }

  volume.Array = scalars;
  volume.Storage.clear();
  volume.Image = ImageView();
  if (inPlace)
  {
    switch (scalars->GetDataType())
    {
      vtkTemplateMacro(
        volume.Image = ImageView::Of(static_cast<const VTK_TT*>(scalars->GetVoidPointer(0)), g));
    }
  }
  if (!volume.Image.Data)
  {
    if (!vtkArrayDispatch::Dispatch::Execute(scalars, ToFloat{}, volume.Storage))
    {
      ToFloat{}(scalars, volume.Storage);
    }
    volume.Image = ImageView::Of(volume.Storage.data(), g);
  }
  return true;
}

std::string FirstNonFinite(std::initializer_list<std::pair<const char*, double>> parameters)
{
  for (const auto& p : parameters)
  {
    if (!std::isfinite(p.second))
    {
      return p.first;
    }
  }
  return std::string();
}
} // namespace dsurf
