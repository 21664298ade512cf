// SPDX-License-Identifier: BSD-3-Clause
// sigma_0 from the start (docs/METHOD.md §9.1) on a distributed image (§9.8): the probe field
// (sigma one voxel, locally normalised) computed on each process's piece within the rays' reach
// of the start (InitialSigmaProbeReach; nothing on a piece beyond it), slab by slab and kept only
// at the voxels the rays can read (LocalPotentialAt, dsScaleSpace.h), equal to the serial one on
// the reached voxels the piece owns, and the rays' strengths sampled by the owners of their
// cells and summed, so every process chooses the serial sigma_0 exactly. Plain C++: the
// processes' reductions come in as callbacks (dsPieceField.h).
#ifndef dsPieceInitialSigma_h
#define dsPieceInitialSigma_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsInitialSigma.h"
#include "dsPieceField.h"

#include <string>

namespace dsurf
{
/// Ghost voxels along axis a the probe field needs around the owned voxels the rays reach: the
/// first Gaussian's (PieceGhostVoxels at one voxel of sigma) and the local normalisation's
/// second Gaussian at twice that sigma (its sampled radius); the whole axis where either is
/// recursive (an axis 3 times finer than the mean spacing, or 1.5 times for the second); at least
/// twice the coarse probe's block (CoarseProbeBlock at the paper's sigma_0, extent / 6).
DEFORMABLESURFACEFILTERS_EXPORT int InitialSigmaProbeGhostVoxels(const ImageGeometry& whole, int a);

/// The coarse probe's grid (docs/METHOD.md §9.7): that of a field at this share of the paper's
/// sigma_0 (DecimationFactor, dsFieldGrid.h): blocks of 3 from a mean extent of 432 voxels (the
/// paper's sigma_0 72 voxels), so the fine probe alone serves every smaller image.
constexpr double CoarseProbeSigmaShare = 1.0 / 8.0;
/// The coarse probe's sigma_0 is kept when it spans at least this many of its blocks (the grid
/// a field of that sigma may use, SamplesPerSigma); a start nearer its edges is probed fine.
constexpr double CoarseProbeKeptBlocks = SamplesPerSigma;

/// The block size of sigma_0's coarse probe on `whole` (1: no coarse probe).
DEFORMABLESURFACEFILTERS_EXPORT int CoarseProbeBlock(const ImageGeometry& whole, double paperSigma);

/// ChooseInitialSigma of the whole image whose piece this process holds: the same choice on
/// every process. Collective (every process calls it with the same mesh and parameters); false
/// with a message on every process when a piece the rays reach holds too few ghost layers (one
/// beyond the reach needs none), its probe does not fit in the memory available, or its probe
/// field cannot be computed, none left waiting in a reduction.
DEFORMABLESURFACEFILTERS_EXPORT bool ChoosePieceInitialSigma(const ImagePiece& piece,
  const TriangleMesh& mesh, double paperSigma, int numberOfThreads, const PieceReductions& reduce,
  InitialSigmaChoice& choice, std::string* error);
} // namespace dsurf

#endif
