// SPDX-License-Identifier: BSD-3-Clause
// The core pieces of dsScaleSpace.h:
// - the smoother's impulse response along x, y and z has unit sum, its centre at the
//   impulse and variance sigma^2 (1e-3 relative) from 0.6 to 300 voxels, and departs from
//   the sampled Gaussian exp(-k^2 / 2 sigma^2) by at most 0.5 % of its peak from 3 voxels on
//   (the recursive filter; 5e-4 for the sampled one from 1 to 3 voxels, 1.2 % at 0.6);
// - the default potential's pull on either side of a step edge, 2 and 3 sigma out (2 only at
//   300 voxels, where the float smoothed image cannot resolve the tail), is within
//   5 % of the pull built on the sampled Gaussian (a 3-pole recursive filter is 14-26 % off
//   at 2 sigma with Young-van Vliet's poles, ~15 % at 3 sigma with van Vliet-Young-Verbeek's);
// - steps at the two ends of a short line follow the replicated border: within the
//   reference with the same border (1e-3 of the step; 5e-3 at 0.6 voxel);
// - a constant volume stays constant (Triggs-Sdika border start: no ringing);
// - 1 and 2 threads give bit-identical force fields;
// - SampleForce / SamplePotential are exact for a trilinear field, false/0 outside.
#include "DSTestHelpers.h"

#include "dsScaleSpace.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
/// A volume n voxels long along `axis` and 2 across: a 1-D signal repeated over the 2 x 2
/// cross-section, which the other two axes leave alone.
struct Line
{
  dsurf::ImageGeometry Geometry;
  int Axis, N;
  Line(int axis, int n)
    : Axis(axis)
    , N(n)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Geometry.Dimensions[a] = a == axis ? n : 2;
    }
  }
  std::size_t At(int t, int cross = 0) const
  {
    int ijk[3] = { 0, 0, 0 };
    ijk[this->Axis] = t;
    ijk[(this->Axis + 1) % 3] = cross & 1;
    ijk[(this->Axis + 2) % 3] = cross >> 1;
    const int* d = this->Geometry.Dimensions;
    return static_cast<std::size_t>(ijk[0] + d[0] * (ijk[1] + d[1] * ijk[2]));
  }
  std::vector<float> Volume(const std::vector<double>& signal) const
  {
    std::vector<float> v(this->Geometry.NumberOfVoxels());
    for (int t = 0; t < this->N; ++t)
      for (int c = 0; c < 4; ++c)
      {
        v[this->At(t, c)] = static_cast<float>(signal[t]);
      }
    return v;
  }
};

/// The reference: exp(-k^2 / 2 sigma^2) sampled out to 8 sigma, normalised to unit sum, applied
/// with the image's replicated border, in double.
std::vector<double> GaussianReference(const std::vector<double>& f, double sigma)
{
  const int R = static_cast<int>(std::ceil(8 * sigma)) + 1, n = static_cast<int>(f.size());
  std::vector<double> taps(2 * R + 1);
  double sum = 0;
  for (int k = -R; k <= R; ++k)
  {
    sum += taps[k + R] = std::exp(-0.5 * k * k / (sigma * sigma));
  }
  std::vector<double> out(n, 0.0);
  for (int t = 0; t < n; ++t)
    for (int k = -R; k <= R; ++k)
    {
      out[t] += taps[k + R] / sum * f[std::min(std::max(t - k, 0), n - 1)];
    }
  return out;
}

/// Largest error of the impulse response against the sampled Gaussian, as a fraction of the
/// Gaussian's peak, for sigma (in voxels) along `axis`; checks unit sum, centre and variance.
double ImpulseError(int axis, double sigma)
{
  const int n = static_cast<int>(std::ceil(12 * sigma)) * 2 + 21, c = n / 2;
  const Line line(axis, n);
  std::vector<double> impulse(n, 0.0);
  impulse[c] = 1.0;
  std::vector<float> v = line.Volume(impulse);
  std::string error;
  DS_CHECK(dsurf::SmoothGaussian(v.data(), line.Geometry, sigma, 1, &error), error);
  const std::vector<double> ref = GaussianReference(impulse, sigma);
  double s0 = 0, s1 = 0, s2 = 0, worst = 0;
  for (int t = 0; t < n; ++t)
  {
    const double w = v[line.At(t, 3)];
    s0 += w;
    s1 += w * (t - c);
    s2 += w * (t - c) * (t - c);
    worst = std::max(worst, std::fabs(w - ref[t]) / ref[c]);
  }
  const double mean = s1 / s0, var = s2 / s0 - mean * mean;
  std::cout << "axis " << axis << " sigma " << sigma << ": sum " << s0 << " mean " << mean
            << " variance / sigma^2 " << var / (sigma * sigma) << ", max |h - Gaussian| "
            << 100 * worst << " % of the peak" << std::endl;
  DS_CHECK_LE(std::fabs(s0 - 1.0), 1e-5, "|sum - 1|");
  DS_CHECK_LE(std::fabs(mean), 1e-3 * sigma, "|mean offset| (voxels)");
  DS_CHECK_LE(std::fabs(var / (sigma * sigma) - 1.0), 1e-3, "|variance / sigma^2 - 1|");
  return worst;
}

/// -dP/dt along a line of P = -g / max g, g = |s'| with s' the central difference, at voxel t,
/// by the chain rule as the field computes it: g' = s'' sign(s'), s'' = s[t+1] - 2 s[t] + s[t-1].
std::vector<double> PullOfStep(const std::vector<double>& smooth)
{
  const int n = static_cast<int>(smooth.size());
  std::vector<double> g(n, 0.0), pull(n, 0.0);
  for (int t = 1; t + 1 < n; ++t)
  {
    g[t] = std::fabs(0.5 * (smooth[t + 1] - smooth[t - 1]));
  }
  const double gMax = *std::max_element(g.begin(), g.end());
  for (int t = 1; t + 1 < n; ++t)
  {
    const double slope = smooth[t + 1] - smooth[t - 1];
    const double curvature = smooth[t + 1] - 2.0 * smooth[t] + smooth[t - 1];
    pull[t] = (slope > 0 ? curvature : slope < 0 ? -curvature : 0.0) / gMax;
  }
  return pull;
}

double Interpolate(const std::vector<double>& f, double x)
{
  const int t = static_cast<int>(std::floor(x));
  return f[t] + (x - t) * (f[t + 1] - f[t]);
}

/// The force of the default potential at 2 and 3 sigma on either side of a step edge, against
/// the same potential built on the sampled Gaussian: the largest relative deviation.
double EdgePullError(int axis, double sigma)
{
  const int n = static_cast<int>(std::ceil(10 * sigma)) * 2 + 21, c = n / 2;
  const Line line(axis, n);
  std::vector<double> step(n, 0.0);
  std::fill(step.begin() + c, step.end(), 1.0); // the edge lies at c - 0.5
  const std::vector<float> v = line.Volume(step);
  dsurf::ScaleSpaceParameters p;
  p.Sigma = sigma;
  dsurf::ForceField field;
  std::string error;
  DS_CHECK(dsurf::ComputeScaleSpaceForce(v.data(), line.Geometry, p, field, &error), error);
  std::vector<double> ours(n);
  for (int t = 0; t < n; ++t)
  {
    ours[t] = field.Force[3 * line.At(t) + axis];
  }
  const std::vector<double> ref = PullOfStep(GaussianReference(step, sigma));
  double worst = 0;
  for (double d : { 2.0, 3.0 })
    for (double side : { -1.0, 1.0 })
    {
      const double x = c - 0.5 + side * d * sigma;
      const double r = Interpolate(ours, x) / Interpolate(ref, x) - 1.0;
      std::cout << "  edge pull at " << side * d << " sigma: " << 100 * r << " %" << std::endl;
      if (d == 2.0)
      {
        DS_CHECK_LE(std::fabs(r), 0.05, "|edge pull at 2 sigma / Gaussian's - 1|");
      }
      worst = std::max(worst, std::fabs(r));
    }
  return worst;
}

/// A step one voxel from each end of a short line: the replicated border, against the
/// reference with the same border; max error as a fraction of the step.
double BorderError(double sigma)
{
  const int n = static_cast<int>(std::ceil(3 * sigma)) + 4;
  const Line line(0, n);
  std::vector<double> f(n, 0.0);
  f[0] = 1.0;
  f[n - 2] = f[n - 1] = 0.5;
  std::vector<float> v = line.Volume(f);
  std::string error;
  DS_CHECK(dsurf::SmoothGaussian(v.data(), line.Geometry, sigma, 1, &error), error);
  const std::vector<double> ref = GaussianReference(f, sigma);
  double worst = 0;
  for (int t = 0; t < n; ++t)
  {
    worst = std::max(worst, std::fabs(v[line.At(t)] - ref[t]));
  }
  return worst;
}
} // namespace

int TestScaleSpaceCore(int, char*[])
{
  // The smoother against the sampled Gaussian (docs/METHOD.md §6c). From 3 voxels on the
  // recursive filter: measured 0.11 % of the peak at 3, 0.10 % from 5 on (the 3rd-order
  // filter used before departed by 8-25 %). Below 3 the sampled Gaussian itself, cut at 4 sigma
  // (measured <= 2.2e-4); at 0.6 voxel its width is raised to keep the variance sigma^2, which
  // moves it 1.0 % of the peak from the plain samples. Edge pull (the chain rule's, as the
  // field computes it): measured within 0.8 % at 2 sigma and 4.0 % at 3 sigma; at 300 voxels
  // 1.8 % at 2 sigma, and 3 sigma out the float smoothed image's resolution shows (19 %). Border
  // steps: measured
  // <= 3.0e-4 (3.3e-3 at 0.6).
  for (double sigma : { 0.6, 1.0, 1.5, 2.0, 2.99, 3.0, 5.3, 10.7, 42.7, 300.0 })
  {
    const double limit = sigma >= 3.0 ? 0.005 : sigma >= 1.0 ? 5e-4 : 0.012;
    for (int axis = 0; axis < 3; ++axis)
    {
      DS_CHECK_LE(ImpulseError(axis, sigma), limit, "max |h - sampled Gaussian| / peak");
    }
    const double pull = EdgePullError(sigma == 42.7 ? 2 : sigma == 300.0 ? 1 : 0, sigma);
    if (sigma < 100.0) // beyond, the float smoothed image limits the pull 3 sigma out
    {
      DS_CHECK_LE(pull, 0.05, "|edge pull at 2 and 3 sigma / Gaussian's - 1|");
    }
    const double border = BorderError(sigma);
    std::cout << "  border steps: max error " << border << std::endl;
    DS_CHECK_LE(border, sigma >= 1.0 ? 1e-3 : 5e-3, "border steps, max error / step");
  }

  // Constant volume: any border ringing would show here.
  {
    dsurf::ImageGeometry g;
    g.Dimensions[0] = 37;
    g.Dimensions[1] = 21;
    g.Dimensions[2] = 15;
    g.Spacing[2] = 0.3;
    std::vector<float> v(g.NumberOfVoxels(), 1234.5f);
    std::string error;
    dsurf::SmoothGaussian(v.data(), g, 20.0, 2, &error);
    double worst = 0;
    for (float x : v)
    {
      worst = std::max(worst, std::fabs(x - 1234.5) / 1234.5);
    }
    DS_CHECK_LE(worst, 1e-6, "constant volume, sigma 20: max relative change");
  }

  // Threads: same numbers with 1 and 2 threads.
  {
    dsurf::ImageGeometry g;
    g.Dimensions[0] = 40;
    g.Dimensions[1] = 33;
    g.Dimensions[2] = 29;
    std::vector<float> v(g.NumberOfVoxels());
    for (size_t i = 0; i < v.size(); ++i)
    {
      v[i] = static_cast<float>(std::sin(0.37 * i) + 0.001 * i);
    }
    dsurf::ScaleSpaceParameters p;
    p.Sigma = 3.0;
    p.ImageWeight = 0.5;
    dsurf::ForceField a, b;
    p.NumberOfThreads = 1;
    dsurf::ComputeScaleSpaceForce(v.data(), g, p, a, nullptr);
    p.NumberOfThreads = 2;
    dsurf::ComputeScaleSpaceForce(v.data(), g, p, b, nullptr);
    DS_CHECK(a.Force == b.Force && a.Potential == b.Potential, "1 and 2 threads identical");
  }

  // Sampling: a trilinear field (f = 1 + 2i - j + 0.5k + 0.1 i j k) is reproduced exactly.
  {
    dsurf::ForceField field;
    dsurf::ImageGeometry& g = field.Geometry;
    g.Dimensions[0] = 5;
    g.Dimensions[1] = 4;
    g.Dimensions[2] = 3;
    g.Spacing[0] = 0.5;
    g.Spacing[1] = 2.0;
    g.Spacing[2] = 1.5;
    g.Origin[0] = 10;
    g.Origin[1] = -3;
    g.Origin[2] = 1;
    const double Rz[9] = { 0, -1, 0, 1, 0, 0, 0, 0, 1 };
    std::copy(Rz, Rz + 9, g.Direction);
    auto lin = [](double i, double j, double k)
    { return 1 + 2 * i - j + 0.5 * k + 0.1 * i * j * k; };
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 5; ++i)
        {
          field.Potential.push_back(static_cast<float>(lin(i, j, k)));
          for (int c = 0; c < 3; ++c)
          {
            field.Force.push_back(static_cast<float>((c + 1) * lin(i, j, k)));
          }
        }
    double worst = 0;
    for (double t = 0; t <= 1.0; t += 0.125)
    {
      const double ijk[3] = { 4 * t, 3 * (1 - t), 2 * t * t };
      double x[3], back[3], f[3];
      g.IndexToWorld(ijk, x);
      g.WorldToIndex(x, back);
      for (int a = 0; a < 3; ++a)
      {
        worst = std::max(worst, std::fabs(back[a] - ijk[a]));
      }
      const double expected = lin(ijk[0], ijk[1], ijk[2]);
      DS_CHECK(field.SampleForce(x, f), "inside point samples");
      worst = std::max(worst, std::fabs(field.SamplePotential(x) - expected));
      for (int c = 0; c < 3; ++c)
      {
        worst = std::max(worst, std::fabs(f[c] - (c + 1) * expected));
      }
    }
    DS_CHECK_LE(worst, 1e-5, "trilinear sampling and index round trip, max error");
    // Within half a voxel beyond the outermost centre the border value is used; beyond
    // that the point is outside.
    const double ijkBorder[3] = { 4.4, 1, 1 }, ijkAtBorder[3] = { 4, 1, 1 };
    double xBorder[3], xAtBorder[3], fb[3], fa[3];
    g.IndexToWorld(ijkBorder, xBorder);
    g.IndexToWorld(ijkAtBorder, xAtBorder);
    DS_CHECK(field.SampleForce(xBorder, fb) && field.SampleForce(xAtBorder, fa) && fb[0] == fa[0] &&
        fb[1] == fa[1] && fb[2] == fa[2],
      "0.4 voxel beyond the last centre -> the border value");
    const double ijkOut[3] = { 4.6, 1, 1 };
    double xOut[3], f[3];
    g.IndexToWorld(ijkOut, xOut);
    DS_CHECK(!field.SampleForce(xOut, f) && f[0] == 0 && f[1] == 0 && f[2] == 0,
      "outside -> false, zero force");
    DS_CHECK(field.SamplePotential(xOut) == 0.0, "outside -> zero potential");
    DS_CHECK_LE(
      std::fabs(g.MeanExtent() - (5 * 0.5 + 4 * 2.0 + 3 * 1.5) / 3.0), 1e-12, "MeanExtent error");
  }
  return dstest::Result("TestScaleSpaceCore");
}

int main(int argc, char* argv[])
{
  return TestScaleSpaceCore(argc, argv);
}
