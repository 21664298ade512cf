// SPDX-License-Identifier: BSD-3-Clause
// What the region force will grow through, before the solve (docs/METHOD.md §9.3): the voxels
// each object's model accepts, connected to its start, as ITK-SNAP shows the region a threshold
// selects before its snake runs. A leak through a thin gap shows before solving. Plain C++.
#ifndef dsRegionPreview_h
#define dsRegionPreview_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsImageView.h"
#include "dsMultilevel.h"
#include "dsTriangleMesh.h"

#include <vector>

namespace dsurf
{
/// Bytes per voxel of the image the preview holds at most: the labels, one object's mask at a
/// time while its surface is made (dsVTKRegionPreview.h) and the contour's edge cases (a byte a
/// voxel), and the seeds and a ring of voxel ids, each at most every voxel (a start enclosing
/// most of the image); checked before anything is allocated.
constexpr double PreviewBytesPerVoxel = sizeof(unsigned short) + 1 + 1 + 2 * sizeof(long long);

/// Per voxel of `image` (x fastest): 0, or 1 + the index of the object whose region reaches it.
/// An object's region: the voxels whose value lies in its range (regions[o], when On) and that
/// join, through 6-neighbours that do too, a voxel inside its start surface (the part of `start`
/// of object o; mesh.Objects) or, for a start enclosing no voxel centre in its range, the voxel
/// nearest one of its points. All objects grow at once, one neighbour ring per step, so where
/// two regions meet each keeps the voxels nearer its start. `counts` receives each object's
/// voxels.
DEFORMABLESURFACEFILTERS_EXPORT std::vector<unsigned short> RegionPreview(const ImageView& image,
  const TriangleMesh& start, const std::vector<ObjectRegion>& regions,
  std::vector<long long>& counts);
} // namespace dsurf

#endif
