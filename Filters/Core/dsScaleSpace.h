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
//   Force = -grad P           central differences of P, to world like g.
#ifndef dsScaleSpace_h
#define dsScaleSpace_h

#include "DeformableSurfaceFiltersModule.h" // for export macro

#include <functional>
#include <string>
#include <vector>

namespace dsurf
{
/// Where the voxels are: world = Origin + Direction * (Spacing .* ijk).
/// Direction is row-major 3x3 and must be orthonormal (VTK's vtkImageData direction
/// matrix; ComputeScaleSpaceForce rejects anything else).
struct DEFORMABLESURFACEFILTERS_EXPORT ImageGeometry
{
  int Dimensions[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  double Origin[3] = { 0, 0, 0 };
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };

  long long NumberOfVoxels() const
  {
    return static_cast<long long>(this->Dimensions[0]) * this->Dimensions[1] * this->Dimensions[2];
  }
  /// Mean physical extent (the paper's "average extent of the volume"):
  /// mean over the axes of Dimensions[a] * Spacing[a], so a 256^3 unit-spacing
  /// volume has extent 256 and sigma = extent / 6 = 42.7.
  double MeanExtent() const;
  /// The voxel size, the mean spacing: the finest detail the image shows.
  double MeanSpacing() const
  {
    return (this->Spacing[0] + this->Spacing[1] + this->Spacing[2]) / 3.0;
  }
  /// World point -> continuous index (i,j,k).
  void WorldToIndex(const double x[3], double ijk[3]) const;
  /// Continuous index -> world point.
  void IndexToWorld(const double ijk[3], double x[3]) const;
};

/// How the edge strength g = |grad(G_sigma * f)| is made unit-free before it enters P.
enum class EdgeNormalization
{
  /// g / max g: the strongest edge of the volume sets the scale for all (skin/air in a
  /// head mutes the brain's own boundary).
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
  /// A piece of a distributed image (dsPieceField.h): with the global maximum normalisation,
  /// called once with the largest edge strength g over the voxels [MaximumBegin, MaximumEnd)
  /// of the field (its own indices; the voxels the piece owns), computed as the normalisation
  /// computes it; it returns the maximum to normalise with (that of the whole image, over every
  /// process). Empty: the field's own maximum.
  std::function<double(double boxMaximum)> GradientMaximum;
  int MaximumBegin[3] = { 0, 0, 0 };
  int MaximumEnd[3] = { 0, 0, 0 };
};

/// P and -grad P on the voxel grid.
struct DEFORMABLESURFACEFILTERS_EXPORT ForceField
{
  ImageGeometry Geometry;
  double Sigma = 0.0;           ///< physical sigma the field was computed at
  std::vector<float> Potential; ///< P per voxel (x fastest)
  std::vector<float> Force;     ///< -grad P per voxel, 3 components, world coordinates

  bool Empty() const { return this->Potential.empty(); }
  /// Trilinear sample of the force at world point x. Returns false (and f = 0)
  /// when x lies outside the volume: more than half a voxel beyond the outermost voxel
  /// centres (within that half voxel the border value is used).
  bool SampleForce(const double x[3], double f[3]) const;
  /// Trilinear sample of the potential (0 outside).
  double SamplePotential(const double x[3]) const;
};

/// Bytes a ForceField takes per voxel (P and the three components of -grad P, as floats):
/// what a solve, or the Scale-Space Gradient filter's output, allocates per voxel of the image.
constexpr double ForceFieldBytesPerVoxel = 4 * sizeof(float);

/// Trilinear sample of a one-value-per-voxel volume at world point x, with the same reach as
/// ForceField::SampleForce (half a voxel past the outermost centres); 0 and *inside = false
/// outside.
DEFORMABLESURFACEFILTERS_EXPORT double SampleVolume(
  const float* values, const ImageGeometry& geometry, const double x[3], bool* inside);

/// Compute P = -(w_edge * g + w_image * f) with g = |grad(G_sigma * f)| (normalised
/// as documented in vtkImageScaleSpaceGradient.h when NormalizePotential), and
/// Why the scale space at sigma cannot be computed on this geometry, empty when it can: the
/// checks ComputeScaleSpaceForce makes before anything else (3-D, spacing, origin, direction,
/// sigma finite and at most 100 000 voxels along an axis).
DEFORMABLESURFACEFILTERS_EXPORT std::string ScaleSpaceProblem(
  const ImageGeometry& geometry, double sigma);

/// Force = -grad P in world coordinates. scalars: one float per voxel, x fastest.
/// Returns false with a message on bad input (empty, 2-D, non-finite sigma...).
DEFORMABLESURFACEFILTERS_EXPORT bool ComputeScaleSpaceForce(const float* scalars,
  const ImageGeometry& geometry, const ScaleSpaceParameters& parameters, ForceField& out,
  std::string* error);

/// Same computation into caller-owned buffers (no copy for the VTK filter):
/// potential holds NumberOfVoxels floats, force 3 * NumberOfVoxels. The force buffer
/// doubles as the smoothing scratch, so peak memory is input + 4 volumes.
/// scalars must not alias either buffer.
DEFORMABLESURFACEFILTERS_EXPORT bool ComputeScaleSpaceForceInto(const float* scalars,
  const ImageGeometry& geometry, const ScaleSpaceParameters& parameters, float* potential,
  float* force, std::string* error);

/// G_sigma * f alone (same separable filter, same border handling), in place on a
/// float volume of geometry.Dimensions. sigma in world units. Exposed for tests.
DEFORMABLESURFACEFILTERS_EXPORT bool SmoothGaussian(float* volume, const ImageGeometry& geometry,
  double sigma, int numberOfThreads, std::string* error);
} // namespace dsurf

#endif
