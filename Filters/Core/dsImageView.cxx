// SPDX-License-Identifier: BSD-3-Clause
#include "dsImageView.h"

#include "vtkSMPTools.h"

#include <algorithm>

namespace dsurf
{
//------------------------------------------------------------------------------
double ImageGeometry::MeanExtent() const
{
  double sum = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    sum += this->Dimensions[a] * this->Spacing[a];
  }
  return sum / 3.0;
}

void ImageGeometry::IndexToWorld(const double ijk[3], double x[3]) const
{
  const double s[3] = { ijk[0] * this->Spacing[0], ijk[1] * this->Spacing[1],
    ijk[2] * this->Spacing[2] };
  const double* D = this->Direction;
  x[0] = this->Origin[0] + D[0] * s[0] + D[1] * s[1] + D[2] * s[2];
  x[1] = this->Origin[1] + D[3] * s[0] + D[4] * s[1] + D[5] * s[2];
  x[2] = this->Origin[2] + D[6] * s[0] + D[7] * s[1] + D[8] * s[2];
}

//------------------------------------------------------------------------------
VoxelBox VoxelBox::Whole(const ImageGeometry& geometry)
{
  VoxelBox box;
  std::copy(geometry.Dimensions, geometry.Dimensions + 3, box.End);
  return box;
}

ImageGeometry BoxGeometry(const ImageGeometry& image, const VoxelBox& box)
{
  ImageGeometry g = image;
  double first[3];
  for (int a = 0; a < 3; ++a)
  {
    g.Dimensions[a] = box.End[a] - box.Begin[a];
    first[a] = box.Begin[a];
  }
  image.IndexToWorld(first, g.Origin);
  return g;
}

bool VoxelBox::Contains(const VoxelBox& other) const
{
  for (int a = 0; a < 3; ++a)
  {
    if (other.Begin[a] < this->Begin[a] || other.End[a] > this->End[a])
    {
      return false;
    }
  }
  return true;
}

long long VoxelBox::NumberOfVoxels() const
{
  long long n = 1;
  for (int a = 0; a < 3; ++a)
  {
    n *= std::max(0, this->End[a] - this->Begin[a]);
  }
  return n;
}

//------------------------------------------------------------------------------
ImageView ImageView::Box(const VoxelBox& box) const
{
  ImageView view = *this;
  view.Geometry = BoxGeometry(this->Geometry, box);
  std::ptrdiff_t offset = this->RowOffset(box.Begin[1], box.Begin[2]) + box.Begin[0];
  VisitValues(*this, [&](const auto* values) { view.Data = values + offset; });
  return view;
}

bool ImageView::IsContiguousFloat() const
{
  return this->Type == ScalarType::Float32 && this->RowStride == this->Geometry.Dimensions[0] &&
    this->SliceStride == this->RowStride * this->Geometry.Dimensions[1];
}

void CopyToFloat(const ImageView& image, float* out)
{
  const int* n = image.Geometry.Dimensions;
  VisitValues(image,
    [&](const auto* values)
    {
      vtkSMPTools::For(0, n[2],
        [&](int kBegin, int kEnd)
        {
          for (int k = kBegin; k < kEnd; ++k)
          {
            for (int j = 0; j < n[1]; ++j)
            {
              const auto* row = values + image.RowOffset(j, k);
              float* o = out + (static_cast<std::ptrdiff_t>(k) * n[1] + j) * n[0];
              for (int i = 0; i < n[0]; ++i)
              {
                o[i] = AsFloat(row[i]);
              }
            }
          }
        });
    });
}

bool IsConstant(const ImageView& image, double& value)
{
  const int* n = image.Geometry.Dimensions;
  bool constant = true, first = true;
  value = 0.0;
  VisitValues(image,
    [&](const auto* values)
    {
      auto reference = values[0];
      for (int k = 0; k < n[2] && constant; ++k)
      {
        for (int j = 0; j < n[1] && constant; ++j)
        {
          const auto* row = values + image.RowOffset(j, k);
          for (int i = 0; i < n[0] && constant; ++i)
          {
            if (row[i] != row[i])
            {
              continue; // NaN is skipped, as in the range of the values
            }
            if (first)
            {
              reference = row[i];
              first = false;
            }
            constant = row[i] == reference;
          }
        }
      }
      value = static_cast<double>(reference);
    });
  return constant && !first; // no number at all is not a constant image
}
} // namespace dsurf
