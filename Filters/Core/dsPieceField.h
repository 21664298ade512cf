// SPDX-License-Identifier: BSD-3-Clause
// The force field of one piece of a distributed image (docs/METHOD.md §9.8): under MPI each
// process holds only its piece of the volume plus ghost layers, and computes the field of a
// level there, equal on the voxels it owns to the field the whole image gives
// (ComputeForceAtScale, dsFieldGrid.h). Plain C++: the processes' reductions come in as
// callbacks (vtkDeformableSurfaceFilter passes vtkMultiProcessController calls).
//
// - Coarse scales (a block size f > 1): each block of the layout BlockMeans gives the whole
//   image (or the box the level is cut to) is averaged by the process counting its first
//   voxel, in the serial order (it holds the block with 2 f ghost layers), and a sum over the
//   processes gives every one of them the whole coarse grid (small: 19^3-171^3 points for the
//   first levels of 512^3), whose field they then compute alike: the serial field bit for bit.
// - Fine scales (f = 1): each process computes the field on the voxels it owns plus
//   PieceGhostVoxels() around them (within the level's box), normalised by the largest edge
//   strength over all processes (ScaleSpaceParameters::GradientMaximum). The sampled Gaussian
//   (sigma below 3 voxels) needs its radius of ghost layers; the recursive one passes its state
//   from piece to piece (dsPieceGaussian.h) and needs one layer, for the differences. Both give
//   the serial field bit for bit. With a surface, a part of more than half the piece is smoothed
//   in slabs from those states and kept in tiles near the surface (dsPieceSlabs.h), as a serial
//   box of more than half the image is.
// Only the default potential is distributed (EdgeWeight alone, ImageWeight 0, the global
// maximum normalisation): the image term's range and the local normalisation's second Gaussian
// would need more reductions; they are refused with a message.
#ifndef dsPieceField_h
#define dsPieceField_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsFieldGrid.h"
#include "dsScaleSpace.h"
#include "dsSolver.h"

#include <functional>
#include <string>
#include <vector>

namespace dsurf
{
/// How the processes holding the pieces combine values. Both are collective: every process
/// calls them in the same order with vectors of the same size.
struct DEFORMABLESURFACEFILTERS_EXPORT PieceReductions
{
  std::function<void(std::vector<double>&)> Sum; ///< element-wise sum over the processes, in place
  std::function<double(double)> Max;             ///< the maximum over the processes
};

/// One process's piece of an image, in the whole image's voxel indices.
struct DEFORMABLESURFACEFILTERS_EXPORT ImagePiece
{
  ImageGeometry Whole; ///< the whole image
  /// The voxels this process answers for (a VTK piece's extent without its ghosts; neighbouring
  /// pieces share their border voxels, as VTK image pieces do).
  VoxelBox Owned;
  VoxelBox Held; ///< the voxels in Image: Owned and ghost layers
  /// The values of Held, read in place in the input's own type (no float copy, as for a whole
  /// image: docs/METHOD.md §9.7); its geometry is HeldGeometry().
  ImageView Image;

  /// The geometry of Held (its own dimensions and origin).
  ImageGeometry HeldGeometry() const;
  /// Whether this piece owns the trilinear cell of world point x (the cell of the voxel below x,
  /// clamped to the image): every cell of the image is owned by exactly one piece of a
  /// partition, and its owner holds the 8 voxels a sample there reads.
  bool OwnsCell(const double x[3]) const;
  /// With OwnsCell(x), the trilinear cell of x located as in the whole image (the same
  /// corners and weights as a serial sample) with ids into an array of the voxels from `begin`
  /// on (whole-image indices) whose id steps per axis are `increments`: false when the piece
  /// does not own the cell or x lies outside the image.
  bool LocateOwnedCell(const double x[3], const int begin[3], const std::ptrdiff_t increments[3],
    TrilinearCell& cell) const;
  /// SampleVolume of the whole image at x, when this piece owns x's cell (*owned true); else 0.
  double SampleOwned(const double x[3], bool* owned) const;
  /// The voxels this piece counts in sums: Owned without the far border voxels it shares with
  /// the next piece (so that every voxel of the image is counted by exactly one piece).
  VoxelBox CountedVoxels() const;
};

/// The reductions of a single process holding the whole image: Sum leaves the values, Max
/// returns its argument (so that one code path serves a whole image and its pieces).
DEFORMABLESURFACEFILTERS_EXPORT PieceReductions SingleProcessReductions();

/// The whole image as the one piece of a single process.
DEFORMABLESURFACEFILTERS_EXPORT ImagePiece WholeImagePiece(const ImageView& image);

/// Ghost voxels a fine field (block size 1) at `sigma` (world units) needs around the owned
/// ones along axis a for the serial field bit for bit: one voxel for the differences of
/// G_sigma * f (the edge strength and the force's chain rule), plus the sampled Gaussian's
/// radius (4 sigma) below 3 voxels of sigma; the recursive Gaussian's state comes from the
/// neighbouring pieces (dsPieceGaussian.h). Coarse fields (block size f > 1) need 2 f.
DEFORMABLESURFACEFILTERS_EXPORT int PieceGhostVoxels(
  double sigma, const ImageGeometry& whole, int a);
/// PieceGhostVoxels for sigmaVoxels voxels of sigma along the axis.
DEFORMABLESURFACEFILTERS_EXPORT int FineGhostVoxels(double sigmaVoxels);

/// The means of the f^3 blocks of `cut` (whole-image voxels) in BlockMeans's layout, on every
/// process: each block averaged by the process counting its first voxel (which holds it with
/// 2 f ghost layers) and one sum over the processes (BlockMeans itself when this process counts
/// the whole cut), so every process gets the serial block means bit for bit. coarseGeometry
/// places each mean on its block's centre voxel. False with a message on every process when a
/// piece holds too few ghost layers. Collective.
DEFORMABLESURFACEFILTERS_EXPORT bool PieceBlockMeans(const ImagePiece& piece, const VoxelBox& cut,
  int f, int numberOfThreads, const PieceReductions& reduce, std::vector<float>& coarse,
  ImageGeometry& coarseGeometry, std::string* error);

/// The bytes ComputePieceForce(piece, box, parameters) holds at most on this process (FieldBytes
/// for a piece): the whole cut's coarse grid with the sums of its block means, or the piece's
/// part of a fine field with its ghosts.
DEFORMABLESURFACEFILTERS_EXPORT double PieceFieldBytes(
  const ImagePiece& piece, const VoxelBox& box, const ScaleSpaceParameters& parameters);

/// The field of ComputeForceAtScale(whole image, box, parameters) on this piece (see above):
/// on coarse scales the whole coarse grid, on fine scales the owned voxels of the box and the
/// ghosts around them (out's geometry says which); with a `surface`, the fine scales keep P and
/// -grad P only in the bricks within reach of its vertices (ComputeBrickedForce: those of the
/// piece's part; FieldInBricks tells when), equal to the serial bricks on every owned voxel.
/// False with a message when the piece holds too few ghost layers for sigma or the potential is
/// not the default one; the processes still make the same reductions then, so none is left
/// waiting. A field in bricks reads piece.Image as the surface moves: its values must outlive
/// `out`.
DEFORMABLESURFACEFILTERS_EXPORT bool ComputePieceForce(const ImagePiece& piece, const VoxelBox& box,
  const ScaleSpaceParameters& parameters, const PieceReductions& reduce, ForceField& out,
  std::string* error, const TriangleMesh* surface = nullptr);

/// Why this piece cannot take part in a distributed solve (no voxels owned, values missing,
/// owned voxels not held or outside the image); empty when it can. Local: the caller combines
/// the answers of all processes (CheckPieces).
DEFORMABLESURFACEFILTERS_EXPORT std::string PieceProblem(const ImagePiece& piece);

/// PieceProblem of every process, combined: empty when all pieces are fine, else this
/// process's problem or, when only others have one, a message saying so. Collective.
DEFORMABLESURFACEFILTERS_EXPORT std::string CheckPieces(
  const ImagePiece& piece, const PieceReductions& reduce);

/// The image's voxels with a value in [lo, hi], each counted by one piece (CountedVoxels) and
/// summed over the processes: CountVoxelsInRange (dsRegion.h) of the whole image. Collective.
DEFORMABLESURFACEFILTERS_EXPORT long long CountPieceVoxelsInRange(
  const ImagePiece& piece, double lo, double hi, const PieceReductions& reduce);

/// The solver's force exchange (Solver::SetForceExchange) of a distributed solve, where every
/// process holds the same mesh and the field of its piece: each keeps the forces of the
/// vertices whose cell it owns (ImagePiece::OwnsCell: exactly one process per vertex inside the
/// image) and zeroes the others, and reduce.Sum gives every process every force; a vertex that
/// no process sampled (outside the image, or outside the level's field) is Outside. The sums
/// add zeros to one value, so every process gets the owner's force exactly.
DEFORMABLESURFACEFILTERS_EXPORT ForceExchange OwnerForceExchange(
  const ImagePiece& piece, const PieceReductions& reduce);
} // namespace dsurf

#endif
