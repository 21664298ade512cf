// SPDX-License-Identifier: BSD-3-Clause
// The image as the core reads it: where its voxels are (ImageGeometry), a box of them (VoxelBox)
// and their values in the input's own type (ImageView), never a float copy of the whole volume
// (docs/METHOD.md §9.6-9.7: a 1024^3 uint16 CT is 2 GiB, its float copy would be 4 more).
// Every reader converts a value to float as it reads it (AsFloat): the conversion a float copy
// made, so results do not depend on whether the input was copied. Plain C++.
#ifndef dsImageView_h
#define dsImageView_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTrilinear.h"

#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace dsurf
{
/// Where the voxels are: world = Origin + Direction * (Spacing .* ijk).
/// Direction is row-major 3x3 and must be orthonormal (VTK's vtkImageData direction
/// matrix; ComputeScaleSpaceForce rejects anything else).
struct DEFORMABLESURFACEFILTERS_EXPORT ImageGeometry
{
  int Dimensions[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  double Origin[3] = { 0, 0, 0 };
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };

  long long NumberOfVoxels() const
  {
    return static_cast<long long>(this->Dimensions[0]) * this->Dimensions[1] * this->Dimensions[2];
  }
  /// Mean physical extent (the paper's "average extent of the volume"):
  /// mean over the axes of Dimensions[a] * Spacing[a], so a 256^3 unit-spacing
  /// volume has extent 256 and sigma = extent / 6 = 42.7.
  double MeanExtent() const;
  /// The voxel size, the mean spacing: the finest detail the image shows.
  double MeanSpacing() const
  {
    return (this->Spacing[0] + this->Spacing[1] + this->Spacing[2]) / 3.0;
  }
  /// World point -> continuous index (i,j,k). Inline: every force and image sample of the
  /// sweep starts here (an exported member is otherwise called through the PLT).
  void WorldToIndex(const double x[3], double ijk[3]) const
  {
    const double d[3] = { x[0] - this->Origin[0], x[1] - this->Origin[1], x[2] - this->Origin[2] };
    const double* D = this->Direction;
    // Orthonormal direction: its inverse is its transpose.
    ijk[0] = (D[0] * d[0] + D[3] * d[1] + D[6] * d[2]) / this->Spacing[0];
    ijk[1] = (D[1] * d[0] + D[4] * d[1] + D[7] * d[2]) / this->Spacing[1];
    ijk[2] = (D[2] * d[0] + D[5] * d[1] + D[8] * d[2]) / this->Spacing[2];
  }
  /// Continuous index -> world point.
  void IndexToWorld(const double ijk[3], double x[3]) const;
};

/// A box of voxels, [Begin, End) along each axis.
struct DEFORMABLESURFACEFILTERS_EXPORT VoxelBox
{
  int Begin[3] = { 0, 0, 0 };
  int End[3] = { 0, 0, 0 };
  /// The whole image.
  static VoxelBox Whole(const ImageGeometry& geometry);
  bool Contains(const VoxelBox& other) const;
  long long NumberOfVoxels() const;
};

/// The geometry of the voxels of `box` of an image of geometry `image`: their dimensions, and the
/// origin at the box's first voxel.
DEFORMABLESURFACEFILTERS_EXPORT ImageGeometry BoxGeometry(
  const ImageGeometry& image, const VoxelBox& box);

/// The value types an image can hold.
enum class ScalarType
{
  Float32,
  Float64,
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Int64,
  UInt64
};

/// The ScalarType of C++ type T (any arithmetic type of 1, 2, 4 or 8 bytes).
template <typename T>
constexpr ScalarType ScalarTypeOf()
{
  static_assert(std::is_arithmetic<T>::value && sizeof(T) <= 8, "a number of at most 8 bytes");
  return std::is_floating_point<T>::value
    ? (sizeof(T) == 4 ? ScalarType::Float32 : ScalarType::Float64)
    : sizeof(T) == 1 ? (std::is_signed<T>::value ? ScalarType::Int8 : ScalarType::UInt8)
    : sizeof(T) == 2 ? (std::is_signed<T>::value ? ScalarType::Int16 : ScalarType::UInt16)
    : sizeof(T) == 4 ? (std::is_signed<T>::value ? ScalarType::Int32 : ScalarType::UInt32)
                     : (std::is_signed<T>::value ? ScalarType::Int64 : ScalarType::UInt64);
}

/// A value as the core computes with it.
template <typename T>
inline float AsFloat(T value)
{
  return static_cast<float>(value);
}

/// An image's values in their own type, read in place: Geometry describes the view's own
/// voxels (Dimensions, and Origin at its first voxel), so a view can be a whole image, a piece
/// of one (a rank's part of a distributed volume) or a box of another view, without copying.
/// x is contiguous; rows and slices lie RowStride and SliceStride values apart.
struct DEFORMABLESURFACEFILTERS_EXPORT ImageView
{
  ImageGeometry Geometry;
  const void* Data = nullptr;
  ScalarType Type = ScalarType::Float32;
  std::ptrdiff_t RowStride = 0, SliceStride = 0;

  /// values: one per voxel of geometry, x fastest, contiguous.
  template <typename T>
  static ImageView Of(const T* values, const ImageGeometry& geometry)
  {
    ImageView view;
    view.Geometry = geometry;
    view.Data = values;
    view.Type = ScalarTypeOf<T>();
    view.RowStride = geometry.Dimensions[0];
    view.SliceStride = view.RowStride * geometry.Dimensions[1];
    return view;
  }
  /// The voxels of `box` (within this view) as a view of their own.
  ImageView Box(const VoxelBox& box) const;
  /// The values are one contiguous float array (usable as a float volume as they are).
  bool IsContiguousFloat() const;
  /// Offset (in values) of voxel (0, j, k).
  std::ptrdiff_t RowOffset(int j, int k) const
  {
    return j * this->RowStride + k * this->SliceStride;
  }
};

/// Calls visit(const T* values) with the view's values in their own type T.
template <typename Visit>
void VisitValues(const ImageView& image, Visit&& visit)
{
  switch (image.Type)
  {
    case ScalarType::Float32:
      visit(static_cast<const float*>(image.Data));
      break;
    case ScalarType::Float64:
      visit(static_cast<const double*>(image.Data));
      break;
    case ScalarType::Int8:
      visit(static_cast<const std::int8_t*>(image.Data));
      break;
    case ScalarType::UInt8:
      visit(static_cast<const std::uint8_t*>(image.Data));
      break;
    case ScalarType::Int16:
      visit(static_cast<const std::int16_t*>(image.Data));
      break;
    case ScalarType::UInt16:
      visit(static_cast<const std::uint16_t*>(image.Data));
      break;
    case ScalarType::Int32:
      visit(static_cast<const std::int32_t*>(image.Data));
      break;
    case ScalarType::UInt32:
      visit(static_cast<const std::uint32_t*>(image.Data));
      break;
    case ScalarType::Int64:
      visit(static_cast<const std::int64_t*>(image.Data));
      break;
    case ScalarType::UInt64:
      visit(static_cast<const std::uint64_t*>(image.Data));
      break;
  }
}

/// Calls row(j, k, values) for every row of the view, values pointing at its first voxel.
template <typename Row>
void ForEachRow(const ImageView& image, Row&& row)
{
  VisitValues(image,
    [&](const auto* values)
    {
      for (int k = 0; k < image.Geometry.Dimensions[2]; ++k)
      {
        for (int j = 0; j < image.Geometry.Dimensions[1]; ++j)
        {
          row(j, k, values + image.RowOffset(j, k));
        }
      }
    });
}

/// Whether the image has a number (NaN skipped) and every one equals the first, which `value`
/// receives: an image without a boundary to find. Stops at the first other value, so
/// it costs next to nothing on a real image.
DEFORMABLESURFACEFILTERS_EXPORT bool IsConstant(const ImageView& image, double& value);

/// The trilinear cell of world point x in an image of `geometry` whose values lie `increments`
/// apart (nullptr: contiguous). A voxel covers half a spacing around its centre, so the volume
/// reaches half a voxel beyond the outermost centres (the image bounds); there the border value
/// is used. A start box at the image bounds thus feels the force at every vertex.
inline bool LocateImageCell(const ImageGeometry& geometry, const double x[3], TrilinearCell& cell,
  const std::ptrdiff_t* increments = nullptr)
{
  double ijk[3];
  geometry.WorldToIndex(x, ijk);
  const int lo[3] = { 0, 0, 0 };
  const int hi[3] = { geometry.Dimensions[0] - 1, geometry.Dimensions[1] - 1,
    geometry.Dimensions[2] - 1 };
  return LocateTrilinearCell(ijk, lo, hi, 0.5, cell, increments);
}

/// The view's values as floats into `out` (NumberOfVoxels of them, x fastest, contiguous). Its
/// loop runs with vtkSMPTools: the caller's SMP scope sets the threads.
DEFORMABLESURFACEFILTERS_EXPORT void CopyToFloat(const ImageView& image, float* out);

/// The trilinear sample of the view's values in `cell` (ids into the view's values). Inline, as
/// SampleVolume, for the solver's per-vertex region sample.
inline double SampleCell(const ImageView& image, const TrilinearCell& cell)
{
  double v = 0.0;
  VisitValues(image,
    [&](const auto* values)
    {
      for (int corner = 0; corner < 8; ++corner)
      {
        v += cell.Weight(corner) * AsFloat(values[cell.Corner(corner)]);
      }
    });
  return v;
}

/// Trilinear sample of the view at world point x, reaching half a voxel past the outermost
/// centres (there the border value is used); 0 and *inside = false further out.
inline double SampleVolume(const ImageView& image, const double x[3], bool* inside)
{
  TrilinearCell c;
  const std::ptrdiff_t increments[3] = { 1, image.RowStride, image.SliceStride };
  const bool in = image.Data && LocateImageCell(image.Geometry, x, c, increments);
  if (inside)
  {
    *inside = in;
  }
  return in ? SampleCell(image, c) : 0.0;
}
} // namespace dsurf

#endif
