// SPDX-License-Identifier: BSD-3-Clause
// A one-dimensional Gaussian mixture fitted to a histogram: the intensity classes around a
// click, for the region competition of dsRegion.h (docs/METHOD.md §9.3). Plain C++.
#ifndef dsMixture_h
#define dsMixture_h

#include "DeformableSurfaceFiltersModule.h" // for export macro

#include <vector>

namespace dsurf
{
/// Gaussian classes of intensity: weights (summing to 1), means and standard deviations.
struct DEFORMABLESURFACEFILTERS_EXPORT Mixture
{
  std::vector<double> Weight, Mean, Sd;
  int Size() const { return static_cast<int>(this->Mean.size()); }
  /// Weight * density of class k at x.
  double Density(int k, double x) const;
  /// Its logarithm, which never underflows (classes as narrow as a bin, far from x).
  double LogDensity(int k, double x) const;
  /// The class of largest Density at x (-1 for an empty mixture).
  int Likeliest(double x) const;
};

/// The mixture of 1 to maxClasses classes that best explains the histogram `counts` (bins of
/// `width` from `low`), each fitted by expectation-maximisation (Dempster, Laird and Rubin,
/// JRSS B 39, 1977) from two starts (the centres of equal-count slices and of equal slices of the
/// span), the number of classes chosen by the Bayesian
/// information criterion (Schwarz, Ann. Stat. 6, 1978) so that noise does not pass for a
/// class. A class is never narrower than a bin. Deterministic: the same histogram gives the
/// same mixture on every process. Empty for no counts, maxClasses < 1 or a bad bin width.
DEFORMABLESURFACEFILTERS_EXPORT Mixture FitHistogramMixture(
  const std::vector<double>& counts, double low, double width, int maxClasses);

/// Whether BIC picks one class among 1 to maxClasses (FitHistogramMixture) when the first and
/// the last bin also hold every value below and above the span (a histogram between two
/// quantiles, the tails piled into its ends): each class's likelihood there is its tail's mass,
/// and those values enter EM at the tail's mean (grouped and truncated data: McLachlan and
/// Jones, Biometrics 44, 1988). Taken at their centres instead, the two piles are spikes that
/// even one Gaussian class cannot fit: one noisy class came out as four.
DEFORMABLESURFACEFILTERS_EXPORT bool IsOneClass(
  const std::vector<double>& counts, double low, double width, int maxClasses);
} // namespace dsurf

#endif
