// SPDX-License-Identifier: BSD-3-Clause
// The one bridge from VTK image data into the plain-C++ core (Filters/Core): the checks,
// geometry and the values (in their own type) that the three filters need. It uses VTK data types,
// so it lives beside the VTK classes, not in the core.
#ifndef dsVTKImage_h
#define dsVTKImage_h

#include "dsScaleSpace.h"

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

class vtkDataArray;
class vtkImageData;

namespace dsurf
{
/// A volume as the core sees it: geometry and the values in their own type (dsImageView.h).
struct ImageVolume
{
  /// The input's own memory, unless its array keeps its values in another layout (not one
  /// contiguous array of numbers, e.g. vtkSOADataArrayTemplate or a bit array): then Storage.
  ImageView Image;
  std::vector<float> Storage;
  vtkDataArray* Array = nullptr; ///< the array the values come from
  std::string Note;              ///< how the array was chosen when it was a fallback
};

/// The point array a filter works on: `selected` (what SetInputArrayToProcess / ParaView's
/// Scalars names) when it exists; otherwise, e.g. when the name is empty because the pvpython
/// reader had not run yet when the filter was made, the image's active point scalars, else
/// its only point array. nullptr when there is none; `how` then says why, and says which
/// array was taken when it fell back (for a debug line).
vtkDataArray* ChooseImageScalars(vtkImageData* image, vtkDataArray* selected, std::string& how);

/// Check that `image` is a 3-D image (>= 2 voxels per axis) and `scalars` one of its
/// one-component point arrays (ChooseImageScalars when `scalars` is nullptr); fill the geometry
/// (index 0 = the first voxel of the extent; spacing, origin and direction honoured) and the values
/// (read in place in their own type; converted to float only when the array does not hold them
/// as one contiguous array). workBytesPerVoxel: what the caller will allocate per voxel beyond
/// the image; with a conversion it must fit in the memory available, checked before anything is
/// allocated. Returns false with a user-facing message.
bool GetImageVolume(vtkImageData* image, vtkDataArray* scalars, double workBytesPerVoxel,
  ImageVolume& volume, std::string& error);

/// The name of the first of the filter's (name, value) parameters that is not finite, or
/// empty. vtkSetClampMacro lets NaN through (every comparison with it is false), and a NaN
/// parameter would silently become a fallback (a Sigma of NaN reads as "choose one"), a solve
/// that never converges (ConvergenceTolerance) or NaN coordinates (Tau).
std::string FirstNonFinite(std::initializer_list<std::pair<const char*, double>> parameters);
} // namespace dsurf

#endif
