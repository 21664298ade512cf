// SPDX-License-Identifier: BSD-3-Clause
// G_sigma * f of an image slab by slab along z, never the whole image at once (docs/METHOD.md
// §9.7): a fine level whose box spans most of the image keeps G_sigma * f only near the surface
// (dsFieldBricks.h), and its normalisation needs every voxel's edge strength once. Plain C++.
//
// Every value handed out equals SmoothGaussianSeparable's over the whole image bit for bit: the
// same passes on the same values in the same order (z, then x and y within each slice).
//   Along z the sampled Gaussian (below 3 voxels of sigma) reads its radius on either side: a
//   slab's z pass reads that many more slices around it.
//   Along z the recursive filter reads the whole line: a first pass runs its forward recursion
//   up the image slab by slab and records each slab's starting state (5 doubles a line); a
//   second pass, down the image, runs the forward recursion of each slab again from its
//   recorded state (the same floats) and the backward one from the state the slab above ended
//   with (RecursiveAxisPass, as the pieces of a distributed image pass theirs:
//   dsPieceGaussian.h). The forward recursion along z runs twice: the cost of not holding the
//   image's forward outputs.
//   The x and y passes then run once, on each slab's final slices.
#ifndef dsSmoothSlabs_h
#define dsSmoothSlabs_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsImageView.h"

#include <functional>
#include <vector>

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

/// The recursive filter's states at a volume's two ends along an axis whose lines go on beyond
/// it (a process's region of a distributed image, dsPieceSlabs.h): Start is the forward state
/// after the position before its first, Ahead the backward state after the position past its
/// last (RecursiveAxisPass::States doubles a line each, in RecursiveAxisPass's order of lines);
/// empty where the lines end with the volume (the serial filter's start there).
struct AxisEnds
{
  std::vector<double> Start, Ahead;
};

/// Smooths a volume in slabs: visit(slab) for slabs whose own slices cover it, coreSlices each
/// (0: DefaultSlabCore), as SmoothInSlabs does for an image (or SmoothPieceInSlabs for a
/// process's region of a distributed one, dsPieceSlabs.h).
using SlabSource =
  std::function<void(int coreSlices, const std::function<void(const SmoothSlab&)>& visit)>;

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

/// A volume's slices [z0, z1) as floats, into `out`, whenever asked: the values its z pass reads.
using SlabSlices = std::function<void(int z0, int z1, float* out)>;

/// The x and y passes of `count` slices from slice `first` on, in place (after the z pass).
using SlabPassesXY = std::function<void(float* values, int first, int count)>;

/// SmoothInSlabs of a volume of `dims` voxels that is never held whole: `slices` gives its
/// values, `z` the recursive filter's states at its ends along z (a region of a distributed
/// image; empty for an image's own lines), `passesXY` the x and y passes of a slab's slices.
DEFORMABLESURFACEFILTERS_EXPORT void SmoothSlabsOf(const int dims[3], const double sigmaVoxels[3],
  int coreSlices, const SlabSlices& slices, const AxisEnds& z, const SlabPassesXY& passesXY,
  const std::function<void(const SmoothSlab&)>& visit);

/// Bytes SmoothInSlabs holds at most for an image of `geometry` at `sigma` (world units).
DEFORMABLESURFACEFILTERS_EXPORT double SmoothInSlabsBytes(
  const ImageGeometry& geometry, double sigma, int coreSlices);

/// The first slice of each slab's core for an image of nz slices and cores of about `core`
/// slices (cores[s] .. cores[s + 1]): as equal as integers allow, each of two slices or more
/// when there are several.
DEFORMABLESURFACEFILTERS_EXPORT std::vector<int> SlabCores(int nz, int core);

/// Slices [z0, z1) of `image` (any value type) as floats into `out`. In the caller's SMP scope.
DEFORMABLESURFACEFILTERS_EXPORT void SlicesAsFloat(
  const ImageView& image, int z0, int z1, float* out);

/// SmoothGaussianSeparable's x and y passes (sigmaVoxels[0], [1]) of `count` slices of nx by ny
/// voxels, in place: each slice alone, as the whole image's passes smooth it. In the caller's
/// SMP scope.
DEFORMABLESURFACEFILTERS_EXPORT void SmoothSlabXY(
  float* values, int nx, int ny, int count, const double sigmaVoxels[3]);

/// The recursive filter along z (sigma at least GaussianRecursiveFromSigmaVoxels) of a volume
/// that is never held whole: `input(z0, z1, out)` gives its slices [z0, z1) whenever asked. Prepare
/// runs a forward pass up the slabs' cores and a pass down the slabs, recording each slab's forward
/// start and backward start (5 doubles a line a slab each); the pass down computes each slab's
/// final values, handed to `visit` when given (the states then freed as it goes, as SmoothInSlabs
/// does). Without a visitor, Slab then gives any slab's values, in any order. Every value is bit
/// for bit the whole lines' (the pieces' arithmetic, RecursiveAxisPass). Slab s spans its core
/// [cores[s], cores[s + 1]) and `margin` (0 or 1) slices on either side within the volume. `ends`:
/// the states at the volume's ends when its lines go on beyond it (empty: they end with it). In the
/// caller's SMP scope.
class DEFORMABLESURFACEFILTERS_EXPORT RecursiveSlabsZ
{
public:
  using Input = std::function<void(int z0, int z1, float* out)>;
  RecursiveSlabsZ(const int dims[3], double sigmaVoxelsZ, std::vector<int> cores, int margin,
    Input input, AxisEnds ends = AxisEnds());
  int Slabs() const { return static_cast<int>(this->Cores.size()) - 1; }
  int Begin(int s) const;
  int End(int s) const;
  /// The visitor may change the values (a slab's x and y passes run in place).
  using Visit = std::function<void(int s, std::vector<float>& values)>;
  void Prepare(const Visit& visit = nullptr);
  /// Slab s's values (End(s) - Begin(s) slices, x fastest) into `values`.
  void Slab(int s, std::vector<float>& values);

private:
  /// Slab s filtered into `values`; with `recordBelow`, the backward state the slab below starts
  /// from is recorded.
  void Run(int s, std::vector<float>& values, bool recordBelow);

  int Dims[3];
  double Sigma;
  std::vector<int> Cores;
  int Margin;
  Input Produce;
  /// Per slab (empty where not needed, and where the slab starts or ends the lines).
  std::vector<std::vector<double>> Starts, Aheads;
  bool Prepared = false;
};
} // namespace dsurf

#endif
