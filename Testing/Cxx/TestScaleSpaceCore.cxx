// The core pieces of dsScaleSpace.h:
// - the smoother's impulse response along x, y and z has unit sum, its centre at the
//   impulse and variance sigma^2 (1e-3 relative) from 0.6 to 42.7 voxels;
// - a constant volume stays constant (Triggs-Sdika border start: no ringing);
// - 1 and 2 threads give bit-identical force fields;
// - SampleForce / SamplePotential are exact for a trilinear field, false/0 outside.
#include "DSTestHelpers.h"

#include "dsScaleSpace.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace
{
void ImpulseMoments(int axis, double sigma)
{
  const int n = static_cast<int>(std::ceil(12 * sigma)) * 2 + 21;
  dsurf::ImageGeometry g;
  for (int a = 0; a < 3; ++a)
  {
    g.Dimensions[a] = a == axis ? n : 2;
  }
  std::vector<float> v(g.NumberOfVoxels(), 0.0f);
  const int c = n / 2;
  auto at = [&](int t)
  {
    int ijk[3] = { 0, 0, 0 };
    ijk[axis] = t;
    return static_cast<size_t>(ijk[0] + g.Dimensions[0] * (ijk[1] + g.Dimensions[1] * ijk[2]));
  };
  // A plane impulse: the other axes see a constant and leave it alone.
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
    {
      size_t idx = at(c);
      const int o1 = (axis + 1) % 3, o2 = (axis + 2) % 3;
      const size_t stride[3] = { 1, static_cast<size_t>(g.Dimensions[0]),
        static_cast<size_t>(g.Dimensions[0]) * g.Dimensions[1] };
      v[idx + a * stride[o1] + b * stride[o2]] = 1.0f;
    }
  std::string error;
  DS_CHECK(dsurf::SmoothGaussian(v.data(), g, sigma, 1, &error), error);
  double s0 = 0, s1 = 0, s2 = 0;
  for (int t = 0; t < n; ++t)
  {
    const double w = v[at(t)];
    s0 += w;
    s1 += w * (t - c);
    s2 += w * (t - c) * (t - c);
  }
  const double mean = s1 / s0, var = s2 / s0 - mean * mean;
  std::cout << "axis " << axis << " sigma " << sigma << ": sum " << s0 << " mean " << mean
            << " variance " << var << " (sigma^2 " << sigma * sigma << ")" << std::endl;
  DS_CHECK_LE(std::fabs(s0 - 1.0), 1e-5, "|sum - 1|");
  DS_CHECK_LE(std::fabs(mean), 1e-3 * sigma, "|mean offset| (voxels)");
  DS_CHECK_LE(std::fabs(var / (sigma * sigma) - 1.0), 1e-3, "|variance / sigma^2 - 1|");
  DS_CHECK_LE(std::fabs(dsurf::SmootherVariance(sigma) / (sigma * sigma) - 1.0), 1e-3,
    "|SmootherVariance / sigma^2 - 1|");
}
} // namespace

int TestScaleSpaceCore(int, char*[])
{
  for (double sigma : { 0.6, 1.0, 2.0, 5.3, 10.7, 42.7 })
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      ImpulseMoments(axis, sigma);
    }
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
