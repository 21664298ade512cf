// SPDX-License-Identifier: BSD-3-Clause
// G_sigma * f of an image slab by slab along z, never the whole image at once (docs/METHOD.md
// §9.7): a fine level whose box spans most of the image keeps G_sigma * f only near the surface
// (dsFieldBricks.h), and its normalisation needs every voxel's edge strength once. Plain C++.
//
// Every value handed out equals SmoothGaussianSeparable's over the whole image bit for bit: the
// same passes on the same values in the same order (x, then y within each slice, then z).
//   Along z the sampled Gaussian (below 3 voxels of sigma) reads its radius on either side: a
//   slab is smoothed with that many more slices around it.
//   Along z the recursive filter reads the whole line: a first pass runs its forward recursion
//   up the image slab by slab and records each slab's starting state (5 doubles a line); a
//   second pass, down the image, smooths each slab again along x and y, runs the forward
//   recursion again from its recorded state (the same floats) and the backward one from the
//   state the slab above ended with (RecursiveAxisPass, as the pieces of a distributed image
//   pass theirs: dsPieceGaussian.h). The x and y passes run twice: the cost of not holding the
//   image's forward outputs.
#ifndef dsSmoothSlabs_h
#define dsSmoothSlabs_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsImageView.h"

#include <functional>

namespace dsurf
{
/// One slab of G_sigma * f: Values holds the final values of slices [First, First + Count) of
/// the image, x fastest. Slices [Core0, Core1) are the slab's own (each slice of the image is
/// one slab's own); their neighbours along z within the image are in Values too.
struct SmoothSlab
{
  const float* Values = nullptr;
  int First = 0, Count = 0, Core0 = 0, Core1 = 0;
};

/// The slices of a slab's own part by default: about sqrt(10 nz) with the recursive filter along
/// z (its recorded states, 40 bytes a line a slab, against 4 bytes a voxel of a slab), 32 or
/// four times the sampled Gaussian's radius otherwise.
DEFORMABLESURFACEFILTERS_EXPORT int DefaultSlabCore(const int dims[3], double sigmaVoxelsZ);

/// G_sigma * f of `image` (any value type), sigmaVoxels[a] voxels along axis a: visit(slab) for
/// slabs whose own slices cover the image, coreSlices each (0: DefaultSlabCore); upwards along z
/// with the sampled Gaussian along z, downwards with the recursive one. In the caller's SMP
/// scope (the passes run in parallel; the slabs one after another, so the visits need no lock).
DEFORMABLESURFACEFILTERS_EXPORT void SmoothInSlabs(const ImageView& image,
  const double sigmaVoxels[3], int coreSlices, const std::function<void(const SmoothSlab&)>& visit);

/// Bytes SmoothInSlabs holds at most for an image of `geometry` at `sigma` (world units).
DEFORMABLESURFACEFILTERS_EXPORT double SmoothInSlabsBytes(
  const ImageGeometry& geometry, double sigma, int coreSlices);
} // namespace dsurf

#endif
