// SPDX-License-Identifier: BSD-3-Clause
// The grid a level's force field lives on (docs/METHOD.md §9.7). Memory and time follow the
// surface and its scale, not the volume:
// - coarse scales on coarse grids: a field at sigma needs no more than a few samples per
//   sigma, so a level whose sigma spans many voxels computes it on a grid of f x f x f blocks
//   of the image, each replaced by its mean, smoothed with the remaining sigma (f^3 times less
//   memory and time; the first levels of a 512^3 volume, sigma 85, 42, 21, 11 voxels, shrink
//   to grids of 19^3-171^3);
// - after the first level, only the surface's neighbourhood: the surface then lies near its
//   object and moves a few sigma at most, so the field covers its bounding box grown by
//   NeighbourhoodSigmas sigma (the reach and the Gaussian's support) and no more; on the image's
//   own grid the first level's too, made again as the surface travels (FieldGrowthShare).
// Plain C++.
#ifndef dsFieldGrid_h
#define dsFieldGrid_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsScaleSpace.h"
#include "dsTriangleMesh.h"

#include <vector>

namespace dsurf
{
/// Grid points per sigma kept on a coarse grid: the block size is the largest odd f with
/// f <= sigma / (SamplesPerSigma * spacing) on every axis (1 = the image's own grid), so blocks
/// of 3 from sigma = 9 voxels. At three samples per sigma the Gaussian loses exp(-pi^2 9 / 2)
/// (5e-20) of its amplitude at the grid's Nyquist frequency and the box holds < 1 % of the
/// variance (RemainingSigma); the force differs from the full grid's by 3.3 % of its largest
/// value within sigma / 2 of an edge (TestFieldGrid; 2.9 % at four samples per sigma).
constexpr double SamplesPerSigma = 3.0;

/// The block size for a field at `sigma` (world units) on `geometry`.
DEFORMABLESURFACEFILTERS_EXPORT int DecimationFactor(double sigma, const ImageGeometry& geometry);

/// The blocks of BlockMeans along an axis of n voxels: Count blocks of f = 2h + 1 voxels, block
/// I centred on voxel First + I f, with as many voxels left over at each end of the axis (one
/// more at the far end when their number is odd), which the end blocks take in.
struct DEFORMABLESURFACEFILTERS_EXPORT AxisBlocks
{
  int Voxels = 0, Factor = 1, Count = 0, First = 0;
  AxisBlocks(int n, int f);
  /// The voxels [begin, end) of block I.
  void Range(int I, int& begin, int& end) const;
};

/// The mean of each f^3 block of `image` (f odd, each block centred on a voxel, the blocks at
/// the ends of an axis also taking in the few voxels left over there; the values read in their
/// own type) into `coarse`, whose geometry places each coarse voxel on its block's centre
/// voxel, with spacing f times the image's.
DEFORMABLESURFACEFILTERS_EXPORT void BlockMeans(const ImageView& image, int f,
  std::vector<float>& coarse, ImageGeometry& coarseGeometry, int numberOfThreads);

/// The sigma left to smooth the block means with so that box and Gaussian together have the
/// variance sigma^2 along the axis where the box adds the most, (f^2 - 1) / 12 spacing^2
/// (the variance of a discrete box of f samples). With f <= sigma / 4 voxels the box holds
/// at most 0.5 % of the variance, and box then Gaussian is Gaussian well within the
/// discretisation error of the coarse grid.
DEFORMABLESURFACEFILTERS_EXPORT double RemainingSigma(
  double sigma, const ImageGeometry& geometry, int f);

/// How far, in sigmas, the field reaches past the surface's bounding box (after the first
/// level, and on the first one when its box follows the surface): 4 sigma of the Gaussian's support
/// (its tail beyond holds < 1e-4 of the weight), so the cut does not change the field where the
/// surface is, and 2 sigma the surface may move.
constexpr double NeighbourhoodSigmas = 6.0;
/// The same with the local edge normalisation, whose second Gaussian (2 sigma) reaches 8 sigma.
constexpr double NeighbourhoodSigmasLocal = 10.0;

/// NeighbourhoodSigmas (or NeighbourhoodSigmasLocal with the local edge normalisation) times
/// sigma: how far a level's field reaches past the surface.
DEFORMABLESURFACEFILTERS_EXPORT double FieldReach(EdgeNormalization normalization, double sigma);

/// A first level on the image's own grid, whose surface may travel far (a click grown by the region
/// force), covers the surface's neighbourhood and, each time the surface nears its side, a new box
/// grown by this share of the surface's largest extent on every side: a surface growing on all
/// sides from a click r voxels wide to an object R wide is boxed again about log(R / r) / log(1.5)
/// times (growing on one side, log(R / r) / log(1.25)), and the boxes' voxels sum to a small
/// multiple of the last box's (MultilevelSolver::FollowSurface).
constexpr double FieldGrowthShare = 0.25;

/// The voxels within `reach` (world units, plus one voxel) of the mesh's bounding box in
/// index space, clipped to the image.
DEFORMABLESURFACEFILTERS_EXPORT VoxelBox SurfaceNeighbourhood(
  const TriangleMesh& mesh, const ImageGeometry& geometry, double reach);

/// The part of an image of geometry `whole` a field at `sigma` over `box` is computed on: the
/// box (a view: no copy) on the image's own grid, whatever its share of the image, so that a field
/// there covers the surface's neighbourhood and no more (the whole image only when that spans
/// it); on a coarse grid, the whole image when the box holds more than half of it (one small
/// field of the whole image at most).
DEFORMABLESURFACEFILTERS_EXPORT VoxelBox FieldCut(
  const VoxelBox& box, const ImageGeometry& whole, double sigma);

/// FieldCut's part of an image of geometry `whole` for a field at `sigma` over `box` (into `cut`)
/// and the block size of its grid there (DecimationFactor; 1: the image's own grid), as
/// ComputeForceAtScale and ComputePieceForce choose them.
DEFORMABLESURFACEFILTERS_EXPORT int FieldCutFactor(
  const VoxelBox& box, const ImageGeometry& whole, double sigma, VoxelBox& cut);

/// The voxels of a field's grid over `cut` with block size f (BlockMeans's blocks, at most one
/// more per axis than whole blocks; the cut's own voxels for f = 1).
DEFORMABLESURFACEFILTERS_EXPORT double FieldGridVoxels(const VoxelBox& cut, int f);

/// Whether a field at `parameters` over `box` of an image of geometry `whole` is kept in bricks
/// around a surface (ComputeForceAtScale, ComputePieceForce with a surface): on the image's own
/// grid. The same on every process of a distributed solve.
DEFORMABLESURFACEFILTERS_EXPORT bool FieldInBricks(
  const VoxelBox& box, const ImageGeometry& whole, const ScaleSpaceParameters& parameters);

/// Bytes a voxel of a field's grid holds at most: P and -grad P (ForceFieldBytesPerVoxel) and a
/// float besides, the block means of a coarse grid or, `bricked`, the smoothed part kept for the
/// bricks, which hold their shared layers twice ((BrickSize + 1)^3 values for BrickSize^3 voxels;
/// FieldBricks::DropUnreachedOverBudget drops the bricks no vertex needs beyond the part's voxels).
DEFORMABLESURFACEFILTERS_EXPORT double FieldBytesPerVoxel(bool bricked);

/// The bytes a field at `parameters` over `box` of an image of geometry `whole` holds
/// (ComputeForceAtScale): at most FieldBytesPerVoxel over FieldCut's part on its grid (for a
/// field smoothed in slabs, its tiles at most the part's voxels) and, in slabs, what the
/// smoothing holds besides (SmoothInSlabsBytes). With the `surface` it is made around, a field in
/// bricks counts what it holds once made (FieldBricks::InitialBytes): the bricks it adds as the
/// surface moves are checked as they are added (FieldBricks::CheckMemoryAsAdded).
/// MultilevelSolver::MakeField checks it before it makes the field (docs/METHOD.md §9.6).
DEFORMABLESURFACEFILTERS_EXPORT double FieldBytes(const VoxelBox& box, const ImageGeometry& whole,
  const ScaleSpaceParameters& parameters, const TriangleMesh* surface = nullptr);

/// The field at parameters.Sigma over all of `part` (a view of the image's values, placed in the
/// image: the cut of ComputeForceAtScale, or a piece's region) but kept only in the bricks within
/// BrickReachSigmas sigma of `surface`'s vertices (dsFieldBricks.h). With parameters.Smooth and
/// GradientMaximum, a piece's part of the field (dsPieceField.h).
/// `inSlabs`: G_sigma * f is smoothed in slabs and kept near the surface only
/// (FieldBricks::InitializeInSlabs: a piece passes its slabs as `source`, dsPieceSlabs.h, and no
/// Smooth hook), else over all of `part`. With the local edge normalisation P is always kept in
/// tiles near the surface only: made over `part` in one pass, or in slabs at the tiles' voxels
/// with `inSlabs`.
/// `checkAsAdded`: the bricks added as the surface moves are checked against the memory
/// available (FieldBricks::CheckMemoryAsAdded; the first ones too, false with its message).
DEFORMABLESURFACEFILTERS_EXPORT bool ComputeBrickedForce(const ImageView& part,
  const ScaleSpaceParameters& parameters, const TriangleMesh& surface, ForceField& out,
  std::string* error, bool inSlabs = false, bool checkAsAdded = false,
  const SlabSource& source = nullptr);

/// A bricked field smooths its cut in slabs (ComputeBrickedForce's inSlabs) when the cut holds
/// more than this share of the image's voxels, so that no float field of the whole image is made
/// (docs/METHOD.md §9.7). A smaller cut is smoothed whole: its bricks read G_sigma * f in place,
/// not from tiles copied out of the slabs, its recursive filter along z runs forward once, and it
/// holds less than half the image.
constexpr double SlabSmoothingShare = 0.5;

/// Whether a bricked field over FieldCut's part `cut` of an image of geometry `whole` is
/// smoothed in slabs (SlabSmoothingShare).
DEFORMABLESURFACEFILTERS_EXPORT bool FieldInSlabs(const VoxelBox& cut, const ImageGeometry& whole);

/// The force field at parameters.Sigma over `box` of the image (over FieldCut), on a grid decimated
/// by DecimationFactor when that is above 1, else on the image's own grid (ComputeScaleSpaceForce).
/// The edge strength is normalised within the box. With a `surface`, a field on the image's own
/// grid is kept only in the bricks within BrickReachSigmas sigma of its vertices (dsFieldBricks.h;
/// more are computed as the surface moves: FieldBricks::Cover). out's earlier field is released
/// first. out.Sigma is parameters.Sigma either way, out.Image the image's geometry.
DEFORMABLESURFACEFILTERS_EXPORT bool ComputeForceAtScale(const ImageView& image,
  const VoxelBox& box, const ScaleSpaceParameters& parameters, ForceField& out, std::string* error,
  const TriangleMesh* surface = nullptr);
} // namespace dsurf

#endif
