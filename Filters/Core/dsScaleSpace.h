// SPDX-License-Identifier: BSD-3-Clause
// Scale-space external force of the deformable surface (docs/METHOD.md §2, §6.6):
// plain C++, no pipeline types. Shared by vtkImageScaleSpaceGradient and
// vtkDeformableSurfaceFilter so the two never disagree.
//
// What is computed (also stated in vtkImageScaleSpaceGradient.h):
//   s  = G_sigma * f          separable Gaussian, sigma isotropic in world units:
//                             sigma_axis = sigma / spacing; a sampled Gaussian below 3 voxels,
//                             a 5th-order recursive filter (van Vliet-Young-Verbeek) from 3 on;
//                             replicated border (dsGaussianSmoother.h, docs/METHOD.md §6c).
//   g  = |grad s|             central differences (one-sided at the border), index
//                             derivatives taken to world by Direction * diag(1/spacing).
//   NormalizePotential on:    P = -(w_edge * g / max g + w_image * (s - min s) / (max s - min s))
//                             (or with the local edge normalisation: g -> g / (G_2sigma * g +
//                             floor), rescaled to a maximum of 1; see EdgeNormalization)
//                             so P lies in [-(w_edge + w_image), 0]; a zero range gives 0.
//   NormalizePotential off:   P = -(w_edge * g + w_image * s)
//   Force = -grad P           by the chain rule from the derivatives of s: -grad P =
//                             w_edge' H grad s / g + w_image' grad s (the gains of P), with
//                             grad s as for g and its Hessian H from second differences
//                             [1, -2, 1] (the border value replicated) and mixed central
//                             differences, to world like g. Central differences of the sampled
//                             P would widen an edge by a voxel and move the force's zero 1.5
//                             voxels into a cube's corner at sigma = 0.5 voxel (docs/METHOD.md
//                             §6 item 1). With the local edge normalisation, whose P divides
//                             by a local mean, the central differences of P.
#ifndef dsScaleSpace_h
#define dsScaleSpace_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsImageView.h"
#include "dsSmoothSlabs.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dsurf
{
/// How the edge strength g = |grad(G_sigma * f)| is made unit-free before it enters P.
enum class EdgeNormalization
{
  /// g / max g: the strongest edge of the field's part of the volume (all of it, or the box
  /// around the surface) sets the scale for all (skin/air in a head mutes the brain's own
  /// boundary).
  GlobalMaximum = 0,
  /// g / (G_2sigma * g + LocalEdgeFloor * max g): each edge against the edge strength around
  /// it, so a weak boundary far (> ~2 sigma) from a strong one is as strong as the strong one;
  /// the floor keeps flat, noisy regions at ~0. Then divided by its maximum, so P in [-1, 0].
  Local = 1
};

struct DEFORMABLESURFACEFILTERS_EXPORT ScaleSpaceParameters
{
  double Sigma = 1.0;       ///< physical units (isotropic in world space); 0 = no smoothing
  double EdgeWeight = 1.0;  ///< w_edge
  double ImageWeight = 0.0; ///< w_image
  bool NormalizePotential = true;
  /// With NormalizePotential: how g is normalised (see EdgeNormalization).
  dsurf::EdgeNormalization EdgeNormalization = dsurf::EdgeNormalization::GlobalMaximum;
  double LocalEdgeFloor = 0.05; ///< Local: the denominator's floor, a fraction of max g
  int NumberOfThreads = 0;      ///< 0 = all the machine has (vtkSMPTools STDThread)
  /// A piece of a distributed image (dsPieceField.h): called with the largest edge strength g
  /// over the voxels [MaximumBegin, MaximumEnd) of the field (its own indices; the voxels the
  /// piece owns), computed as the normalisation computes it; it returns the maximum to
  /// normalise with (that of the whole image, over every process). With the local
  /// normalisation it is called a second time, with the largest locally normalised g there.
  /// Empty: the field's own maxima.
  std::function<double(double boxMaximum)> GradientMaximum;
  int MaximumBegin[3] = { 0, 0, 0 };
  int MaximumEnd[3] = { 0, 0, 0 };
  /// A piece of a distributed image (dsPieceGaussian.h): G_sigma * f in place on the field's
  /// voxels (`volume`, the image's values as floats), sigmaVoxels per axis, the recursive
  /// filter's state passed between the pieces. Empty: SmoothGaussianSeparable.
  std::function<void(float* volume, const double sigmaVoxels[3])> Smooth;
  /// With the local edge normalisation, false computes P alone (ComputeScaleSpaceForce leaves
  /// Force empty and works in 12 bytes a voxel instead of 16): the sigma_0 probe samples only P
  /// (dsInitialSigma.h). Ignored with the global normalisation.
  bool ComputeForce = true;
};

/// Whether a field at `parameters` is locally normalised (EdgeNormalization::Local with
/// NormalizePotential): P then comes from a second Gaussian of g, and -grad P from central
/// differences of P.
inline bool LocallyNormalised(const ScaleSpaceParameters& parameters)
{
  return parameters.NormalizePotential && parameters.EdgeNormalization == EdgeNormalization::Local;
}

class FieldBricks;
class VoxelSet;

/// P and -grad P on the voxel grid.
struct DEFORMABLESURFACEFILTERS_EXPORT ForceField
{
  ImageGeometry Geometry;
  double Sigma = 0.0;           ///< physical sigma the field was computed at
  std::vector<float> Potential; ///< P per voxel (x fastest)
  std::vector<float> Force;     ///< -grad P per voxel, 3 components, world coordinates
  /// When set, the field exists only in bricks around the surface (dsFieldBricks.h; Geometry
  /// is their box): Potential and Force are empty and every sample comes from the bricks.
  std::shared_ptr<FieldBricks> Bricks;
  /// The image the field's grid is a box of (Dimensions 0: the grid is the whole image).
  ImageGeometry Image;

  bool Empty() const { return this->Potential.empty() && !this->Bricks; }
  /// Trilinear sample of the force at world point x. Returns false (and f = 0)
  /// when x lies outside the image: more than half a voxel beyond its outermost voxel
  /// centres (within that half voxel the border value is used). Inside the image but outside
  /// the field's grid (or in a brick not computed), f = 0 and true.
  bool SampleForce(const double x[3], double f[3]) const;
  /// Trilinear sample of the potential (0 outside).
  double SamplePotential(const double x[3]) const;
};

/// Bytes a ForceField takes per voxel (P and the three components of -grad P, as floats):
/// what a solve, or the Scale-Space Gradient filter's output, allocates per voxel of the image.
constexpr double ForceFieldBytesPerVoxel = 4 * sizeof(float);

/// Trilinear sample of a one-float-per-voxel volume at world point x, with the same reach as
/// ForceField::SampleForce (half a voxel past the outermost centres); 0 and *inside = false
/// outside (SampleVolume of dsImageView.h for a volume of any type).
DEFORMABLESURFACEFILTERS_EXPORT double SampleVolume(
  const float* values, const ImageGeometry& geometry, const double x[3], bool* inside);

/// Compute P = -(w_edge * g + w_image * f) with g = |grad(G_sigma * f)| (normalised
/// as documented in vtkImageScaleSpaceGradient.h when NormalizePotential), and
/// Why the scale space at sigma cannot be computed on this geometry, empty when it can: the
/// checks ComputeScaleSpaceForce makes before anything else (3-D, spacing, origin, direction,
/// sigma finite and at most 100 000 voxels along an axis).
DEFORMABLESURFACEFILTERS_EXPORT std::string ScaleSpaceProblem(
  const ImageGeometry& geometry, double sigma);

/// Force = -grad P in world coordinates, over the voxels of `image` (any value type; out's
/// geometry is the view's). Returns false with a message on bad input (empty, 2-D, non-finite
/// sigma...).
DEFORMABLESURFACEFILTERS_EXPORT bool ComputeScaleSpaceForce(const ImageView& image,
  const ScaleSpaceParameters& parameters, ForceField& out, std::string* error);
/// The same for a float volume, one value per voxel of `geometry`, x fastest.
DEFORMABLESURFACEFILTERS_EXPORT bool ComputeScaleSpaceForce(const float* scalars,
  const ImageGeometry& geometry, const ScaleSpaceParameters& parameters, ForceField& out,
  std::string* error);

/// Same computation into caller-owned buffers (no copy for the VTK filter):
/// potential holds NumberOfVoxels floats, force 3 * NumberOfVoxels. The potential buffer
/// holds G_sigma * f (and first the image converted to float when it is not a contiguous float
/// array), replaced by P slice by slice as the force is computed (two slices of scratch); with
/// the local edge normalisation the force buffer is the scratch. So peak memory is the input
/// + 4 floats per voxel.
/// The image must not alias either buffer.
DEFORMABLESURFACEFILTERS_EXPORT bool ComputeScaleSpaceForceInto(const ImageView& image,
  const ScaleSpaceParameters& parameters, float* potential, float* force, std::string* error);

/// How the edge strength g and the smoothed image s make the potential:
/// P = -(Edge g + Image s + Offset) (the normalisation of the header comment folded in).
struct DEFORMABLESURFACEFILTERS_EXPORT PotentialGains
{
  double Edge = 0, Image = 0, Offset = 0;
};

/// ComputeScaleSpaceForceInto in two stages, for a field computed only in pieces of the image
/// (dsFieldBricks.h). First G_sigma * f over the whole `image` into `smooth` (NumberOfVoxels
/// floats) and the gains, normalised over the whole image as ComputeScaleSpaceForceInto does;
/// the same checks, false with a message. The local edge normalisation (a second Gaussian of
/// g over the image) is not staged: parameters must not ask for it. On a piece of a distributed
/// image, parameters.Smooth and GradientMaximum make the same reductions as there.
DEFORMABLESURFACEFILTERS_EXPORT bool SmoothForPotential(const ImageView& image,
  const ScaleSpaceParameters& parameters, float* smooth, PotentialGains& gains, std::string* error);
/// SmoothForPotential without G_sigma * f over the whole image: the image is smoothed slab by
/// slab along z (dsSmoothSlabs.h, coreSlices slices each, 0: the default) and keep(slab) is
/// called with each slab's values, which are gone after the call; the gains are the same bit for
/// bit. The slabs come from `source` when given (a process's region of a distributed image,
/// smoothed from its pieces' states: dsPieceSlabs.h; parameters.GradientMaximum then gives the
/// whole image's maximum), else SmoothInSlabs of the image. Not the local edge normalisation, nor
/// parameters.Smooth. Without `findGains` (the same box smoothed again, whose gains are known)
/// the edge statistics are not gathered and `gains` is left as it is.
DEFORMABLESURFACEFILTERS_EXPORT bool SmoothForPotentialInSlabs(const ImageView& image,
  const ScaleSpaceParameters& parameters, int coreSlices,
  const std::function<void(const SmoothSlab&)>& keep, PotentialGains& gains, std::string* error,
  const SlabSource& source = nullptr, bool findGains = true);
/// Then P and -grad P at the voxels of `part` (a box within `box`) of the image of `geometry`
/// whose G_sigma * f is `smooth`, stored where they lie in `box` (x fastest): bit for bit what
/// ComputeScaleSpaceForceInto gives there. potential holds box.NumberOfVoxels() floats, force
/// three times as many; the values outside `part` are left alone. Runs serially.
DEFORMABLESURFACEFILTERS_EXPORT void PotentialAndForceInBox(const float* smooth,
  const ImageGeometry& geometry, const VoxelBox& box, const VoxelBox& part,
  const PotentialGains& gains, float* potential, float* force);
/// The same with G_sigma * f known over `smoothBox` only (x fastest), which holds `part` and its
/// neighbours within the image.
DEFORMABLESURFACEFILTERS_EXPORT void PotentialAndForceInBox(const float* smooth,
  const VoxelBox& smoothBox, const ImageGeometry& geometry, const VoxelBox& box,
  const VoxelBox& part, const PotentialGains& gains, float* potential, float* force);

/// P and -grad P at the voxels of `part` (a box within `box`) of the image of `geometry` whose
/// locally normalised P (EdgeNormalization::Local) is known over `potentialBox` (x fastest;
/// `part` and its neighbours within the image), stored where they lie in `box`: -grad P by
/// central differences of P (one-sided at the image's border), bit for bit what
/// ComputeScaleSpaceForceInto gives there with that normalisation. Runs serially.
DEFORMABLESURFACEFILTERS_EXPORT void ForceOfPotentialInBox(const float* potentialValues,
  const VoxelBox& potentialBox, const ImageGeometry& geometry, const VoxelBox& box,
  const VoxelBox& part, float* potential, float* force);

/// P of ComputeScaleSpaceForce with the local edge normalisation (EdgeNormalization::Local)
/// at the voxels of `wanted` only (ids of the voxels of `image`, x fastest; the set finished):
/// potential[wanted.Rank(v)] is bit for bit the whole field's P at v, both maxima of the
/// normalisation taken over the voxels [MaximumBegin, MaximumEnd) and passed through
/// GradientMaximum when it is set (Smooth must be empty). The field is computed in slabs of
/// `coreSlices` slices along z (0: four times the pipeline's reach along z) with that reach on
/// either side, and only the maxima and the wanted voxels' values are kept: 12 bytes a voxel of
/// one slab and 8 a wanted voxel (12 with an image term), instead of 12 bytes a voxel of the
/// image. Where the second Gaussian is recursive along z (2 sigma of 3 voxels or more: it
/// reads whole lines) each slab's g is made twice (its G_sigma * f twice more when that is
/// recursive along z too), its passes along z started from the
/// states recorded by passes up and down the slabs (dsSmoothSlabs.h's RecursiveSlabsZ; slabs of
/// `coreSlices`, 0: about sqrt(10 nz)); that holds a few slabs and 80 bytes a line a slab
/// boundary for each recursive pass along z. The largest
/// locally normalised g is found without a second pass: a voxel's ratio g / (G_2sigma * g +
/// floor) cannot exceed that of a voxel with a larger g and a smaller G_2sigma * g, so only the
/// voxels no earlier voxel beats on both are kept until the floor is known. False with a
/// message as ComputeScaleSpaceForce.
DEFORMABLESURFACEFILTERS_EXPORT bool LocalPotentialAt(const ImageView& image,
  const ScaleSpaceParameters& parameters, const VoxelSet& wanted, std::vector<float>& potential,
  std::string* error, int coreSlices = 0);

/// Bytes LocalPotentialAt holds at most for `wanted` voxels of an image of `geometry` with
/// these parameters and coreSlices (the memory estimate of the sigma_0 probe, dsMemory.h): its
/// three floats a voxel of one slab and at most two more for the slab's candidates for the
/// largest ratio (or, recursive along z, the slabs and states above), two floats a wanted voxel
/// (three with an image term) and the set itself.
DEFORMABLESURFACEFILTERS_EXPORT double LocalPotentialBytes(const ImageGeometry& geometry,
  const ScaleSpaceParameters& parameters, const VoxelSet& wanted, int coreSlices = 0);
/// The same for a set of `wantedVoxels` members (a field's tiles, dsFieldBricks.h).
DEFORMABLESURFACEFILTERS_EXPORT double LocalPotentialBytes(const ImageGeometry& geometry,
  const ScaleSpaceParameters& parameters, double wantedVoxels, int coreSlices = 0);

/// G_sigma * f alone (same separable filter, same border handling), in place on a
/// float volume of geometry.Dimensions. sigma in world units. Exposed for tests.
DEFORMABLESURFACEFILTERS_EXPORT bool SmoothGaussian(float* volume, const ImageGeometry& geometry,
  double sigma, int numberOfThreads, std::string* error);
} // namespace dsurf

#endif
