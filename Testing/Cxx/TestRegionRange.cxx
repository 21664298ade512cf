// SPDX-License-Identifier: BSD-3-Clause
// The intensity range the region force estimates from a start surface (dsRegion.h), on the
// core: a box start whose vertices lie exactly on voxel centres (picked points often do),
// around a bright cube in a dark image with a brighter object further out:
// - the voxels counted inside are those of the box and nothing else (no scan line paired
//   wrongly where it passes through the box's vertices and edges);
// - the range's low end lies midway between the object and its background, its high end
//   below the brighter neighbour; on a 0/1 mask of the cube too;
// - a start inside one region (no contrast with its outside) gives median -+ 3 s;
// - an inward-oriented start gives the same range once its pieces are turned outward;
// - spheres around a blurred ball in an empty image put the low end at the ball's half level.
// - a click inside one noisy class (its tails beyond the histogram's quantiles) finds one class
//   and keeps the whole class in its range (IsOneClass).
// - clicks in a CT: a soft tissue, which the whole span's fit merges with its neighbours, and a
//   ventricle's CSF, which the fit near it merges with the brain, end between their own class
//   and each neighbour; the air keeps its class.
// - a click beside a dark tissue that lies between two brighter ones (CSF between brain and
//   scalp, the image's empty margin beyond) ends its range at that tissue: it is no blend.
// - a start around an object of an integer image, moved by thousandths of a voxel, keeps its
//   range's low end (whole values counted over the unit each stands for).
#include "DSTestHelpers.h"
#include "TestSolverMeshes.h"

#include "dsMixture.h"
#include "dsRegion.h"
#include "dsScaleSpace.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace dsurf;

namespace
{
/// An n^3 image whose voxel (i, j, k) is tissue(i, j, k, noise), noise() drawing standard normal
/// values from a generator seeded with `seed` (voxels in x-fastest order, so the draws are too).
template <typename Tissue>
std::vector<float> NoisyImage(int n, unsigned seed, Tissue tissue)
{
  std::vector<float> image(static_cast<size_t>(n) * n * n);
  std::mt19937 random(seed);
  std::normal_distribution<float> normal(0.f, 1.f);
  auto noise = [&] { return normal(random); };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        image[(static_cast<size_t>(k) * n + j) * n + i] = tissue(i, j, k, noise);
  return image;
}
} // namespace

int TestRegionRange(int, char*[])
{
  const int n = 40;
  ImageGeometry g;
  g.Dimensions[0] = g.Dimensions[1] = g.Dimensions[2] = n;
  // 100 in the cube [10, 26]^3 (voxel centres), 0 around it, 250 in a slab x >= 34.
  std::vector<float> image(static_cast<size_t>(n) * n * n, 0.f);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        float v = 0.f;
        if (i >= 10 && i <= 26 && j >= 10 && j <= 26 && k >= 10 && k <= 26)
          v = 100.f;
        if (i >= 34)
          v = 250.f;
        image[(static_cast<size_t>(k) * n + j) * n + i] = v;
      }

  // A box from 8 to 28 (half side 10 around 18): vertices on whole voxel indices.
  TriangleMesh box = dstest::MakeCubeSurface(3, 10.0, { 18.0, 18.0, 18.0 });
  std::string error;
  DS_CHECK(box.BuildTopology(&error), error);
  RangeEstimate e;
  DS_CHECK(EstimateIntensityRange(ImageView::Of(image.data(), g), box, 1.0, e, &error), error);
  std::cout << "box start: " << e.Samples << " voxels inside, median " << e.Median << ", range ["
            << e.Range[0] << ", " << e.Range[1] << "], separation " << e.Separation << std::endl;
  // Centres strictly inside (9..27)^3 = 19^3; those on the box's faces (8 or 28) may count.
  DS_CHECK_GE(e.Samples, 19 * 19 * 19, "voxels inside the box: at least those strictly inside");
  DS_CHECK_LE(
    e.Samples, 21 * 21 * 21, "voxels inside the box: at most those within its closed bounds");
  DS_CHECK(e.Contrast, "object against background");
  DS_CHECK_LE(std::abs(e.Range[0] - 50.0), 2.0,
    "range low end midway between object (100) and background (0)");
  DS_CHECK(e.Range[1] >= 100.0 && e.Range[1] < 250.0,
    "range high end above the object, below the bright slab");

  // The cube alone as a 0/1 mask: its whole values span 256 bins each (counted once per value,
  // AddSpreadValues); the low end still lies midway.
  {
    std::vector<float> mask(image.size());
    std::transform(
      image.begin(), image.end(), mask.begin(), [](float v) { return v == 100.f ? 1.f : 0.f; });
    RangeEstimate m;
    DS_CHECK(EstimateIntensityRange(ImageView::Of(mask.data(), g), box, 1.0, m, &error), error);
    std::cout << "box start on the cube's 0/1 mask: range [" << m.Range[0] << ", " << m.Range[1]
              << "]" << std::endl;
    DS_CHECK(m.Contrast, "0/1 mask: object against background");
    DS_CHECK_LE(std::abs(m.Range[0] - 0.5), 0.05, "0/1 mask: the low end midway between 0 and 1");
  }

  // The same box, inward-oriented, turned outward first: the same estimate.
  TriangleMesh inward = box;
  for (auto& t : inward.Triangles)
  {
    std::swap(t[1], t[2]);
  }
  DS_CHECK(inward.BuildTopology(&error), error);
  DS_CHECK(inward.OrientPiecesOutward() == inward.NumberOfTriangles(),
    "every triangle of the inward box reversed");
  RangeEstimate f;
  DS_CHECK(EstimateIntensityRange(ImageView::Of(image.data(), g), inward, 1.0, f, &error), error);
  DS_CHECK(f.Samples == e.Samples && f.Range[0] == e.Range[0] && f.Range[1] == e.Range[1],
    "inward start turned outward: the same estimate");

  // A small box inside the object (a click): no contrast, median -+ 3 s.
  TriangleMesh click = dstest::MakeCubeSurface(2, 3.0, { 18.0, 18.0, 18.0 });
  DS_CHECK(click.BuildTopology(&error), error);
  RangeEstimate c;
  DS_CHECK(EstimateIntensityRange(ImageView::Of(image.data(), g), click, 1.0, c, &error), error);
  std::cout << "click: median " << c.Median << ", spread " << c.Spread << ", range [" << c.Range[0]
            << ", " << c.Range[1] << "]" << std::endl;
  DS_CHECK(!c.Contrast, "a start inside one region: no contrast");
  DS_CHECK(c.Median == 100.0 && c.Range[0] < 100.0 && c.Range[1] > 100.0,
    "click: the region's value in the range");
  DS_CHECK(c.Range[1] < 250.0 && c.Range[0] > 0.0, "click: neither the background nor the slab");

  // A blurred ball in an empty image (1 / (1 + exp(3 (r - 8))), 0 far away), a sphere three
  // voxels around it: the sphere encloses ~a thousand voxels just above 0 (the ball's tail).
  // The boundary must come out at the ball's half level and the range must hold its inside.
  {
    const int nb = 40;
    ImageGeometry gb;
    gb.Dimensions[0] = gb.Dimensions[1] = gb.Dimensions[2] = nb;
    std::vector<float> ball(static_cast<size_t>(nb) * nb * nb);
    for (int k = 0; k < nb; ++k)
      for (int j = 0; j < nb; ++j)
        for (int i = 0; i < nb; ++i)
        {
          const double r =
            std::sqrt((i - 20.0) * (i - 20.0) + (j - 20.0) * (j - 20.0) + (k - 20.0) * (k - 20.0));
          ball[(static_cast<size_t>(k) * nb + j) * nb + i] =
            static_cast<float>(1.0 / (1.0 + std::exp(3.0 * (r - 8.0))));
        }
    for (double radius : { 10.0, 11.0, 14.0 })
    {
      TriangleMesh sphere = dstest::MakeIcosphere(3, radius, { 20.0, 20.0, 20.0 });
      DS_CHECK(sphere.BuildTopology(&error), error);
      RangeEstimate b;
      DS_CHECK(
        EstimateIntensityRange(ImageView::Of(ball.data(), gb), sphere, 1.0, b, &error), error);
      std::cout << "sphere of radius " << radius << " around the blurred ball: range ["
                << b.Range[0] << ", " << b.Range[1] << "]" << std::endl;
      DS_CHECK(b.Contrast, "blurred ball: object against background");
      DS_CHECK_LE(std::abs(b.Range[0] - 0.5), 0.05, "blurred ball: low end at the half level");
      DS_CHECK_GE(b.Range[1], 0.99, "blurred ball: the ball's inside in the range");
    }
  }

  // A two-tone object (80 and 110, as grey and white matter) with a brighter neighbour (140,
  // as fat) just outside the box: level + 3 s would reach past 140 (s ~ 22); the object's
  // 99.5 % quantile caps the range at its own brightest values.
  {
    std::vector<float> mixed(static_cast<size_t>(n) * n * n, 0.f);
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
          float v = 0.f;
          if (i >= 10 && i <= 26 && j >= 10 && j <= 26 && k >= 10 && k <= 26)
            v = i < 18 ? 80.f : 110.f;
          if (i >= 29)
            v = 140.f;
          mixed[(static_cast<size_t>(k) * n + j) * n + i] = v;
        }
    RangeEstimate mx;
    DS_CHECK(EstimateIntensityRange(ImageView::Of(mixed.data(), g), box, 1.0, mx, &error), error);
    std::cout << "two-tone object beside a brighter slab: range [" << mx.Range[0] << ", "
              << mx.Range[1] << "]" << std::endl;
    DS_CHECK(mx.Contrast, "two-tone object: object against background");
    DS_CHECK(
      mx.Range[0] < 80.0 && mx.Range[1] >= 110.0, "two-tone object: both tones in the range");
    DS_CHECK(mx.Range[1] < 125.0, "two-tone object: the range stops below the brighter neighbour");
  }

  // A click's competitors (docs/METHOD.md §9.3): the same small box with a reach of 16 voxels
  // sees the cube (100), the background (0) and the slab (250); the range runs between the
  // decision boundaries of the cube's class and its neighbours', a two-sided force.
  {
    RangeEstimate k;
    DS_CHECK(
      EstimateIntensityRange(ImageView::Of(image.data(), g), click, 1.0, k, &error, 16.0), error);
    std::cout << "click with competitors: " << k.Classes << " classes, range [" << k.Range[0]
              << ", " << k.Range[1] << "]" << std::endl;
    DS_CHECK(k.Contrast && k.Classes == 3, "click: three classes around it, the force two-sided");
    DS_CHECK(k.Range[0] > 10.0 && k.Range[0] < 90.0, "click: low end between background and cube");
    DS_CHECK(
      k.Range[1] > 110.0 && k.Range[1] < 240.0, "click: high end between the cube and the slab");
    // Without the slab in reach (4 voxels: the cube and the background only), the side
    // without a competitor stays open: past the brightest value there.
    RangeEstimate open;
    DS_CHECK(
      EstimateIntensityRange(ImageView::Of(image.data(), g), click, 1.0, open, &error, 4.0), error);
    std::cout << "click, slab out of reach: " << open.Classes << " classes, range ["
              << open.Range[0] << ", " << open.Range[1] << "]" << std::endl;
    DS_CHECK(open.Classes == 1 && !open.Contrast && open.Range[1] < 250.0,
      "click inside the cube's class alone: the median -+ 3 s range, grow only");
  }

  // A narrow tissue beside the click's class is a competitor, not their partial volume, even
  // with a rare brighter class beyond it (docs/METHOD.md §9.3): Colin27's caudate (grey matter,
  // s.d. 14) beside white matter (s.d. 4) with a little bright tissue further out. Slabs along x
  // with Gaussian noise (a fixed seed): 40 +- 10 (CSF), 90 +- 14 (the click's), 113 +- 4, and
  // 157 +- 7 in a small block; the click in the grey slab. Taken for a blend, the range ran past
  // the white matter to the bright class (139 on Colin27).
  {
    const std::vector<float> tissues = NoisyImage(n, 24,
      [](int i, int j, int k, auto& noise)
      {
        float v = i < 7 ? 40.f + 10.f * noise() : 90.f + 14.f * noise();
        if (i >= 30)
          v = 113.f + 4.f * noise();
        if (i >= 32 && j < 10 && k < 10)
          v = 157.f + 7.f * noise();
        return v;
      });
    RangeEstimate t;
    DS_CHECK(
      EstimateIntensityRange(ImageView::Of(tissues.data(), g), click, 1.0, t, &error, 40.0), error);
    std::cout << "click beside a narrow tissue: " << t.Classes << " classes, range [" << t.Range[0]
              << ", " << t.Range[1] << "]" << std::endl;
    DS_CHECK(t.Contrast && t.Range[0] > 40.0 && t.Range[0] < 90.0,
      "narrow tissue: the low end between the dark class and the click's");
    DS_CHECK(t.Range[1] > 90.0 && t.Range[1] < 113.0,
      "narrow tissue: the high end below the narrow tissue, which competes");
  }

  // A dark tissue between two brighter ones is no blend of the darker class beyond it
  // (docs/METHOD.md §9.3, BlendBetweenShare): the README's brain click, whose CSF and bone (22
  // +- 8.5) lie between the brain and the scalp, with the image's empty margin (0) beyond. Slabs
  // along x: 0 exactly, 168 +- 15 (scalp), 22 +- 8 (CSF), the click's 110 +- 3. By its spread the
  // dark class passed for the blend of the margin and the click's class, the margin competed, and
  // the range ran down to 23, into the dark class (101 now).
  {
    const std::vector<float> head = NoisyImage(n, 27,
      [](int i, int, int, auto& noise)
      {
        float v = i < 10 ? 0.f : 168.f + 15.f * noise();
        if (i >= 12)
          v = 22.f + 8.f * noise();
        if (i >= 14)
          v = 110.f + 3.f * noise();
        return v;
      });
    RangeEstimate t;
    DS_CHECK(
      EstimateIntensityRange(ImageView::Of(head.data(), g), click, 1.0, t, &error, 40.0), error);
    std::cout << "click beside a dark tissue between brighter ones: " << t.Classes
              << " classes, range [" << t.Range[0] << ", " << t.Range[1] << "]" << std::endl;
    DS_CHECK(t.Contrast && t.Range[0] > 22.0 + 3 * 8.0 && t.Range[0] < 110.0,
      "dark tissue: the low end between it and the click's class, which it competes with");
  }

  // A soft tissue in a CT (docs/METHOD.md §9.3): slabs along x of air (-1000 +- 5 HU), fat
  // (-100 +- 15), the click's tissue (20 +- 8, as an eye's vitreous), muscle (55 +- 8) and bone
  // (1200 +- 150), the click in the tissue. Their 0.2-99.8 % span puts 9 HU in a bin, the
  // tissue in under three: fitted over the whole span, the tissue merged with its neighbours and
  // the range ran from far into the fat to past the muscle. Fitted again over the click's
  // median +- 10 s.d. of its class, it ends between the tissue and each neighbour.
  {
    const std::vector<float> hu = NoisyImage(n, 2012,
      [](int i, int, int, auto& noise)
      {
        float v = i < 6 ? -1000.f + 5.f * noise() : -100.f + 15.f * noise();
        if (i >= 12)
          v = 20.f + 8.f * noise();
        if (i >= 25)
          v = 55.f + 8.f * noise();
        if (i >= 31)
          v = 1200.f + 150.f * noise();
        return v;
      });
    RangeEstimate t;
    DS_CHECK(
      EstimateIntensityRange(ImageView::Of(hu.data(), g), click, 1.0, t, &error, 40.0), error);
    std::cout << "click in a CT's soft tissue: " << t.Classes << " classes, range [" << t.Range[0]
              << ", " << t.Range[1] << "], object " << t.ObjectMedian << ", nearest class "
              << t.BackgroundMedian << std::endl;
    DS_CHECK(t.Contrast && t.Range[0] > -70.0 && t.Range[0] < 0.0,
      "CT soft tissue: the low end between the fat and the tissue");
    DS_CHECK(t.Range[1] > 30.0 && t.Range[1] < 50.0,
      "CT soft tissue: the high end between the tissue and the muscle");
  }

  // A click in a CT's air: -1024 HU (the scanner's floor) and the integers just above it, in
  // slabs beside fat and bone as above. The air's class is as narrow as a bin because the air
  // is, not because the histogram merges it with a neighbour: fitted again near it, it split
  // into a spike per integer, the next one competed, and the click's own voxels fell outside
  // its range (the surface collapsed). It keeps the whole span's fit.
  {
    const std::vector<float> hu = NoisyImage(n, 2013,
      [](int i, int, int, auto& noise)
      {
        float v = std::max(-1024.f, std::round(-1022.f + 3.f * noise()));
        if (i >= 26)
          v = -100.f + 15.f * noise();
        if (i >= 31)
          v = 1200.f + 150.f * noise();
        return v;
      });
    RangeEstimate t;
    DS_CHECK(
      EstimateIntensityRange(ImageView::Of(hu.data(), g), click, 1.0, t, &error, 40.0), error);
    std::cout << "click in a CT's air: " << t.Classes << " classes, range [" << t.Range[0] << ", "
              << t.Range[1] << "]" << std::endl;
    DS_CHECK(t.Range[0] <= -1024.0 && t.Range[1] >= -1014.0,
      "CT air: the range holds the air's values, the floor and those just above it");
    DS_CHECK(t.Range[1] < -300.0, "CT air: the range ends below the fat");
  }

  // A click in a small tissue that the neighbourhood's mixture merges with others (docs/METHOD.md
  // §9.3, MergesClickTissue): a CT's ventricle, CSF (0 +- 7 HU) in a block of 7^3 voxels around
  // the click, under 1 % of a neighbourhood of brain (25 +- 7 and, where it varies more, 20 +-
  // 15), air (-1000 +- 5), bone (1200 +- 150) and their partial volumes (values spread evenly
  // over [-60, 260] HU). Fitted near the click, the CSF merged with the brain's wider part into
  // a class of 18.5 +- 20.8 and the range, [-32, 69], took in the brain (on the real CT the
  // surface spread over the head). The click's own voxels, narrower than that class and beyond
  // the one-mode bound from its mean, compete in its place: [-22.5, 11.5].
  {
    const std::vector<float> hu = NoisyImage(n, 2014,
      [](int i, int j, int k, auto& noise)
      {
        float v = j < 20 ? 25.f + 7.f * noise() : 20.f + 15.f * noise();
        if (i < 5)
          v = -1000.f + 5.f * noise();
        else if (i >= 35)
          v = 1200.f + 150.f * noise();
        else if (i < 9 || i >= 31)
          v = -60.f + 320.f * (0.5f + 0.5f * std::erf(noise() / std::sqrt(2.f)));
        if (std::abs(i - 18) < 4 && std::abs(j - 18) < 4 && std::abs(k - 18) < 4)
          v = 7.f * noise();
        return v;
      });
    RangeEstimate t;
    DS_CHECK(
      EstimateIntensityRange(ImageView::Of(hu.data(), g), click, 1.0, t, &error, 40.0), error);
    std::cout << "click in a CT's ventricle: " << t.Classes << " classes, range [" << t.Range[0]
              << ", " << t.Range[1] << "], object " << t.ObjectMedian << ", nearest class "
              << t.BackgroundMedian << std::endl;
    DS_CHECK(t.Contrast && t.Range[0] > -40.0 && t.Range[0] < -10.0,
      "CT ventricle: the low end below the CSF, above the partial volumes' spread");
    DS_CHECK(t.Range[1] > 5.0 && t.Range[1] < 18.0,
      "CT ventricle: the high end between the CSF and the brain");
  }

  // A click inside one noisy region, all its neighbourhood one class (a click at the centre of
  // a CT-like ball much larger than its reach: uint16 values 1100 +- 60): one class, so the
  // range is the median -+ 3 s and holds the whole class. The histogram spans the values'
  // 0.5-99.5 % quantiles, the tails piled into its end bins; a mixture fitted as if the span
  // were all (densities at the bin centres) split the one class into four, and the click took
  // the half of its own class beyond its median for a competitor: the range began at ~1100,
  // and the 1024^3 click of BenchScale did not grow.
  {
    std::vector<std::uint16_t> ct(image.size());
    std::mt19937 random(4);
    std::normal_distribution<float> noise(0.f, 1.f);
    for (auto& v : ct)
      v = static_cast<std::uint16_t>(std::lround(1100.f + 60.f * noise(random)));
    TriangleMesh centre = dstest::MakeCubeSurface(2, 3.0, { 19.5, 19.5, 19.5 });
    DS_CHECK(centre.BuildTopology(&error), error);
    RangeEstimate one;
    DS_CHECK(
      EstimateIntensityRange(ImageView::Of(ct.data(), g), centre, 1.0, one, &error, 16.0), error);
    std::cout << "click inside one noisy class: " << one.Classes << " classes, range ["
              << one.Range[0] << ", " << one.Range[1] << "]" << std::endl;
    DS_CHECK(one.Classes == 1 && !one.Contrast, "one noisy class around the click: one class");
    DS_CHECK(one.Range[0] < 1100.0 - 2.0 * 60.0 && one.Range[1] > 1100.0 + 2.0 * 60.0,
      "one noisy class: the range holds the class's values within 2 s.d. of its mean");
  }

  // An integer image (a ball of 100-120, radius 12, in 20 +- 5, with a small dark blob of -200
  // four voxels beyond it, rounded to whole values) and a sphere of radius 14.5 around the ball
  // moved by a few thousandths of a voxel: the range's low end stays put. The lowest values are
  // the few outside samples interpolated on the blob's steep flanks, so the histogram's span
  // moves with the start; binned as they came, the whole values fell into bins about a level
  // wide, some holding one value and some two, and the object's mode jumped between the teeth of
  // that comb as the bins' edges moved (docs/METHOD.md §9.1).
  {
    const std::vector<float> ball = NoisyImage(n, 9,
      [](int i, int j, int k, auto noise)
      {
        const double r =
          std::sqrt((i - 20.0) * (i - 20.0) + (j - 20.0) * (j - 20.0) + (k - 20.0) * (k - 20.0));
        const double inside = 1.0 / (1.0 + std::exp(2.0 * (r - 12.0)));
        // The object's values spread evenly over 100-120 (a flat top, as grey and white matter
        // together make one), the background's noisy.
        const double flat = 0.5 * std::erfc(-noise() / std::sqrt(2.0));
        const double blob =
          std::sqrt((i - 20.0) * (i - 20.0) + (j - 20.0) * (j - 20.0) + (k - 36.0) * (k - 36.0));
        const double value = blob <= 1.0
          ? -200.0 + noise()
          : 20.0 + (80.0 + 20.0 * flat) * inside + 5.0 * (1.0 - inside) * noise();
        return static_cast<float>(std::lround(value));
      });
    double lowest = 1e300, highest = -1e300;
    for (double shift : { 0.0, 0.003, 0.006, 0.009, 0.012, 0.015 })
    {
      TriangleMesh sphere = dstest::MakeIcosphere(3, 14.5, { 20.0 + shift, 20.0, 20.0 });
      DS_CHECK(sphere.BuildTopology(&error), error);
      RangeEstimate r;
      DS_CHECK(
        EstimateIntensityRange(ImageView::Of(ball.data(), g), sphere, 1.0, r, &error), error);
      std::cout << "sphere around an integer ball, moved " << shift << " voxel: range ["
                << r.Range[0] << ", " << r.Range[1] << "]" << std::endl;
      DS_CHECK(r.Contrast, "integer ball: object against background");
      lowest = std::min(lowest, r.Range[0]);
      highest = std::max(highest, r.Range[0]);
    }
    DS_CHECK_LE(highest - lowest, 0.2,
      "integer ball: the low end moves by less than 0.2 when the start moves by 0.015 voxel");
  }

  // The mixture itself: two Gaussians (means 40 and 160, s.d. 10 and 25, weights 0.3 and 0.7)
  // as a 256-bin histogram; BIC keeps two classes, EM finds them.
  {
    std::vector<double> counts(256);
    const double low = 0.0, width = 1.0;
    for (int b = 0; b < 256; ++b)
    {
      const double x = low + (b + 0.5) * width;
      counts[b] = std::round(1e5 *
        (0.3 * std::exp(-0.5 * std::pow((x - 40) / 10, 2)) / (10 * std::sqrt(2 * M_PI)) +
          0.7 * std::exp(-0.5 * std::pow((x - 160) / 25, 2)) / (25 * std::sqrt(2 * M_PI))));
    }
    const Mixture m = FitHistogramMixture(counts, low, width, 4);
    std::cout << "mixture: " << m.Size() << " classes";
    for (int c = 0; c < m.Size(); ++c)
    {
      std::cout << " (" << m.Weight[c] << ", " << m.Mean[c] << ", " << m.Sd[c] << ")";
    }
    std::cout << std::endl;
    DS_CHECK(m.Size() == 2, "mixture: two classes by BIC");
    DS_CHECK(std::abs(m.Mean[0] - 40) < 0.5 && std::abs(m.Mean[1] - 160) < 0.5 &&
        std::abs(m.Sd[0] - 10) < 0.5 && std::abs(m.Sd[1] - 25) < 0.5 &&
        std::abs(m.Weight[0] - 0.3) < 0.01,
      "mixture: the classes' weights, means and spreads");
    DS_CHECK(m.Likeliest(40) == 0 && m.Likeliest(160) == 1, "mixture: each level in its class");
    DS_CHECK(!IsOneClass(counts, low, width, 4), "two Gaussians: not one class");
  }

  // One Gaussian (mean 1100, s.d. 60) as CompetitorsAround bins it: 256 bins between its
  // 0.2 and 99.8 % quantiles (-+2.878 s.d.), the 0.2 % beyond each end in the end bins.
  {
    const double low = 1100 - 2.878 * 60, width = 2 * 2.878 * 60 / 256;
    const auto below = [](double x)
    { return 0.5 * std::erfc(-(x - 1100) / (60 * std::sqrt(2.0))); };
    std::vector<double> counts(256);
    for (int b = 0; b < 256; ++b)
    {
      const double a = b == 0 ? -1e300 : low + b * width;
      const double c = b == 255 ? 1e300 : low + (b + 1) * width;
      counts[b] = std::round(1e6 * (below(c) - below(a)));
    }
    DS_CHECK(IsOneClass(counts, low, width, 4),
      "one Gaussian cut at its 0.2 and 99.8 % quantiles, the tails in the end bins: one class");
  }

  // Speeds: +1 inside, -1 outside, 0 at the ends, never NaN.
  DS_CHECK(RegionSpeed(75, 50, 150) == 1.0 && RegionSpeed(0, 50, 150) == -1.0 &&
      RegionSpeed(50, 50, 150) == 0.0,
    "speed +1 inside, -1 outside, 0 at the ends");
  DS_CHECK(RegionSpeed(std::nan(""), 50, 150) == 0.0, "NaN intensity: no force");

  // A click's last level (MidpointSpeed): a bright rim (600) between the object's range
  // [170, 499] and soft tissue (50) moves the end to the midpoint of the two sides, 325.
  DS_CHECK(MidpointSpeed(325, 600, 50, 170, 499, 0.7) == 0.0 &&
      MidpointSpeed(300, 600, 50, 170, 499, 0.7) < 0.0 &&
      MidpointSpeed(350, 600, 50, 170, 499, 0.7) > 0.0,
    "a rim above the range: the speed changes sign at the midpoint 325, not at 170");
  DS_CHECK(MidpointSpeed(600, 600, 50, 170, 499, -0.7) == 1.0,
    "the rim itself, beyond the range's other end: pushed outward, the ramp is one-sided");
  DS_CHECK(MidpointSpeed(45, 20, 70, 0, 45, -0.2) == 0.0 &&
      MidpointSpeed(44, 20, 70, 0, 45, 0.1) > 0.0 && MidpointSpeed(46, 20, 70, 0, 45, -0.1) < 0.0,
    "a dark object in a bright surround: its end moves to the midpoint 45 of 20 and 70");
  DS_CHECK(MidpointSpeed(300, 300, 200, 170, 499, 0.9) == 0.9,
    "the outside within the range: the range's own speed");
  DS_CHECK(MidpointSpeed(160, 180, 150, 170, 499, -0.2) == -0.2,
    "two sides closer than a fifth of the range (noise): the range's own speed");

  // A click's first levels (WithoutInwardEdgePull): the edge force's pull against the normal
  // weakens by the region speed; a push along the normal and a pull across it are kept.
  const Vec3 up{ 0, 0, 1 };
  const Vec3 pull{ 0.3, -0.2, -2.0 }, push{ 0.3, -0.2, 2.0 };
  DS_CHECK(WithoutInwardEdgePull(pull, up, 1.0) == (Vec3{ 0.3, -0.2, 0.0 }),
    "speed 1: the inward pull is dropped, the tangential part kept");
  DS_CHECK(WithoutInwardEdgePull(pull, up, 0.25) == (Vec3{ 0.3, -0.2, -1.5 }),
    "speed 0.25: three quarters of the inward pull kept");
  DS_CHECK(WithoutInwardEdgePull(push, up, 1.0) == push, "an outward push is kept");
  return dstest::Result("TestRegionRange");
}

int main(int argc, char* argv[])
{
  return TestRegionRange(argc, argv);
}
