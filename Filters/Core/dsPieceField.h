// The force field of one piece of a distributed image (docs/METHOD.md §9.8): under MPI each
// process holds only its piece of the volume plus ghost layers, and computes the field of a
// level there, equal on the voxels it owns to the field the whole image gives
// (ComputeForceAtScale, dsFieldGrid.h). Plain C++: the processes' reductions come in as
// callbacks (vtkDeformableSurfaceFilter passes vtkMultiProcessController calls).
//
// - Coarse scales (a block size f > 1): every process sums the f^3 blocks of the voxels it
//   owns, on the block layout of the whole image (or of the box the level is cut to), and a
//   sum over the processes gives every one of them the whole coarse grid (small: 25^3-103^3
//   points for the first levels of 512^3), whose field they then compute alike. Equal to the
//   serial field up to the order of the block sums (doubles, rounded to float).
// - Fine scales (f = 1): each process computes the unnormalised field on the voxels it owns
//   plus PieceGhostVoxels() around them (within the level's box) and divides it by the
//   maximum edge strength over all processes (the serial normalisation by max g). Its owned
//   voxels then agree with the serial field to float rounding (about 2e-7 of the largest
//   force) with the sampled Gaussian, and to < 1e-6 with the recursive one (its start at the
//   cut fades over ~14 sigma).
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
  VoxelBox Held;                 ///< the voxels in Scalars: Owned and ghost layers, x fastest
  const float* Scalars = nullptr;

  /// The geometry of Held (its own dimensions and origin).
  ImageGeometry HeldGeometry() const;
  /// Whether this piece owns the trilinear cell of world point x (the cell of the voxel below x,
  /// clamped to the image): every cell of the image is owned by exactly one piece of a
  /// partition, and its owner holds the 8 voxels a sample there reads.
  bool OwnsCell(const double x[3]) const;
  /// The voxels this piece counts in sums: Owned without the far border voxels it shares with
  /// the next piece (so that every voxel of the image is counted by exactly one piece).
  VoxelBox CountedVoxels() const;
};

/// Ghost voxels a fine field (block size 1) at `sigma` (world units) needs around the owned
/// ones along axis a: the Gaussian's reach (the sampled kernel's radius, 4 sigma, below 3
/// voxels of sigma; 14 sigma for the recursive filter, whose start at a cut fades slowly) and
/// two voxels for the central differences of the edge strength and the potential. Coarse
/// fields need none.
DEFORMABLESURFACEFILTERS_EXPORT int PieceGhostVoxels(double sigma, const ImageGeometry& whole, int a);

/// The field of ComputeForceAtScale(whole image, box, parameters) on this piece (see above):
/// on coarse scales the whole coarse grid, on fine scales the owned voxels of the box and the
/// ghosts around them (out's geometry says which). False with a message when the piece holds
/// too few ghost layers for sigma or the potential is not the default one; the processes
/// still make the same reductions then, so none is left waiting.
DEFORMABLESURFACEFILTERS_EXPORT bool ComputePieceForce(const ImagePiece& piece, const VoxelBox& box,
  const ScaleSpaceParameters& parameters, const PieceReductions& reduce, ForceField& out,
  std::string* error);

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
