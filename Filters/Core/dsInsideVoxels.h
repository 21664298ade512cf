// SPDX-License-Identifier: BSD-3-Clause
// The voxels whose centres lie inside a closed triangle mesh, row by row (scan-line parity):
// the intensity range's estimate samples them (dsRegion.h), the region preview starts from
// them (dsRegionPreview.h). Plain C++.
#ifndef dsInsideVoxels_h
#define dsInsideVoxels_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsFieldGrid.h"
#include "dsScaleSpace.h"
#include "dsTriangleMesh.h"

#include <vector>

namespace dsurf
{
/// A start far outside the image has indices beyond int: clamped in double to [-1, n] first.
inline int ClampedIndex(double x, int n)
{
  return static_cast<int>(std::min(static_cast<double>(n), std::max(-1.0, x)));
}

/// For every voxel row (j, k) of `rows` (whole-image indices of geometry g), the x indices
/// (continuous) where the row's line crosses the mesh's triangles, sorted: the centres between
/// the 1st and 2nd, 3rd and 4th... crossing are inside (parity). Row (j, k) is entry
/// (j - rows.Begin[1]) + (rows.End[1] - rows.Begin[1]) * (k - rows.Begin[2]). In continuous
/// index space, so spacing and direction are honoured, and every process of a distributed
/// image finds the same crossings for a row.
DEFORMABLESURFACEFILTERS_EXPORT std::vector<std::vector<double>> RowCrossings(
  const ImageGeometry& g, const VoxelBox& rows, const TriangleMesh& mesh);
} // namespace dsurf

#endif
