// SPDX-License-Identifier: BSD-3-Clause
// What a distributed solve makes from its start (docs/METHOD.md §9.8): sigma_0 from the start
// (ChoosePieceInitialSigma, dsPieceInitialSigma.h; §9.1) and the estimated intensity range
// (EstimatePieceIntensityRange, dsRegion.h; §9.3), the processes emulated by threads
// (EmulatedRanks.h): a 40 x 40 x 120 image (anisotropic spacing, an origin off zero) of two soft
// balls and noise, split into 2 and 3 slabs along z, each rank holding its slab and
// InitialSigmaProbeGhostVoxels() around it.
// - Starts near the first ball and across the slabs' borders: every rank chooses the serial
//   sigma_0 exactly (the same 90th-percentile distance, rays and rays that met an edge), and
//   no rank holds the whole image; the same for the image as uint16, read in its own type, and
//   for the image turned about x (a direction matrix).
// - A start spanning the image keeps extent / 6 on every rank without a probe, and so does one
//   far outside it (no ray meets the image; its reach clamped to the image's border).
// - A large image (96 x 96 x 1500) is probed coarse first: a start 20 units from a ball keeps
//   the coarse choice (blocks of 3) within 1.5 of 20, one 4 units from it is probed fine, within
//   1 of 4; every rank chooses the serial sigma_0 exactly either way.
// - What lies beyond the rays' reach of the start does not change sigma_0 (a block 1 000 times
//   brighter at the far end), serial or on slabs; a slab beyond it computes no probe.
// - The intensity range estimated from a start around the first ball (object against
//   background), a click inside it (no contrast: median -+ 3 s), a start enclosing too few voxel
//   centres (sampled at its vertices) and one across the slabs' borders: every rank's estimate
//   (range, median, spread, separation, sample counts) equals the serial one exactly, float
//   and uint16 images.
// - Bad input: a rank holding no ghost layers fails every rank with a message, and so does a
//   rank whose probe fails after the first maximum of its normalisation, a 0 that skips the
//   second (no rank waits in a reduction: a hang would hit the ctest timeout).
#include "DSTestHelpers.h"
#include "PieceSlabs.h"
#include "ScaleSpaceTestUtils.h"
#include "TestSolverMeshes.h"

#include "dsPieceInitialSigma.h"
#include "dsRegion.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

using namespace dsurf;

namespace
{
/// Soft balls of radius 10 at world (17, 24, 30) and (17, 24, 80), the second dimmer, and noise.
std::vector<float> Image(const ImageGeometry& g)
{
  std::vector<float> v;
  unsigned state = 777;
  for (int k = 0; k < g.Dimensions[2]; ++k)
    for (int j = 0; j < g.Dimensions[1]; ++j)
      for (int i = 0; i < g.Dimensions[0]; ++i)
      {
        const double x = -3.0 + i - 17.0, y = 2.0 + 1.1 * j - 24.0, z = 5.0 + 0.9 * k;
        const double a = std::sqrt(x * x + y * y + (z - 30) * (z - 30));
        const double b = std::sqrt(x * x + y * y + (z - 80) * (z - 80));
        state = state * 1664525u + 1013904223u;
        v.push_back(static_cast<float>(100.0 / (1.0 + std::exp(a - 10.0)) +
          60.0 / (1.0 + std::exp(b - 10.0)) + 8.0 * (state >> 8) / 16777216.0));
      }
  return v;
}

TriangleMesh Sphere(double radius, const Vec3& centre)
{
  TriangleMesh m = dstest::MakeIcosphere(3, radius, centre);
  std::string err;
  DS_CHECK(m.BuildTopology(&err), err);
  return m;
}

bool SameChoice(const InitialSigmaChoice& a, const InitialSigmaChoice& b)
{
  return a.Sigma == b.Sigma && a.StartDistance == b.StartDistance && a.Rays == b.Rays &&
    a.RaysWithEdge == b.RaysWithEdge && a.SpansVolume == b.SpansVolume &&
    a.ProbeBlock == b.ProbeBlock;
}

/// The serial choice against every rank's, on 2 and 3 slabs; returns the serial one.
template <typename T>
InitialSigmaChoice SameAsSerial(const ImageGeometry& g, const std::vector<T>& image,
  const TriangleMesh& start, const std::string& label, int ghostOverride = -1)
{
  const double paper = g.MeanExtent() / 6.0;
  InitialSigmaChoice serial;
  std::string error;
  DS_CHECK(ChooseInitialSigma(ImageView::Of(image.data(), g), start, paper, 1, serial, &error),
    label + ": serial: " + error);
  for (int nRanks : { 2, 3 })
  {
    dstest::EmulatedRanks ranks(nRanks);
    std::vector<InitialSigmaChoice> choices(nRanks);
    std::vector<int> ok(nRanks, 0), same(nRanks, 0);
    std::vector<long long> held(nRanks, 0);
    ranks.Run(
      [&](int r)
      {
        std::vector<T> values;
        const ImagePiece piece = dstest::Slab<T>(
          g, image, r, nRanks, [&](int a) { return InitialSigmaProbeGhostVoxels(g, a); }, values);
        held[r] = piece.Held.NumberOfVoxels();
        std::string message;
        ok[r] = ChoosePieceInitialSigma(
          piece, start, paper, 1, dstest::ReductionsOf(ranks, r), choices[r], &message);
        same[r] = SameChoice(choices[r], serial);
      });
    const std::string l = label + ", " + std::to_string(nRanks) + " ranks";
    std::cout << l << ": sigma_0 " << serial.Sigma << " (distance " << serial.StartDistance << ", "
              << serial.RaysWithEdge << " of " << serial.Rays << " rays met an edge); rank 0 "
              << choices[0].Sigma << "; held voxels";
    for (long long h : held)
    {
      std::cout << " " << h;
    }
    std::cout << " of " << g.NumberOfVoxels() << std::endl;
    DS_CHECK(std::count(ok.begin(), ok.end(), 1) == nRanks, l + ": every rank chose");
    DS_CHECK(std::count(same.begin(), same.end(), 1) == nRanks,
      l + ": every rank's choice equals the serial one exactly");
    DS_CHECK(ranks.Mismatches() == 0, l + ": the ranks reduced vectors of one size");
    if (!serial.SpansVolume)
    {
      DS_CHECK_LE(*std::max_element(held.begin(), held.end()), g.NumberOfVoxels() - 1,
        l + ": voxels held by the largest piece");
    }
  }
  return serial;
}

/// A large image (96 x 96 x 1500, the paper's sigma_0 86 world units) is probed coarse first
/// (CoarseProbeBlock 3): a start 20 units from the ball it surrounds keeps the coarse choice, one
/// 4 units from it is probed fine; serial and on slabs alike.
/// The large image of CoarseProbe and SampledStatistics: 96 x 96 x 1500 voxels
/// (AnisotropicGeometry), a soft ball of radius 20 at LargeCentre, noise; uint8.
const Vec3 LargeCentre{ 44.5, 54.25, 680.0 };
std::vector<std::uint8_t> LargeImage(const ImageGeometry& g)
{
  unsigned state = 4242; // SampleOnGrid visits the voxels in order, x fastest
  const std::vector<float> values = sstest::SampleOnGrid(g,
    [&](const double* x)
    {
      state = state * 1664525u + 1013904223u;
      const double r = Norm(Vec3{ x[0], x[1], x[2] } - LargeCentre);
      return 30.0 + 170.0 / (1.0 + std::exp(r - 20.0)) + 8.0 * (state >> 8) / 16777216.0;
    });
  return std::vector<std::uint8_t>(values.begin(), values.end());
}

void CoarseProbe()
{
  const ImageGeometry g = dstest::AnisotropicGeometry(96, 96, 1500);
  const Vec3 centre = LargeCentre;
  const std::vector<std::uint8_t> image = LargeImage(g);
  DS_CHECK(CoarseProbeBlock(g, g.MeanExtent() / 6.0) == 3, "the large image's coarse probe block");
  const InitialSigmaChoice far = SameAsSerial(g, image, Sphere(40.0, centre), "coarse: 20 out");
  DS_CHECK(far.ProbeBlock == 3, "a start 20 units out keeps the coarse probe's choice");
  InitialSigmaChoice twoThreads;
  std::string error;
  DS_CHECK(ChooseInitialSigma(ImageView::Of(image.data(), g), Sphere(40.0, centre),
             g.MeanExtent() / 6.0, 2, twoThreads, &error) &&
      SameChoice(twoThreads, far),
    "coarse: 20 out, two threads choose as one: " + error);
  DS_CHECK_LE(std::abs(far.Sigma - 20.0), 1.5, "its sigma_0 against its distance 20");
  const InitialSigmaChoice near = SameAsSerial(g, image, Sphere(24.0, centre), "coarse: 4 out");
  DS_CHECK(near.ProbeBlock == 1, "a start 4 units out is probed fine");
  DS_CHECK_LE(std::abs(near.Sigma - 4.0), 1.0, "its sigma_0 against its distance 4");
}

bool SameEstimate(const RangeEstimate& a, const RangeEstimate& b)
{
  return a.Range[0] == b.Range[0] && a.Range[1] == b.Range[1] && a.Samples == b.Samples &&
    a.OutsideSamples == b.OutsideSamples && a.Median == b.Median && a.Spread == b.Spread &&
    a.Separation == b.Separation && a.ObjectMedian == b.ObjectMedian &&
    a.BackgroundMedian == b.BackgroundMedian && a.FromVertices == b.FromVertices &&
    a.Contrast == b.Contrast && a.Classes == b.Classes;
}

/// The serial range estimate against every rank's, on 2 and 3 slabs; returns the serial one.
template <typename T>
RangeEstimate SameRange(const ImageGeometry& g, const std::vector<T>& image,
  const TriangleMesh& start, const std::string& label, double competitorReach = 0.0)
{
  RangeEstimate serial;
  std::string error;
  DS_CHECK(EstimateIntensityRange(
             ImageView::Of(image.data(), g), start, 1.0, serial, &error, competitorReach),
    label + ": serial: " + error);
  for (int nRanks : { 2, 3 })
  {
    dstest::EmulatedRanks ranks(nRanks);
    std::vector<RangeEstimate> estimates(nRanks);
    std::vector<int> ok(nRanks, 0), same(nRanks, 0);
    ranks.Run(
      [&](int r)
      {
        std::vector<T> values;
        const ImagePiece piece = dstest::Slab<T>(
          g, image, r, nRanks, [&](int a) { return InitialSigmaProbeGhostVoxels(g, a); }, values);
        std::string message;
        ok[r] = EstimatePieceIntensityRange(piece, start, 1.0, dstest::ReductionsOf(ranks, r),
          estimates[r], &message, competitorReach);
        same[r] = SameEstimate(estimates[r], serial);
      });
    const std::string l = label + ", " + std::to_string(nRanks) + " ranks";
    std::cout << l << ": range [" << serial.Range[0] << ", " << serial.Range[1] << "] from "
              << serial.Samples << (serial.FromVertices ? " vertices" : " voxels") << " inside, "
              << serial.OutsideSamples << " outside, contrast " << serial.Contrast << ", "
              << serial.Classes << " classes around; rank 0 [" << estimates[0].Range[0] << ", "
              << estimates[0].Range[1] << "]" << std::endl;
    DS_CHECK(std::count(ok.begin(), ok.end(), 1) == nRanks, l + ": every rank estimated");
    DS_CHECK(std::count(same.begin(), same.end(), 1) == nRanks,
      l + ": every rank's estimate equals the serial one exactly");
    DS_CHECK(ranks.Mismatches() == 0, l + ": the ranks reduced vectors of one size");
  }
  return serial;
}

/// A start enclosing more than 2^22 voxels (an ellipsoid around the large image's ball, ~5.3
/// million): the range statistics read every n-th voxel id (dsRegion.cxx, SampledValues), the
/// same ids on every rank, so each rank's estimate equals the serial one exactly.
void SampledStatistics()
{
  const ImageGeometry g = dstest::AnisotropicGeometry(96, 96, 1500);
  const std::vector<std::uint8_t> image = LargeImage(g);
  TriangleMesh large = Sphere(1.0, LargeCentre);
  for (Vec3& p : large.Points)
  {
    const Vec3 d = p - LargeCentre;
    p = LargeCentre + Vec3{ 44.0 * d[0], 48.0 * d[1], 600.0 * d[2] };
  }
  const RangeEstimate sampled = SameRange(g, image, large, "a start of ~5.3 million voxels");
  DS_CHECK_LE(sampled.Samples, 1LL << 22, "its statistics read at most 2^22 values");
  DS_CHECK_GE(sampled.Samples, 1LL << 20, "and about a third of its voxels");
}

/// sigma_0 depends only on the image within the rays' reach of the start
/// (InitialSigmaProbeReach): a block 1 000 times brighter than the balls beyond it (its edge, in
/// a probe of the whole image, set the floor of the local normalisation and left the balls'
/// edges below the significance: sigma_0 became extent / 6) changes nothing, serial or on slabs
/// (a slab beyond the reach computes no probe).
void BeyondReach(const ImageGeometry& g, const std::vector<float>& image, const TriangleMesh& start)
{
  const double paper = g.MeanExtent() / 6.0;
  const int firstBright = 95; // z from 90.5, the start and its reach end below z 67
  std::vector<float> bright = image;
  const std::size_t slice = static_cast<std::size_t>(g.Dimensions[0]) * g.Dimensions[1];
  for (std::size_t v = firstBright * slice; v < bright.size(); ++v)
  {
    bright[v] += 1.0e5f;
  }
  InitialSigmaChoice plain, withBlock;
  std::string error;
  DS_CHECK(ChooseInitialSigma(ImageView::Of(image.data(), g), start, paper, 1, plain, &error) &&
      ChooseInitialSigma(ImageView::Of(bright.data(), g), start, paper, 1, withBlock, &error),
    "beyond reach: " + error);
  std::cout << "a bright block beyond reach: sigma_0 " << withBlock.Sigma << " (without it "
            << plain.Sigma << ", extent / 6 " << paper << ")" << std::endl;
  DS_CHECK(SameChoice(plain, withBlock), "a bright block beyond reach: the same sigma_0");
  DS_CHECK_LE(plain.Sigma, 0.5 * paper, "sigma_0 from the start's own edge");
  SameAsSerial(g, bright, start, "a start near the first ball, a bright block beyond reach");
}

/// ChoosePieceInitialSigma on 3 slabs, rank r holding ghost(r, a) ghost layers along axis a:
/// every rank fails, rank `culprit` saying `why` and the others that another process could not
/// compute its probe (none is left waiting in a reduction: a hang would hit the ctest timeout).
void EveryRankFails(const ImageGeometry& g, const std::vector<float>& image,
  const TriangleMesh& start, const std::function<int(int, int)>& ghost, int culprit,
  const std::string& why, const std::string& label)
{
  dstest::EmulatedRanks ranks(3);
  std::vector<int> failed(3, 0), said(3, 0);
  std::vector<std::string> messages(3);
  ranks.Run(
    [&](int r)
    {
      std::vector<float> values;
      const ImagePiece piece = dstest::Slab<float>(
        g, image, r, 3, [&](int a) { return ghost(r, a); }, values);
      InitialSigmaChoice choice;
      failed[r] = !ChoosePieceInitialSigma(piece, start, g.MeanExtent() / 6.0, 1,
        dstest::ReductionsOf(ranks, r), choice, &messages[r]);
      said[r] = messages[r].find(r == culprit ? why : "another process") != std::string::npos;
    });
  const int other = culprit == 2 ? 0 : 2;
  std::cout << label << ": rank " << culprit << ": " << messages[culprit] << " / rank " << other
            << ": " << messages[other] << std::endl;
  DS_CHECK(std::count(failed.begin(), failed.end(), 1) == 3, label + ": every rank fails");
  DS_CHECK(std::count(said.begin(), said.end(), 1) == 3, label + ": each rank says why");
}

void BadPiece(const ImageGeometry& g, const std::vector<float>& image, const TriangleMesh& start)
{
  EveryRankFails(
    g, image, start, [&](int r, int a) { return r == 1 ? 0 : InitialSigmaProbeGhostVoxels(g, a); },
    1, "too few ghost layers", "rank 1 without ghosts");
}

/// A probe that fails after its first maximum: a flat image within the reach (its largest g is
/// 0, so ComputeScaleSpaceForce makes no second reduction) and, beyond it in rank 0's ghost
/// layers, a step between -+3.3e38 on a grid of half the spacing, whose g overflows single
/// precision (the potential is not finite). Rank 0 fails; the slabs beyond the reach, which
/// compute no probe, make the same reductions.
void FailsAfterFirstMaximum()
{
  ImageGeometry g = dstest::AnisotropicGeometry(24, 24, 120);
  for (double& s : g.Spacing)
  {
    s *= 0.5;
  }
  const TriangleMesh start = Sphere(2.0, { 3.0, 8.0, 9.0 }); // its reach ends below z index 37
  const std::size_t slice = static_cast<std::size_t>(g.Dimensions[0]) * g.Dimensions[1];
  std::vector<float> image(slice * g.Dimensions[2], 0.0f);
  for (std::size_t v = 43 * slice; v < image.size(); ++v)
  {
    image[v] = v < 46 * slice ? 3.3e38f : -3.3e38f;
  }
  EveryRankFails(
    g, image, start, [&](int, int a) { return InitialSigmaProbeGhostVoxels(g, a); }, 0,
    "not finite", "a probe not finite beyond the reach, its maximum 0");
}
} // namespace

int TestDistributedStart(int, char*[])
{
  const ImageGeometry g = dstest::AnisotropicGeometry(40, 40, 120);
  const std::vector<float> image = Image(g);
  // 3 voxels outside the first ball; across both slab borders (z 49-83 of 120), between the balls.
  const TriangleMesh nearBall = Sphere(13.0, { 17.0, 24.0, 30.0 });
  const TriangleMesh across = Sphere(15.0, { 17.0, 24.0, 64.4 });
  SameAsSerial(g, image, nearBall, "a start near the first ball");
  SameAsSerial(g, image, across, "a start across the slabs' borders");
  std::vector<std::uint16_t> image16;
  for (float v : image)
  {
    image16.push_back(static_cast<std::uint16_t>(std::lround(100.0 * v)));
  }
  SameAsSerial(g, image16, nearBall, "uint16, a start near the first ball");
  // The image turned about x (a direction matrix): the reach is a box in index space.
  ImageGeometry turned = g;
  const double c = std::cos(0.5), s = std::sin(0.5);
  const double rotation[9] = { 1, 0, 0, 0, c, -s, 0, s, c };
  std::copy(rotation, rotation + 9, turned.Direction);
  const double ballIndex[3] = { 20.0, 22.0 / 1.1, 25.0 / 0.9 };
  double ball[3];
  turned.IndexToWorld(ballIndex, ball);
  SameAsSerial(turned, image, Sphere(13.0, { ball[0], ball[1], ball[2] }),
    "a turned image, a start near the first ball");
  SameAsSerial(g, image, Sphere(200.0, { 17.0, 24.0, 60.0 }), "a start spanning the image");
  // Its reach clamped to the image's first two slices (indices beyond int: no cast of them), the
  // other slabs beyond it; no ray meets the image.
  const InitialSigmaChoice far =
    SameAsSerial(g, image, Sphere(13.0, { 17.0, 24.0, -1.0e12 }), "a start far outside the image");
  DS_CHECK(far.Sigma == g.MeanExtent() / 6.0 && far.RaysWithEdge == 0 && far.Rays > 0,
    "a start far outside the image: extent / 6, no ray met an edge");
  SameRange(g, image, nearBall, "the range from a start around the first ball");
  SameRange(g, image, Sphere(4.0, { 17.0, 24.0, 30.0 }), "the range from a click in it");
  SameRange(g, image, Sphere(1.2, { 17.3, 24.2, 30.1 }), "the range from a start around a voxel");
  // A click's competitors (the classes within the reach, a mixture fitted to reduced
  // histograms): the same classes and range on every rank.
  SameRange(g, image, Sphere(4.0, { 17.0, 24.0, 30.0 }), "a click's competitors", 12.0);
  SameRange(g, image16, Sphere(4.0, { 17.0, 24.0, 30.0 }), "uint16, a click's competitors", 40.0);
  SameRange(g, image, across, "the range from a start across the slabs' borders");
  SameRange(g, image16, nearBall, "uint16, the range from a start around the first ball");
  BeyondReach(g, image, nearBall);
  CoarseProbe();
  SampledStatistics();
  BadPiece(g, image, nearBall);
  FailsAfterFirstMaximum();
  return dstest::Result("TestDistributedStart");
}

int main(int argc, char* argv[])
{
  return TestDistributedStart(argc, argv);
}
