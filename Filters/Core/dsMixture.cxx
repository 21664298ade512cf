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

/// EM for k classes on the histogram (centres x, counts n; total > 0), started from the
/// centres of k equal-count slices (spread) or of k equal slices of the span (!spread): a few
/// spikes (a noise-free phantom) can put several equal-count slices on one spike.
Fit FitClasses(
  const std::vector<double>& x, const std::vector<double>& n, double width, int k, bool spread)
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
  for (int it = 0; it <= Iterations; ++it)
  {
    // E step: responsibilities; on the last pass only the likelihood.
    // In logarithms (log-sum-exp): a bin far from every class keeps its responsibility.
    double logLikelihood = 0;
    for (int b = 0; b < bins; ++b)
    {
      double top = -std::numeric_limits<double>::infinity();
      for (int c = 0; c < k; ++c)
      {
        r[c * bins + b] = m.LogDensity(c, x[b]);
        top = std::max(top, r[c * bins + b]);
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
        s += q * x[b];
      }
      const double mu = w > 0 ? s / w : m.Mean[c];
      for (int b = 0; b < bins; ++b)
      {
        ss += r[c * bins + b] * n[b] * (x[b] - mu) * (x[b] - mu);
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

Mixture FitHistogramMixture(
  const std::vector<double>& counts, double low, double width, int maxClasses)
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
      Fit fit = FitClasses(x, counts, width, k, spread);
      if (fit.Bic < best.Bic)
      {
        best = std::move(fit);
      }
    }
  }
  return best.Model;
}
} // namespace dsurf
