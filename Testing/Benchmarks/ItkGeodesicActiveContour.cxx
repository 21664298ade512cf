// SPDX-License-Identifier: BSD-3-Clause
#include "ItkGeodesicActiveContour.h"

#include "itkGeodesicActiveContourLevelSetImageFilter.h"
#include "itkGradientMagnitudeRecursiveGaussianImageFilter.h"
#include "itkImage.h"
#include "itkImageRegionIteratorWithIndex.h"
#include "itkImportImageFilter.h"
#include "itkMinimumMaximumImageCalculator.h"
#include "itkSigmoidImageFilter.h"

#include <algorithm>
#include <cmath>

namespace dsbench
{
namespace
{
using FloatImage = itk::Image<float, 3>;

FloatImage::Pointer Import(const float* volume, int n)
{
  using Importer = itk::ImportImageFilter<float, 3>;
  auto importer = Importer::New();
  Importer::SizeType size;
  size.Fill(static_cast<itk::SizeValueType>(n));
  Importer::RegionType region;
  region.SetSize(size);
  importer->SetRegion(region);
  const size_t count = static_cast<size_t>(n) * n * n;
  importer->SetImportPointer(const_cast<float*>(volume), count, false);
  importer->Update();
  return importer->GetOutput();
}

FloatImage::Pointer SphereLevelSet(const FloatImage* like, const GacSettings& s)
{
  auto phi = FloatImage::New();
  phi->CopyInformation(like);
  phi->SetRegions(like->GetLargestPossibleRegion());
  phi->Allocate();
  itk::ImageRegionIteratorWithIndex<FloatImage> it(phi, phi->GetLargestPossibleRegion());
  for (it.GoToBegin(); !it.IsAtEnd(); ++it)
  {
    const auto idx = it.GetIndex();
    double d2 = 0;
    for (int a = 0; a < 3; ++a)
      d2 += (idx[a] - s.StartCenter[a]) * (idx[a] - s.StartCenter[a]);
    it.Set(static_cast<float>(std::sqrt(d2) - s.StartRadius));
  }
  return phi;
}

/// The speed image: ~1 in flat regions, ~0 on edges (the example's sigmoid recipe).
FloatImage::Pointer FeatureImage(const FloatImage* input, const GacSettings& s)
{
  using Gradient = itk::GradientMagnitudeRecursiveGaussianImageFilter<FloatImage, FloatImage>;
  auto gradient = Gradient::New();
  gradient->SetInput(input);
  gradient->SetSigma(s.FeatureSigma);
  gradient->Update();
  auto range = itk::MinimumMaximumImageCalculator<FloatImage>::New();
  range->SetImage(gradient->GetOutput());
  range->ComputeMaximum();
  const double k1 = s.EdgeFraction * range->GetMaximum(), k2 = s.FlatFraction * range->GetMaximum();
  using Sigmoid = itk::SigmoidImageFilter<FloatImage, FloatImage>;
  auto sigmoid = Sigmoid::New();
  sigmoid->SetInput(gradient->GetOutput());
  sigmoid->SetOutputMinimum(0.0);
  sigmoid->SetOutputMaximum(1.0);
  sigmoid->SetAlpha(-(k1 - k2) / 6.0);
  sigmoid->SetBeta((k1 + k2) / 2.0);
  sigmoid->Update();
  FloatImage::Pointer feature = sigmoid->GetOutput();
  feature->DisconnectPipeline(); // the gradient magnitude image is freed with its filter
  return feature;
}
} // namespace

bool RunGeodesicActiveContour(
  const float* volume, int n, const GacSettings& settings, GacResult& result)
{
  try
  {
    FloatImage::Pointer input = Import(volume, n);
    FloatImage::Pointer feature = FeatureImage(input, settings);
    FloatImage::Pointer start = SphereLevelSet(input, settings);
    input = nullptr;
    using Gac = itk::GeodesicActiveContourLevelSetImageFilter<FloatImage, FloatImage>;
    auto gac = Gac::New();
    gac->SetPropagationScaling(settings.PropagationScaling);
    gac->SetCurvatureScaling(settings.CurvatureScaling);
    gac->SetAdvectionScaling(settings.AdvectionScaling);
    gac->SetMaximumRMSError(settings.MaximumRMSError);
    gac->SetNumberOfIterations(settings.NumberOfIterations);
    gac->SetInput(start);
    gac->SetFeatureImage(feature);
    gac->Update();
    result.Iterations = static_cast<int>(gac->GetElapsedIterations());
    result.RMSChange = gac->GetRMSChange();
    // Free the filter's working images before the copy, so that the copy does not raise the peak.
    FloatImage::Pointer levelSet = gac->GetOutput();
    levelSet->DisconnectPipeline();
    gac = nullptr;
    feature = nullptr;
    start = nullptr;
    const float* out = levelSet->GetBufferPointer();
    result.LevelSet.assign(out, out + static_cast<size_t>(n) * n * n);
    return true;
  }
  catch (const itk::ExceptionObject& e)
  {
    result.Error = e.GetDescription();
    return false;
  }
}
} // namespace dsbench
