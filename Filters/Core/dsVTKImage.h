// The one bridge from VTK image data into the plain-C++ core: the checks, geometry and
// float scalars that vtkImageScaleSpaceGradient and vtkDeformableSurfaceFilter both need.
// (Everything else in Filters/Core is free of VTK types.)
#ifndef dsVTKImage_h
#define dsVTKImage_h

#include "dsScaleSpace.h"

#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;

namespace dsurf
{
/// A volume as the core sees it: geometry and one float per voxel (x fastest).
struct ImageVolume
{
  ImageGeometry Geometry;
  const float* Values = nullptr; ///< the input's own memory for float arrays, else Storage
  std::vector<float> Storage;
};

/// Check that `image` is a 3-D image (>= 2 voxels per axis) and `scalars` one of its
/// one-component point arrays; fill the geometry (index 0 = the first voxel of the
/// extent; spacing, origin and direction honoured) and the values (float input is used
/// in place, any other type converted). Returns false with a user-facing message.
bool GetImageVolume(vtkImageData* image, vtkDataArray* scalars, ImageVolume& volume, std::string& error);
} // namespace dsurf

#endif
