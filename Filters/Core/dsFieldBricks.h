// SPDX-License-Identifier: BSD-3-Clause
// A fine level's force field only where the surface is (docs/METHOD.md §9.7). The surface of an
// object fills a thin shell of its bounding box, so P and -grad P
// (16 bytes a voxel) are kept only in bricks of BrickSize^3 voxels within the surface's reach;
// G_sigma * f (4 bytes a voxel) stays over the level's whole box, because the recursive
// Gaussian runs along whole lines and the potential is normalised by the strongest edge in the
// box. A brick's values are computed from it exactly as the whole box's would be
// (PotentialAndForceInBox), so a vertex in a brick samples bit for bit today's whole-box field;
// a voxel two bricks share is computed once and copied.
// Bricks are computed when the surface first comes within reach of them and kept for the
// level. Plain C++.
#ifndef dsFieldBricks_h
#define dsFieldBricks_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsImageView.h"
#include "dsScaleSpace.h"
#include "dsTriangleMesh.h"

#include <atomic>
#include <memory>
#include <string>
#include <vector>

namespace dsurf
{
/// How far, in sigmas, the bricks reach past the surface's vertices: the 2 sigma a surface may
/// move in a level (NeighbourhoodSigmas less the Gaussian's support, which G_sigma * f over the
/// box already holds).
constexpr double BrickReachSigmas = 2.0;

class DEFORMABLESURFACEFILTERS_EXPORT FieldBricks
{
public:
  /// Voxels along a brick's side (its values also hold the next brick's first layer, so every
  /// trilinear cell lies in one brick).
  static constexpr int BrickSize = 8;

  /// G_sigma * f over `image` (a level's box of the image) and the potential's gains
  /// (SmoothForPotential; global edge normalisation only); no brick yet. `reach`: world
  /// distance from a vertex that Cover computes bricks within.
  bool Initialize(const ImageView& image, const ScaleSpaceParameters& parameters, double reach,
    std::string* error);
  /// Computes the bricks within the reach of a vertex of `mesh` that are not computed yet (in
  /// parallel, NumberOfThreads of the parameters); returns how many. Between sweeps only.
  int Cover(const TriangleMesh& mesh);

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
  /// Bytes held: G_sigma * f and the computed bricks.
  double Bytes() const;

private:
  /// The brick of the trilinear cell of world point x and the cell within it; false outside
  /// the box. slot: the brick's storage, -1 when it is not computed.
  bool Locate(const double x[3], int& slot, TrilinearCell& cell) const;
  /// The voxels of brick b (its index along each axis): its cells' corners.
  VoxelBox BrickBox(const int b[3]) const;
  /// The voxels brick b computes itself: all but the layer it shares with the next brick
  /// along each axis (that brick's first), which the last brick along the axis has alone.
  VoxelBox OwnBox(const int b[3]) const;
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
  int Bricks[3] = { 0, 0, 0 }; ///< bricks along each axis
  std::vector<int> Slots;      ///< per brick (x fastest): its index in Potential, or -1
  std::vector<std::vector<float>> Potential, Force; ///< per computed brick, x fastest
  std::vector<char> BrickFinite; ///< per computed brick: all its values are finite
  std::vector<int> FreeSlots;    ///< slots of dropped bricks, reused before new ones
  mutable std::atomic<long long> MissCount{ 0 };
};
} // namespace dsurf

#endif
