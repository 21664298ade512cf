// SPDX-License-Identifier: BSD-3-Clause
// PreviewRegion of vtkDeformableSurfaceFilter (docs/METHOD.md §9.3): instead of solving, output 0
// is the boundary of the voxels the region force will grow each object through (RegionPreview,
// Core/dsRegionPreview.h), with the ranges it would use, so that a leak shows before the solve
// and the range can be tuned first.
#ifndef dsVTKRegionPreview_h
#define dsVTKRegionPreview_h

#include <string>
#include <vector>

class vtkPolyData;

namespace dsurf
{
struct ImageView;
struct MultilevelParameters;
struct TriangleMesh;

struct RegionPreviewMode
{
  bool PreviewRegion = false; ///< the filter's property of the same name (its one default)
};

/// The preview of `start` on `image` with the filter's parameters into `output`: the region's
/// boundary surface (the voxels' 0.5 iso-surface, each object's with its ObjectId when the
/// start has several) and field data IntensityRange (the first object's range),
/// ObjectIntensityRanges (several objects) and PreviewVoxels (per object). An empty surface
/// with the field data when the region force is off or reaches nothing (`warnings` says why,
/// with the range estimate's own warnings). False with `error`.
bool DeliverRegionPreview(const ImageView& image, TriangleMesh& start,
  const MultilevelParameters& parameters, vtkPolyData* output, std::string& error,
  std::vector<std::string>& warnings);
} // namespace dsurf

#endif
