// SPDX-License-Identifier: BSD-3-Clause
#include "dsMixture.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dsurf
{
namespace
{
constexpr int Iterations = 200;

struct Fit
{
  Mixture Model;
  double Bic = std::numeric_limits<double>::infinity();
};

/// The standard normal's upper tail, accurate far out (erfc, not 1 - erf).
double UpperTail(double z)
{
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

double UnitDensity(double z)
{
  return std::isinf(z) ? 0.0 : std::exp(-0.5 * z * z) / std::sqrt(2.0 * M_PI);
}

/// Class c's share of an outer bin open to one side (below `edge` when `below`, else above),
/// as grouped and truncated data (McLachlan and Jones, Biometrics 44, 1988): the log of its
/// tail's mass per unit of bin width (so that it adds to the likelihood as a density at a bin
/// centre does), and the mean and variance of the class truncated to that tail. False when the
/// tail's mass underflows: the bin is then taken at its centre.
bool OuterBin(const Mixture& m, int c, double edge, bool below, double width, double& logShare,
  double& mean, double& variance)
{
  const double sd = m.Sd[c], a = (edge - m.Mean[c]) / sd;
  const double mass = below ? UpperTail(-a) : UpperTail(a); // on the tail's side: no 1 - (~1)
  if (!(mass > 1e-300))
  {
    return false;
  }
  const double z = (below ? -UnitDensity(a) : UnitDensity(a)) / mass; // the tail's mean, in s.d.
  logShare = std::log(m.Weight[c]) + std::log(mass / width);
  mean = m.Mean[c] + sd * z;
  variance = sd * sd * std::max(0.0, 1.0 + a * z - z * z);
  return true;
}

/// EM for k classes on the histogram (centres x, counts n; total > 0), started from the
/// centres of k equal-count slices (spread) or of k equal slices of the span (!spread): a few
/// spikes (a noise-free phantom) can put several equal-count slices on one spike. With
/// `openEnds` the first and last bins hold every value below and above the span (OuterBin):
/// taken at its centre, such a bin is a spike (a tail of MixtureTailShare in one bin) that even one
/// Gaussian class cannot fit, so BIC took the one class of a noisy ball for four.
Fit FitClasses(const std::vector<double>& x, const std::vector<double>& n, double width, int k,
  bool spread, bool openEnds)
{
  const int bins = static_cast<int>(x.size());
  double total = 0;
  for (double c : n)
  {
    total += c;
  }
  Mixture m;
  m.Weight.assign(k, 1.0 / k);
  m.Mean.assign(k, 0.0);
  m.Sd.assign(k, 0.0);
  // Start: the k equal-count slices' centres, a spread of a k-th of the whole.
  double mean = 0, var = 0;
  for (int b = 0; b < bins; ++b)
  {
    mean += n[b] * x[b] / total;
  }
  for (int b = 0; b < bins; ++b)
  {
    var += n[b] * (x[b] - mean) * (x[b] - mean) / total;
  }
  double acc = 0;
  for (int c = 0, b = 0; c < k; ++c)
  {
    const double target = (c + 0.5) / k * total;
    while (b + 1 < bins && acc + n[b] < target)
    {
      acc += n[b++];
    }
    m.Mean[c] = spread ? x[b] : x.front() + (c + 0.5) / k * (x.back() - x.front());
    m.Sd[c] = std::max(width, std::sqrt(var) / k);
  }
  std::vector<double> r(static_cast<std::size_t>(k) * bins);
  // Where each bin's values lie for each class, and their variance within it (0 at a centre).
  std::vector<double> at(r.size()), within(r.size(), 0.0);
  for (int it = 0; it <= Iterations; ++it)
  {
    // E step: responsibilities; on the last pass only the likelihood.
    // In logarithms (log-sum-exp): a bin far from every class keeps its responsibility.
    double logLikelihood = 0;
    for (int b = 0; b < bins; ++b)
    {
      double top = -std::numeric_limits<double>::infinity();
      const bool outer = openEnds && (b == 0 || b + 1 == bins);
      for (int c = 0; c < k; ++c)
      {
        const std::size_t i = c * bins + b;
        at[i] = x[b];
        within[i] = 0.0;
        if (!outer ||
          !OuterBin(
            m, c, x[b] + (b == 0 ? 0.5 : -0.5) * width, b == 0, width, r[i], at[i], within[i]))
        {
          r[i] = m.LogDensity(c, x[b]);
        }
        top = std::max(top, r[i]);
      }
      double sum = 0;
      for (int c = 0; c < k; ++c)
      {
        r[c * bins + b] = std::exp(r[c * bins + b] - top);
        sum += r[c * bins + b];
      }
      logLikelihood += n[b] * (top + std::log(sum * width));
      for (int c = 0; c < k; ++c)
      {
        r[c * bins + b] /= sum;
      }
    }
    if (it == Iterations)
    {
      Fit fit;
      fit.Model = m;
      fit.Bic = -2.0 * logLikelihood + (3.0 * k - 1.0) * std::log(total);
      return fit;
    }
    // M step.
    for (int c = 0; c < k; ++c)
    {
      double w = 0, s = 0, ss = 0;
      for (int b = 0; b < bins; ++b)
      {
        const double q = r[c * bins + b] * n[b];
        w += q;
        s += q * at[c * bins + b];
      }
      const double mu = w > 0 ? s / w : m.Mean[c];
      for (int b = 0; b < bins; ++b)
      {
        const double d = at[c * bins + b] - mu; // as before when `within` is 0
        ss += r[c * bins + b] * n[b] * d * d + r[c * bins + b] * n[b] * within[c * bins + b];
      }
      m.Weight[c] = std::max(w / total, 1e-12);
      m.Mean[c] = mu;
      m.Sd[c] = std::max(width, w > 0 ? std::sqrt(ss / w) : width);
    }
  }
  return Fit();
}
} // namespace

double Mixture::Density(int k, double x) const
{
  const double z = (x - this->Mean[k]) / this->Sd[k];
  return this->Weight[k] * std::exp(-0.5 * z * z) / (this->Sd[k] * std::sqrt(2.0 * M_PI));
}

double Mixture::LogDensity(int k, double x) const
{
  const double z = (x - this->Mean[k]) / this->Sd[k];
  return std::log(this->Weight[k]) - 0.5 * z * z - std::log(this->Sd[k] * std::sqrt(2.0 * M_PI));
}

int Mixture::Likeliest(double x) const
{
  if (this->Size() == 0)
  {
    return -1;
  }
  int best = 0;
  for (int k = 1; k < this->Size(); ++k)
  {
    best = this->LogDensity(k, x) > this->LogDensity(best, x) ? k : best;
  }
  return best;
}

namespace
{
Mixture BestMixture(
  const std::vector<double>& counts, double low, double width, int maxClasses, bool openEnds)
{
  double total = 0;
  for (double c : counts)
  {
    total += c;
  }
  if (counts.empty() || maxClasses < 1 || !(total > 0) || !(width > 0) || !std::isfinite(low) ||
    !std::isfinite(width))
  {
    return Mixture();
  }
  std::vector<double> x(counts.size());
  for (std::size_t b = 0; b < x.size(); ++b)
  {
    x[b] = low + (b + 0.5) * width;
  }
  Fit best;
  for (int k = 1; k <= maxClasses; ++k)
  {
    for (const bool spread : { true, false })
    {
      Fit fit = FitClasses(x, counts, width, k, spread, openEnds);
      if (fit.Bic < best.Bic)
      {
        best = std::move(fit);
      }
    }
  }
  return best.Model;
}
} // namespace

Mixture FitHistogramMixture(
  const std::vector<double>& counts, double low, double width, int maxClasses)
{
  return BestMixture(counts, low, width, maxClasses, false);
}

bool IsOneClass(const std::vector<double>& counts, double low, double width, int maxClasses)
{
  return BestMixture(counts, low, width, maxClasses, true).Size() == 1;
}
} // namespace dsurf
