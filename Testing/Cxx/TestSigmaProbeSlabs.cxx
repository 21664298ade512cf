// SPDX-License-Identifier: BSD-3-Clause
// The sigma_0 probe's potential computed slab by slab at chosen voxels only (LocalPotentialAt,
// dsScaleSpace.h; docs/METHOD.md §9.7) equals the whole field's P there bit for bit (tolerance
// 0): on a noisy uint16 image with two edges of different contrast, in one slab (100 slices,
// more than the image's 61), in slabs of 1, 5 and 17 slices and of the default, with both
// Gaussians sampled along z and with the second or both recursive along z, with both maxima over
// the whole image and over a box of it, on one and on two threads, through the reductions'
// callback too; and its memory estimate counts one slab and the wanted voxels, less than the
// whole field.
#include "DSTestHelpers.h"

#include "dsScaleSpace.h"
#include "dsVoxelSet.h"

#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <vector>

using namespace dsurf;

namespace
{
/// 40 x 34 x 61 voxels, anisotropic spacing: a bright ball, a dim block, Gaussian noise.
std::vector<std::uint16_t> Scene(ImageGeometry& g)
{
  g.Dimensions[0] = 40;
  g.Dimensions[1] = 34;
  g.Dimensions[2] = 61;
  g.Spacing[0] = 1.0;
  g.Spacing[1] = 0.9;
  g.Spacing[2] = 1.1;
  std::vector<std::uint16_t> v(static_cast<std::size_t>(g.NumberOfVoxels()));
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 30.0);
  std::size_t n = 0;
  for (int k = 0; k < g.Dimensions[2]; ++k)
    for (int j = 0; j < g.Dimensions[1]; ++j)
      for (int i = 0; i < g.Dimensions[0]; ++i, ++n)
      {
        const double r =
          std::sqrt((i - 18.0) * (i - 18.0) + (j - 16.0) * (j - 16.0) + (k - 25.0) * (k - 25.0));
        const bool block = i > 5 && i < 15 && j > 20 && j < 30 && k > 40 && k < 55;
        const double value = (r < 11.0 ? 1100.0 : block ? 300.0 : 100.0) + noise(rng);
        v[n] = static_cast<std::uint16_t>(std::max(0.0, value));
      }
  return v;
}

/// Every third voxel and a few runs along x (as a ray's cells are).
VoxelSet Wanted(const ImageGeometry& g)
{
  VoxelSet wanted(g.NumberOfVoxels());
  for (long long v = 0; v < g.NumberOfVoxels(); v += 3)
  {
    wanted.Insert(v);
  }
  for (long long v = 1000; v < 1300; ++v)
  {
    wanted.Insert(v);
  }
  wanted.Finish();
  return wanted;
}

/// The largest |difference| of the slabs' P from the whole field's at the wanted voxels.
double Difference(
  const ImageView& view, ScaleSpaceParameters p, const VoxelSet& wanted, int coreSlices, int* calls)
{
  ForceField whole;
  std::string error;
  const bool wholeOk = ComputeScaleSpaceForce(view, p, whole, &error);
  DS_CHECK(wholeOk, error);
  *calls = 0;
  if (p.GradientMaximum)
  {
    p.GradientMaximum = [calls](double m)
    {
      ++*calls;
      return m;
    };
  }
  std::vector<float> at;
  const bool ok = LocalPotentialAt(view, p, wanted, at, &error, coreSlices);
  DS_CHECK(ok, error);
  double worst = 0.0;
  for (long long v = 0; ok && wholeOk && v < view.Geometry.NumberOfVoxels(); ++v)
  {
    if (wanted.Contains(v))
    {
      worst =
        std::max(worst, std::abs(static_cast<double>(at[wanted.Rank(v)]) - whole.Potential[v]));
    }
  }
  return ok && wholeOk ? worst : 1e9;
}
} // namespace

int TestSigmaProbeSlabs(int, char*[])
{
  ImageGeometry g;
  const std::vector<std::uint16_t> image = Scene(g);
  const ImageView view = ImageView::Of(image.data(), g);
  const VoxelSet wanted = Wanted(g);
  long long before = 0; // members below voxel 1299, counted one by one
  for (long long v = 0; v < 1299; ++v)
  {
    before += wanted.Contains(v) ? 1 : 0;
  }
  DS_CHECK(wanted.Size() > g.NumberOfVoxels() / 3 && wanted.Rank(1299) == before && before == 633,
    "the set counts its members in order");
  ScaleSpaceParameters p;
  p.EdgeNormalization = EdgeNormalization::Local;
  p.ComputeForce = false;
  // sigma 1: both Gaussians sampled along z; 2: G_2sigma * g recursive along z (3.6 voxels);
  // 3.5: both recursive along z.
  for (double sigma : { 1.0, 2.0, 3.5 })
    for (int threads : { 1, 2 })
    {
      p.Sigma = sigma;
      p.NumberOfThreads = threads;
      for (bool box : { false, true })
      {
        const int end[3] = { g.Dimensions[0], g.Dimensions[1], g.Dimensions[2] };
        const int inner0[3] = { 3, 6, 20 }, inner1[3] = { 30, 33, 50 };
        for (int a = 0; a < 3; ++a)
        {
          p.MaximumBegin[a] = box ? inner0[a] : 0;
          p.MaximumEnd[a] = box ? inner1[a] : end[a];
        }
        // The whole field normalises over the box only through the callback.
        p.GradientMaximum = box ? [](double m) { return m; } : std::function<double(double)>();
        for (int core : { 0, 1, 5, 17, 100 })
        {
          int calls = 0;
          const double d = Difference(view, p, wanted, core, &calls);
          DS_CHECK(d == 0.0,
            "sigma " + std::to_string(sigma) + ", slabs of " + std::to_string(core) + " slices, " +
              std::to_string(threads) + " thread(s), maxima over " + (box ? "a box" : "the image") +
              ": P equals the whole field's (largest difference " + std::to_string(d) + ")");
          DS_CHECK(calls == (box ? 2 : 0), "both maxima pass through the reductions' callback");
        }
      }
    }
  p.GradientMaximum = nullptr;
  p.Sigma = 3.5;
  ImageGeometry large;
  large.Dimensions[0] = large.Dimensions[1] = large.Dimensions[2] = 512;
  const double recursive = LocalPotentialBytes(large, p, 0.0);
  std::cout << "512^3, sigma 3.5 voxels: " << recursive / large.NumberOfVoxels() << " bytes a voxel"
            << std::endl;
  DS_CHECK_LE(recursive / (12.0 * large.NumberOfVoxels()), 0.5,
    "recursive along z, 512^3: the estimate against the whole field's 12 bytes a voxel");
  p.Sigma = 1.0;
  const double bytes = LocalPotentialBytes(g, p, wanted, 5);
  const double slab = 20.0 * (5 + 2 * 13) * g.Dimensions[0] * g.Dimensions[1];
  DS_CHECK(
    bytes == slab + 8.0 * wanted.Size() + wanted.Bytes() && bytes < 16.0 * g.NumberOfVoxels(),
    "the estimate counts one slab of 5 + 2 x 13 slices and the wanted voxels, less than a whole "
    "field's 16 bytes a voxel");
  VoxelSet few(g.NumberOfVoxels());
  few.Insert(5);
  few.Finish();
  DS_CHECK(few.Bytes() < 0.3 * g.NumberOfVoxels() && few.Size() == 1 && few.Rank(5) == 0,
    "a set holds a quarter of a byte a voxel of its box");
  return dstest::Result("TestSigmaProbeSlabs");
}

int main(int argc, char* argv[])
{
  return TestSigmaProbeSlabs(argc, argv);
}
