// SPDX-License-Identifier: BSD-3-Clause
// G_sigma * f on a piece of a distributed image (docs/METHOD.md §6c, §9.8): the serial
// separable Gaussian (dsGaussianSmoother.h) with the recursive filter's state passed from piece
// to piece, so that every process gets the serial values on its voxels, bit for bit, without
// holding the whole axis. Plain C++: the processes meet through PieceReductions::Sum only.
//
// Along an axis with the recursive filter (3 voxels of sigma and more) the forward pass of a
// piece whose voxels do not start at the cut's first starts from the state, at the voxel before
// its first, of the piece counting that voxel (ImagePiece::CountedVoxels: exactly one per
// voxel); the backward pass likewise from the state after its last. The cut's two ends keep the
// serial start (the replicated first sample, Triggs & Sdika's at the last), on the piece
// holding them. One sum carries one such plane of states: every process contributes -0.0 where
// it does not count the voxel (x + -0.0 == x bit for bit, for x = -0.0 too), so the sum is the
// counting piece's state exactly. The pieces start in as many rounds as they have distinct
// first voxels along the axis (and end in as many as distinct last ones): one round with two
// slabs, 2 with three slabs; a brick split also along another axis adds rounds there. A sum is
// the only collective the core has (the force exchange, the block means and the edge maximum
// use it too); a point-to-point hook would send 1/P of the data, which at these plane sizes
// (5 doubles per voxel of the cut's cross-section, a few per level) is not worth a second kind
// of callback.
#ifndef dsPieceGaussian_h
#define dsPieceGaussian_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsPieceField.h"

#include <functional>
#include <memory>
#include <vector>

namespace dsurf
{
/// One recursive pass along an axis over a process's region, as the rounds run it: Forward, then
/// Backward, each from the state at the region's end (null: the cut's end, the serial start),
/// recording each line's state after the given positions along the axis (region indices), as
/// RecursiveAxisPass does on a volume held whole (dsPieceSlabs.h runs it slab by slab).
class DEFORMABLESURFACEFILTERS_EXPORT PieceAxisRun
{
public:
  virtual ~PieceAxisRun() = default;
  virtual void Forward(const double* start, const std::vector<int>& record,
    std::vector<std::vector<double>>& recorded) = 0;
  virtual void Backward(const double* ahead, const std::vector<int>& record,
    std::vector<std::vector<double>>& recorded) = 0;
};

/// The rounds of SmoothPieceGaussian without its arithmetic: for each axis a in order (z, x, y)
/// whose filter is recursive and along which the pieces' regions start or end at different voxels,
/// the runs and the sums that pass the states between them, runOf(a) making this process's run
/// along a (called once per such axis; null with no region); `uncut(a)` is called for every
/// other axis (the serial pass there). Every process makes the same sums whatever its runs do.
/// Collective.
DEFORMABLESURFACEFILTERS_EXPORT void PieceGaussianRounds(const ImagePiece& piece,
  const VoxelBox& cut, const VoxelBox& region, bool hasRegion, const double sigmaVoxels[3],
  const std::function<std::unique_ptr<PieceAxisRun>(int axis)>& runOf,
  const std::function<void(int axis)>& uncut, const PieceReductions& reduce);

/// G_sigma * f, sigmaVoxels[a] voxels along axis a, of the voxels `region` (whole-image indices,
/// within `cut`) that this process holds of `piece`, in place in `volume` (region's voxels, x
/// fastest): on the region's voxels farther than the sampled Gaussian's radius from the
/// region's sides within the cut (along sampled axes; every voxel along recursive ones), equal
/// bit for bit to SmoothGaussianSeparable over the whole cut. Collective: every process calls it
/// alike; one with nothing to smooth (no voxel of the cut, or a failure before) passes a null
/// volume and still takes part in the sums.
DEFORMABLESURFACEFILTERS_EXPORT void SmoothPieceGaussian(const ImagePiece& piece,
  const VoxelBox& cut, const VoxelBox& region, float* volume, const double sigmaVoxels[3],
  const PieceReductions& reduce);
} // namespace dsurf

#endif
