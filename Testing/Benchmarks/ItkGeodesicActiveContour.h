// SPDX-License-Identifier: BSD-3-Clause
// ITK's GeodesicActiveContourLevelSetImageFilter as the benchmark runs it, behind a plain-C++
// interface so that no VTK header meets an ITK header (ItkGeodesicActiveContour.cxx is built
// only when CMake finds ITK, for the benchmark; never part of the module).
//
// The pipeline is the one of ITK's own example (Examples/Segmentation/
// GeodesicActiveContourImageFilter.cxx) without its edge-preserving smoothing:
// - feature (speed) image: GradientMagnitudeRecursiveGaussian (FeatureSigma voxels) through a
//   Sigmoid to [0, 1], with the example's recipe alpha = -(K1 - K2) / 6, beta = (K1 + K2) / 2,
//   K1 = EdgeFraction * the largest gradient magnitude (on the boundary), K2 = FlatFraction * it
//   (noise in the flat regions): the speed is ~1 inside flat regions and ~0 on the boundary;
// - initial level set: the signed distance to a sphere inside the object (what the example's
//   fast marching from a seed point with an initial distance gives);
// - the example's scalings (propagation, curvature, advection 1) and stopping (RMS change 0.02
//   or 800 iterations).
#ifndef ItkGeodesicActiveContour_h
#define ItkGeodesicActiveContour_h

#include <string>
#include <vector>

namespace dsbench
{
struct GacSettings
{
  double FeatureSigma = 1.0; ///< voxels
  double EdgeFraction = 0.5, FlatFraction = 0.1;
  double PropagationScaling = 1.0, CurvatureScaling = 1.0, AdvectionScaling = 1.0;
  double MaximumRMSError = 0.02;
  int NumberOfIterations = 800;
  double StartCenter[3] = { 0, 0, 0 }; ///< voxel coordinates
  double StartRadius = 1;              ///< voxels
};

struct GacResult
{
  std::vector<float> LevelSet; ///< n^3, negative inside; its zero level is the surface
  int Iterations = 0;
  double RMSChange = 0;
  std::string Error;
};

/// Runs the pipeline on an n^3 float volume (unit spacing, origin 0). False with Error set on
/// an ITK exception.
bool RunGeodesicActiveContour(
  const float* volume, int n, const GacSettings& settings, GacResult& result);
} // namespace dsbench

#endif
