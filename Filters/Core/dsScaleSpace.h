// Scale-space external force of the deformable surface (SPEC.md §2, §6.6):
// plain C++, no pipeline types. Shared by vtkImageScaleSpaceGradient and
// vtkDeformableSurfaceFilter so the two never disagree.
#ifndef dsScaleSpace_h
#define dsScaleSpace_h

#include "DeformableSurfaceFiltersModule.h" // for export macro

#include <string>
#include <vector>

namespace dsurf
{
/// Where the voxels are: world = Origin + Direction * (Spacing .* ijk).
/// Direction is row-major 3x3 and orthonormal (VTK's vtkImageData direction matrix).
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
  /// Mean physical extent (the paper's "average extent of the volume").
  double MeanExtent() const;
  /// World point -> continuous index (i,j,k).
  void WorldToIndex(const double x[3], double ijk[3]) const;
  /// Continuous index -> world point.
  void IndexToWorld(const double ijk[3], double x[3]) const;
};

struct DEFORMABLESURFACEFILTERS_EXPORT ScaleSpaceParameters
{
  double Sigma = 1.0;          ///< physical units (isotropic in world space)
  double EdgeWeight = 1.0;     ///< w_edge
  double ImageWeight = 0.0;    ///< w_image
  bool NormalizePotential = true;
  int NumberOfThreads = 0;     ///< 0 = all the machine has (vtkSMPTools STDThread)
};

/// P and -grad P on the voxel grid.
struct DEFORMABLESURFACEFILTERS_EXPORT ForceField
{
  ImageGeometry Geometry;
  double Sigma = 0.0;          ///< physical sigma the field was computed at
  std::vector<float> Potential; ///< P per voxel (x fastest)
  std::vector<float> Force;     ///< -grad P per voxel, 3 components, world coordinates

  bool Empty() const { return this->Potential.empty(); }
  /// Trilinear sample of the force at world point x. Returns false (and f = 0)
  /// when x lies outside the volume.
  bool SampleForce(const double x[3], double f[3]) const;
  /// Trilinear sample of the potential (0 outside).
  double SamplePotential(const double x[3]) const;
};

/// Compute P = -(w_edge * g + w_image * f) with g = |grad(G_sigma * f)| (normalised
/// as documented in vtkImageScaleSpaceGradient.h when NormalizePotential), and
/// Force = -grad P in world coordinates. scalars: one float per voxel, x fastest.
/// Returns false with a message on bad input (empty, 2-D, non-finite sigma...).
DEFORMABLESURFACEFILTERS_EXPORT bool ComputeScaleSpaceForce(const float* scalars,
  const ImageGeometry& geometry, const ScaleSpaceParameters& parameters, ForceField& out,
  std::string* error);
} // namespace dsurf

#endif
