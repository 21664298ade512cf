// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkImageScaleSpaceGradient
 * @brief   External potential and force of the deformable surface at scale sigma.
 *
 * Computes, on the voxel grid of a 3-D vtkImageData, the external potential of
 * Lürig, Kobbelt & Ertl (2000)
 *
 *   P = -( w_edge * |grad(G_sigma * f)| + w_image * (G_sigma * f) )
 *
 * and the force -grad P that pulls a deformable surface onto boundaries. The
 * output is the input image (all its arrays kept, shallow) plus two float32
 * point arrays: "Potential" (P) and "Force" (-grad P, 3 components).
 *
 * How:
 * - f is the array chosen with SetInputArrayToProcess (ParaView: Scalars), any
 *   scalar type, read in place and converted to float as it is read; default the
 *   active point scalars.
 * - G_sigma is separable and isotropic in world units: along axis a it has
 *   sigma / spacing[a] voxels. From 3 voxels on, an axis uses a 5th-order recursive
 *   Gaussian (the poles of van Vliet, Young & Verbeek 1998 with q solved so the
 *   impulse response variance is exactly sigma^2; forward + backward pass, constant
 *   cost per voxel whatever sigma is) with the Triggs & Sdika (2006) start values for
 *   a replicated border, so the border does not ring. Its impulse response departs
 *   from the sampled Gaussian by at most 0.11 % of the peak (0.1 % from 5 voxels on),
 *   and the pull of an edge 2-3 sigma away is within 3.1 % of a true Gaussian's.
 *   Below 3 voxels the axis uses the sampled Gaussian itself (radius 4 sigma; below
 *   ~0.8 voxel its width is raised so the taps keep the variance sigma^2). Sigma
 *   below 0.001 voxel means no smoothing. Measurements: docs/METHOD.md section 6c.
 * - Derivatives are central differences (one-sided on the border) in index
 *   space, taken to world coordinates by Direction * diag(1/Spacing). Spacing,
 *   origin, extent and the direction matrix are honoured: Force is a world vector.
 *   Force is -grad P by the chain rule, w_edge H grad s / |grad s| + w_image grad s
 *   (with the gains of the normalisation below), H the Hessian of s = G_sigma * f from
 *   second differences [1, -2, 1] and mixed central differences: central differences of
 *   the sampled P would widen an edge by about a voxel (docs/METHOD.md section 6.1).
 *   With the local edge normalisation the force stays the central differences of P.
 * - NormalizePotential (default on) makes the defaults work on CT in HU, MRI in
 *   uint8 and float phantoms alike:
 *     P = -( w_edge * g / max(g) + w_image * (s - min s) / (max s - min s) ),
 *   g = |grad s|, s = G_sigma * f, extrema over the whole volume, so P lies in
 *   [-(w_edge + w_image), 0] (a zero range contributes 0). With it off,
 *   P = -(w_edge * g + w_image * s) in the data's own units (Force in units per
 *   world length).
 * - Sigma <= 0 (the default) means Sigma = SigmaFraction * mean extent, the
 *   mean over the axes of dimension * spacing (the paper's 1/6 by default).
 *   The sigma used is stored in the output field data array "Sigma".
 * - Multithreaded with vtkSMPTools on the STDThread backend, NumberOfThreads
 *   threads (0 = all cores).
 *
 * Caveats: the whole extent is requested and processed (no streaming). The
 * direction matrix must be a rotation (orthonormal): a shear or scale is rejected
 * with an error, as are non-finite voxel values (one NaN would spread through the
 * recursive filter). Peak memory is the input and 4 float volumes (P and Force;
 * the image converted to float, then smoothed, lives in the Potential buffer and
 * is replaced by P slice by slice, with two slices of scratch). The max-normalisation follows
 * the strongest edge: one very strong edge (metal in CT) weakens the others.
 * Bad input (no scalars, a 2-D or empty image, multi-component array, NaN/Inf
 * values, a non-rotation direction matrix, a sigma of more than 100000 voxels along an
 * axis) gives an error and an empty output.
 *
 * The computation lives in dsScaleSpace.h (dsurf::ComputeScaleSpaceForce), which
 * vtkDeformableSurfaceFilter also calls, so the two never disagree.
 */
#ifndef vtkImageScaleSpaceGradient_h
#define vtkImageScaleSpaceGradient_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class DEFORMABLESURFACEFILTERS_EXPORT vtkImageScaleSpaceGradient : public vtkImageAlgorithm
{
public:
  static vtkImageScaleSpaceGradient* New();
  vtkTypeMacro(vtkImageScaleSpaceGradient, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Gaussian sigma in world units (isotropic). 0 (default) = use SigmaFraction.
   */
  vtkSetClampMacro(Sigma, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Sigma, double);
  ///@}

  ///@{
  /**
   * Sigma as a fraction of the mean physical extent, used when Sigma is 0.
   * Default 1/6 (the paper's coarsest scale).
   */
  vtkSetClampMacro(SigmaFraction, double, 0.0, 1.0);
  vtkGetMacro(SigmaFraction, double);
  ///@}

  ///@{
  /**
   * w_edge: weight of the edge term |grad(G_sigma * f)|. Default 1.
   */
  vtkSetClampMacro(EdgeWeight, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(EdgeWeight, double);
  ///@}

  ///@{
  /**
   * w_image: weight of the (smoothed) image term, attraction to bright regions. Default 0.
   */
  vtkSetClampMacro(ImageWeight, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ImageWeight, double);
  ///@}

  ///@{
  /**
   * Scale both terms to [0, 1] before weighting (see the class comment). Default on.
   */
  vtkSetMacro(NormalizePotential, bool);
  vtkGetMacro(NormalizePotential, bool);
  vtkBooleanMacro(NormalizePotential, bool);
  ///@}

  ///@{
  /**
   * Threads for the computation; 0 (default) = all cores.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /**
   * Sigma (world units) used by the last successful execution, 0 before.
   */
  vtkGetMacro(EffectiveSigma, double);

protected:
  vtkImageScaleSpaceGradient();
  ~vtkImageScaleSpaceGradient() override;

  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // Sigma and SigmaFraction are this filter's (the core takes the sigma itself; its
  // ScaleSpaceParameters::Sigma is always given); the other defaults are the core's
  // (dsurf::ScaleSpaceParameters), copied in the constructor.
  double Sigma = 0.0;
  double SigmaFraction = 1.0 / 6.0;
  double EdgeWeight{};
  double ImageWeight{};
  bool NormalizePotential{};
  int NumberOfThreads{};
  double EffectiveSigma = 0.0;

private:
  vtkImageScaleSpaceGradient(const vtkImageScaleSpaceGradient&) = delete;
  void operator=(const vtkImageScaleSpaceGradient&) = delete;
};
#endif
