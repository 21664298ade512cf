// SPDX-License-Identifier: BSD-3-Clause
// G_sigma * f of a process's region of a distributed image slab by slab along z, never the
// region whole (docs/METHOD.md §9.7, §9.8): a piece keeps a fine level's field in tiles near the
// surface, as a serial box of more than half the image does (dsSmoothSlabs.h). Plain C++.
//
// Two stages.
// - GatherPieceSmoothing makes the sums of SmoothPieceGaussian (dsPieceGaussian.h: the same
//   rounds, so each process may take either way) with runs that stream the region slab by slab
//   and keep no values: each records the states other pieces go on from and keeps those it was
//   started from, the region's AxisEnds along each axis it is cut along.
// - SmoothPieceInSlabs then smooths the region slab by slab from those ends, with no sums: as
//   often as the field's tiles are made again (FieldBricks), on this process alone.
// A slab's z pass is SmoothSlabsOf's (RecursiveSlabsZ from the ends along z where z's filter is
// recursive), its x and y passes start each line from its ends (a slab's lines along x, or along
// y, are a contiguous run of the region's), so every value equals SmoothPieceGaussian's, and the
// serial image's, bit for bit. The cost of not holding the region: each round a process runs in
// reads the region again, a run along z its slices (twice for the backward one), a run along x or
// y its slabs smoothed along z (up and down the slabs, for the recursive filter) and, for y,
// along x.
#ifndef dsPieceSlabs_h
#define dsPieceSlabs_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsPieceField.h"
#include "dsSmoothSlabs.h"

#include <functional>

namespace dsurf
{
/// What a process needs to smooth its region alone: the sigma in voxels per axis, the axes with
/// rounds (where the region's lines go on in other pieces, or where the serial pass is
/// RecursiveAxisPass's: dsPieceGaussian.h), and their states at the region's ends.
struct DEFORMABLESURFACEFILTERS_EXPORT PieceSmoothing
{
  double SigmaVoxels[3] = { 0.0, 0.0, 0.0 };
  bool Rounds[3] = { false, false, false };
  AxisEnds Ends[3];
};

/// The PieceSmoothing of `region` (whole-image indices within `cut`, the voxels `regionImage`
/// views; null when this process has nothing to smooth, which still takes part in the sums),
/// its runs streaming slabs of coreSlices slices (0: DefaultSlabCore) on numberOfThreads
/// threads (0: the machine's). Collective, with the same sums as SmoothPieceGaussian.
DEFORMABLESURFACEFILTERS_EXPORT PieceSmoothing GatherPieceSmoothing(const ImagePiece& piece,
  const VoxelBox& cut, const VoxelBox& region, const ImageView* regionImage,
  const double sigmaVoxels[3], int coreSlices, int numberOfThreads, const PieceReductions& reduce);

/// Bytes a PieceSmoothing of `region` holds at most: the states of both ends along every axis.
DEFORMABLESURFACEFILTERS_EXPORT double PieceSmoothingBytes(const VoxelBox& region);

/// SmoothInSlabs of the region: visit(slab) for slabs whose own slices cover it (coreSlices
/// each, 0: DefaultSlabCore), every value SmoothPieceGaussian's bit for bit. Local. In the
/// caller's SMP scope.
DEFORMABLESURFACEFILTERS_EXPORT void SmoothPieceInSlabs(const ImageView& regionImage,
  const PieceSmoothing& smoothing, int coreSlices,
  const std::function<void(const SmoothSlab&)>& visit);
} // namespace dsurf

#endif
