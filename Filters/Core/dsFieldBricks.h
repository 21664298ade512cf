// SPDX-License-Identifier: BSD-3-Clause
// A fine level's force field only where the surface is (docs/METHOD.md §9.7). The surface of an
// object fills a thin shell of its bounding box, so P and -grad P (16 bytes a voxel) are kept
// only in bricks of BrickSize^3 voxels within the surface's reach. G_sigma * f (4 bytes a voxel)
// is computed over the level's whole box, because the recursive Gaussian runs along whole lines
// and the potential is normalised by the strongest edge in the box; it is held over the box
// (Initialize) or, for a box of more than half the image, smoothed slab by slab and held only in
// tiles near the surface (InitializeInSlabs, dsSmoothSlabs.h, SlabSmoothingShare of
// dsFieldGrid.h). A brick's values are computed from it exactly as the whole box's would be
// (PotentialAndForceInBox), so a vertex in a brick samples the whole-box field bit for bit; a
// voxel two bricks share is computed once and copied. Bricks are computed when the surface
// first comes within reach of them and kept for the level. With the local edge normalisation
// the tiles hold P itself: made over the whole box in one pass and read off at the tiles (a box
// of at most half the image), or computed in slabs at the tiles' voxels only (LocalPotentialAt,
// dsScaleSpace.h); a brick's -grad P is the central differences of P, as the whole box's is.
// Plain C++.
#ifndef dsFieldBricks_h
#define dsFieldBricks_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsImageView.h"
#include "dsScaleSpace.h"
#include "dsTriangleMesh.h"

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dsurf
{
/// How far, in sigmas, the bricks reach past the surface's vertices. A batch of sweeps ends once
/// a vertex may have moved half of it, and Cover then follows the surface (dsMultilevel.cxx), so
/// the reach need not hold a level's whole travel: one sigma keeps the bricks to a thin shell
/// (the near start at 512^3 held 0.68 GiB with 2 sigma, 0.59 with 1: BENCHMARKS.md).
constexpr double BrickReachSigmas = 1.0;

class DEFORMABLESURFACEFILTERS_EXPORT FieldBricks
{
public:
  /// Voxels along a brick's side (its values also hold the next brick's first layer, so every
  /// trilinear cell lies in one brick).
  static constexpr int BrickSize = 8;

  /// InitializeInSlabs's coreSlices for the local normalisation's P made over the whole box in
  /// one pass (a box of at most half the image).
  static constexpr int LocalOnePass = -1;
  /// Bytes a computed brick holds at most (P and -grad P over (BrickSize + 1)^3 voxels), and a
  /// tile (G_sigma * f over at most (BrickSize + 1)^3).
  static constexpr double BrickBytes =
    4.0 * sizeof(float) * (BrickSize + 1) * (BrickSize + 1) * (BrickSize + 1);
  static constexpr double TileBytes =
    sizeof(float) * (BrickSize + 1) * (BrickSize + 1) * (BrickSize + 1);
  /// G_sigma * f over `image` (a level's box of the image) and the potential's gains
  /// (SmoothForPotential; global edge normalisation only); no brick yet. `reach`: world
  /// distance from a vertex that Cover computes bricks within.
  bool Initialize(const ImageView& image, const ScaleSpaceParameters& parameters, double reach,
    std::string* error);
  /// The same without G_sigma * f over the box: it is smoothed in slabs along z (coreSlices
  /// slices each, 0: dsSmoothSlabs.h's default) and kept in tiles (a brick's own voxels) only
  /// near `surface`; when the surface later comes within reach of a brick whose tiles were not
  /// kept, the box is smoothed again in slabs, keeping the tiles near it then, with a margin twice
  /// as wide each time. The values equal Initialize's (the whole box's) bit for bit. `image` must
  /// outlive the bricks. With the local edge normalisation (for any box) the tiles hold P instead,
  /// computed at their voxels by LocalPotentialAt (coreSlices its slabs' cores) or, coreSlices
  /// LocalOnePass, read off the box's whole P made in one pass (12 bytes a voxel of the box, then
  /// freed), and again, with the wider margin, when the surface goes past them. A process's
  /// region of a distributed image (dsPieceField.h) passes its slabs as `source`
  /// (dsPieceSlabs.h) and its maximum as parameters.GradientMaximum, which the first smoothing
  /// calls; the gains found then are kept when the box is smoothed again. Not parameters.Smooth.
  bool InitializeInSlabs(const ImageView& image, const ScaleSpaceParameters& parameters,
    double reach, const TriangleMesh& surface, int coreSlices, std::string* error,
    const SlabSource& source = nullptr);
  /// Computes the bricks within the reach of a vertex of `mesh` that are not computed yet (in
  /// parallel, NumberOfThreads of the parameters); returns how many. Between sweeps only. With
  /// CheckMemoryAsAdded, bricks (or tiles smoothed again) that the memory available cannot hold
  /// are not made: Shortfall says so, and the caller ends the solve.
  int Cover(const TriangleMesh& mesh);
  /// From now on Cover checks what it adds against the memory available, for a field whose first
  /// check counted only the bricks and tiles near its first surface (InitialBytes): the
  /// machine's, read at each check (dsMemory.h), or (`available` >= 0, for tests) a budget of
  /// that many bytes, used up by what is added.
  void CheckMemoryAsAdded(double available = -1.0)
  {
    this->CheckGrowth = true;
    this->Available = available;
  }
  /// Why Cover made no more bricks (the memory available), empty while it could.
  const std::string& Shortfall() const { return this->ShortfallMessage; }
  /// The bytes a field in bricks over `grid` (a level's box of an image) holds once made and
  /// covering `surface`: G_sigma * f over the box or (inSlabs) the tiles near the surface and
  /// what making them holds (TileMakingBytes; coreSlices: InitializeInSlabs's, LocalOnePass for the
  /// local normalisation's one pass), and the bricks
  /// within `reach` of its vertices. MultilevelSolver::MakeField checks it; Cover checks the rest
  /// as it is added.
  static double InitialBytes(const ImageGeometry& grid, const ScaleSpaceParameters& parameters,
    double reach, const TriangleMesh& surface, bool inSlabs, int coreSlices = 0);

  /// The grid of the box the bricks divide.
  const ImageGeometry& Geometry() const { return this->Grid; }
  /// Trilinear sample of the force at world point x. False (f = 0) outside the box (as
  /// ForceField::SampleForce); inside it but in a brick not computed, f = 0 and a miss is
  /// counted (Misses).
  bool SampleForce(const double x[3], double f[3]) const;
  /// Trilinear sample of the potential (0 outside or in a brick not computed).
  double SamplePotential(const double x[3]) const;
  /// Samples that fell in a brick not computed, since Initialize.
  long long Misses() const { return this->MissCount.load(); }
  /// Counts a sample that missed the field in another way (ForceField::SampleForce: beyond the
  /// box, inside the image).
  void CountMiss() const { ++this->MissCount; }
  /// Bricks held now (computed and not dropped).
  int ComputedBricks() const
  {
    return static_cast<int>(this->Potential.size() - this->FreeSlots.size());
  }
  /// Every computed value is finite (huge weights can overflow single precision).
  bool Finite() const;
  /// Bytes held: G_sigma * f (over the box, or its tiles) and the computed bricks.
  double Bytes() const;
  /// Times the box was smoothed in slabs (InitializeInSlabs: 1, and 1 more a refill); 0 for
  /// Initialize.
  int SlabSmoothings() const { return this->Smoothings; }

private:
  /// The brick of the trilinear cell of world point x and the cell within it; false outside
  /// the box. slot: the brick's storage, -1 when it is not computed.
  bool Locate(const double x[3], int& slot, TrilinearCell& cell) const;
  /// The voxels of brick b (its index along each axis): its cells' corners.
  VoxelBox BrickBox(const int b[3]) const;
  /// The voxels brick b computes itself: all but the layer it shares with the next brick
  /// along each axis (that brick's first), which the last brick along the axis has alone.
  VoxelBox OwnBox(const int b[3]) const;
  /// Empty when `bytes` more fit in the memory available (CheckMemoryAsAdded), else the message,
  /// kept in ShortfallMessage.
  bool Affords(double bytes, const char* what);
  /// Forgets every brick and tile, for a box of `grid`.
  void Reset(const ImageGeometry& grid, const ScaleSpaceParameters& parameters, double reach);
  /// The box, its parameters and the bricks along each axis, and nothing held per brick: all the
  /// marks need (InitialBytes counts a field of a box that may be refused, without its slots).
  void SetBox(const ImageGeometry& grid, const ScaleSpaceParameters& parameters, double reach);
  /// The bricks of the box.
  std::size_t BrickCount() const;
  /// The voxels whose G_sigma * f brick b's tile holds in slabs: its own, and the last voxel
  /// along an axis for the last brick along it (the tiles partition the box).
  VoxelBox TileBox(const int b[3]) const;
  /// Marks (1) the bricks holding a cell within `reach` (world) of one of the points, and a
  /// voxel more; `grow` bricks more along each axis.
  void MarkNear(
    const std::vector<Vec3>& points, double reach, int grow, std::vector<char>& mark) const;
  /// Marks the bricks within `reach` of any point of the surface (not only its vertices), and a
  /// brick more along each axis: the tiles the bricks near it read.
  void MarkNearSurface(const TriangleMesh& mesh, double reach, std::vector<char>& mark) const;
  /// G_sigma * f smoothed in slabs, the tiles of the `keep` bricks (and no other) stored.
  bool SmoothTiles(const std::vector<char>& keep, std::string* error);
  /// With the local edge normalisation: P at the voxels of the `keep` bricks' tiles (and no
  /// other), computed by LocalPotentialOfBox.
  bool LocalTiles(const std::vector<char>& keep, std::string* error);
  /// The voxels of the `keep` bricks' tiles, whose ids go into `kept`.
  VoxelSet TileVoxels(const std::vector<char>& keep, std::vector<int>& kept) const;
  /// The box's locally normalised P at the `wanted` voxels (by rank): LocalPotentialAt in slabs
  /// of SlabCore slices, or for LocalOnePass the box's whole P made in one pass.
  bool LocalPotentialOfBox(
    const VoxelSet& wanted, std::vector<float>& potential, std::string* error) const;
  /// Calls row(v, n, at) for each row of brick `id`'s tile: its first voxel's id v in the box,
  /// its n voxels, its place `at` in the tile's values.
  template <typename Row>
  void ForEachTileRow(int id, Row&& row) const
  {
    const int b[3] = { id % this->Bricks[0], (id / this->Bricks[0]) % this->Bricks[1],
      id / (this->Bricks[0] * this->Bricks[1]) };
    const VoxelBox tile = this->TileBox(b);
    const std::ptrdiff_t nx = this->Grid.Dimensions[0];
    const std::ptrdiff_t slice = nx * this->Grid.Dimensions[1];
    const std::ptrdiff_t tx = tile.End[0] - tile.Begin[0], ty = tile.End[1] - tile.Begin[1];
    for (int k = tile.Begin[2]; k < tile.End[2]; ++k)
      for (int j = tile.Begin[1]; j < tile.End[1]; ++j)
      {
        row(k * slice + j * nx + tile.Begin[0], tx,
          (j - tile.Begin[1]) * tx + (k - tile.Begin[2]) * tx * ty);
      }
  }
  /// The tiles of the `keep` bricks made (SmoothTiles, or LocalTiles when Local()).
  bool FillTiles(const std::vector<char>& keep, std::string* error)
  {
    return this->Local() ? this->LocalTiles(keep, error) : this->SmoothTiles(keep, error);
  }
  /// Whether the field is locally normalised: its tiles hold P, not G_sigma * f.
  bool Local() const { return LocallyNormalised(this->Parameters); }
  /// Bytes making the `tiles` kept tiles holds besides them, at most (the slabs' smoothing, or
  /// LocalPotentialAt's, or the box's whole P for LocalOnePass).
  static double TileMakingBytes(const ImageGeometry& grid, const ScaleSpaceParameters& parameters,
    double tiles, int coreSlices);
  /// Before the `fresh` bricks are computed: makes the tiles again (FillTiles) unless every tile
  /// they read is held. False only when that fails.
  bool EnsureTiles(const TriangleMesh& mesh, const std::vector<int>& fresh);
  /// G_sigma * f (P when Local()) over brick b's voxels and their neighbours within the box, into
  /// `values` (x fastest over the returned box): a pointer into Smooth, or gathered from the
  /// tiles.
  const float* SmoothAround(const int b[3], std::vector<float>& values, VoxelBox& over) const;
  /// Computes brick b's own voxels (OwnBox) into its slot.
  void ComputeBrick(const int b[3], int slot);
  /// Frees the computed bricks not `needed` when keeping them and computing `fresh` more would
  /// pass the whole field's size (Cover).
  void DropUnreachedOverBudget(const std::vector<char>& needed, std::size_t fresh);
  /// Fills the rest of brick b's voxels, once every fresh brick's own ones are computed: copied
  /// from the brick that owns them when it is computed, else computed. Then checks the brick.
  void CompleteBrick(const int b[3], int slot);

  ImageGeometry Grid;
  ScaleSpaceParameters Parameters;
  PotentialGains Gains;
  double Reach = 0;
  /// G_sigma * f over the box; new float[] leaves it unset (SmoothForPotential writes every
  /// voxel: a zero fill first would be a pass over the box for nothing).
  std::unique_ptr<float[]> Smooth;
  /// In slabs (InitializeInSlabs): the image, G_sigma * f (P when Local()) per brick's TileBox
  /// (empty where not kept), the margin past the reach the tiles were kept within, and the
  /// smoothings.
  ImageView Source;
  SlabSource Slabs; ///< the slabs of the image, when not SmoothInSlabs's
  /// A piece's GradientMaximum (dsPieceField.h), for the first smoothing only.
  std::function<double(double)> FirstMaximum;
  int SlabCore = 0;
  std::vector<std::vector<float>> Tiles;
  double TileMargin = 0;
  int Smoothings = 0;
  /// CheckMemoryAsAdded: its switch, the bytes available (negative: the machine's), and why
  /// bricks were not made.
  bool CheckGrowth = false;
  double Available = -1.0;
  std::string ShortfallMessage;
  int Bricks[3] = { 0, 0, 0 }; ///< bricks along each axis
  std::vector<int> Slots;      ///< per brick (x fastest): its index in Potential, or -1
  std::vector<std::vector<float>> Potential, Force; ///< per computed brick, x fastest
  std::vector<char> BrickFinite; ///< per computed brick: all its values are finite
  std::vector<int> FreeSlots;    ///< slots of dropped bricks, reused before new ones
  mutable std::atomic<long long> MissCount{ 0 };
};
} // namespace dsurf

#endif
