// SPDX-License-Identifier: BSD-3-Clause
#include "dsRegion.h"

#include "dsFieldGrid.h"
#include "dsInsideVoxels.h"
#include "dsMixture.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace dsurf
{
namespace
{

/// Calls row(j, k, values) for every row (j, k) of `box` (whole-image indices, held by the
/// piece), values pointing at voxel (box.Begin[0], j, k) in the input's own type.
template <typename Row>
void ForEachCountedRow(const ImagePiece& piece, const VoxelBox& box, Row&& row)
{
  const int* h = piece.Held.Begin;
  VisitValues(piece.Image,
    [&](const auto* values)
    {
      for (int k = box.Begin[2]; k < box.End[2]; ++k)
      {
        for (int j = box.Begin[1]; j < box.End[1]; ++j)
        {
          row(j, k, values + piece.Image.RowOffset(j - h[1], k - h[2]) + (box.Begin[0] - h[0]));
        }
      }
    });
}

/// A float's key in the order of the values (-0 as +0): a value's bits, the sign flipped for
/// positive values and all bits for negative ones.
std::uint32_t OrderKey(float value)
{
  std::uint32_t u;
  const float v = value == 0.0f ? 0.0f : value;
  std::memcpy(&u, &v, sizeof u);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

float KeyValue(std::uint32_t key)
{
  const std::uint32_t u = (key & 0x80000000u) ? (key & 0x7fffffffu) : ~key;
  float v;
  std::memcpy(&v, &u, sizeof v);
  return v;
}

/// This process's share of values sampled by all processes, and the count of all of them.
struct SharedValues
{
  const std::vector<float>& Values;
  long long Count;
};

long long CountOfAll(const std::vector<float>& values, const PieceReductions& reduce)
{
  std::vector<double> n{ static_cast<double>(values.size()) };
  reduce.Sum(n);
  return static_cast<long long>(n[0]);
}

/// Values a chunk of the parallel loops below holds.
constexpr std::size_t ChunkValues = 1 << 20;

/// The counts of the values whose OrderKey has `prefix` in its `known` bits, by the `digits`
/// values of its bits from `shift` on, counted chunk by chunk in parallel (in the caller's SMP
/// scope) and added in the chunks' order.
std::vector<double> DigitHistogram(const std::vector<float>& values, int shift, int digits,
  std::uint32_t known, std::uint32_t prefix)
{
  const std::size_t chunks = (values.size() + ChunkValues - 1) / ChunkValues;
  std::vector<std::vector<double>> counts(chunks, std::vector<double>(digits, 0.0));
  vtkSMPTools::For(0, static_cast<vtkIdType>(chunks), 1,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType c = first; c < last; ++c)
      {
        const std::size_t end =
          std::min(values.size(), static_cast<std::size_t>(c + 1) * ChunkValues);
        for (std::size_t i = static_cast<std::size_t>(c) * ChunkValues; i < end; ++i)
        {
          const std::uint32_t key = OrderKey(values[i]);
          if ((key & known) == prefix)
          {
            counts[c][(key >> shift) & (digits - 1)] += 1.0;
          }
        }
      }
    });
  std::vector<double> histogram(digits, 0.0);
  for (const std::vector<double>& h : counts)
  {
    for (int d = 0; d < digits; ++d)
    {
      histogram[d] += h[d];
    }
  }
  return histogram;
}

/// The value at fraction q in [0, 1] of all processes' values (Count > 0): the k-th smallest,
/// k = q (n - 1) rounded, found digit by digit of OrderKey (11, 11 and 10 bits) from the
/// summed histograms of each share: every process gets the value a sort of all of them gives.
double Quantile(const SharedValues& all, double q, const PieceReductions& reduce)
{
  const long long n = all.Count;
  long long k = std::min(n - 1, static_cast<long long>(q * (n - 1) + 0.5));
  std::uint32_t prefix = 0, known = 0; // the key's bits found so far, and which
  for (const int shift : { 21, 10, 0 })
  {
    const int digits = shift == 0 ? 1 << 10 : 1 << 11;
    std::vector<double> histogram = DigitHistogram(all.Values, shift, digits, known, prefix);
    reduce.Sum(histogram);
    int d = 0;
    for (; d + 1 < digits && k >= static_cast<long long>(histogram[d]); ++d)
    {
      k -= static_cast<long long>(histogram[d]);
    }
    prefix |= static_cast<std::uint32_t>(d) << shift;
    known |= static_cast<std::uint32_t>(digits - 1) << shift;
  }
  return KeyValue(prefix);
}

/// Values a robust statistic of a large image or start reads at most (about): beyond them,
/// every n-th voxel (n odd, so that no power-of-two row length aliases with it). 2^22 floats are
/// 16 MiB, and their quantiles are those of all voxels to well within a voxel's noise (the
/// standard error of a 1 % quantile of 4 million values is about 0.2 % of the class's s.d.).
/// Reading every value of a start enclosing millions of voxels costs the solve a tenth of its
/// time and tells nothing more (BENCHMARKS.md, BenchScale's near start).
constexpr long long SampledValues = 1LL << 22;

/// The n of SampledValues for `voxels` voxels: 1 up to SampledValues, else odd, so that at most
/// SampledValues are read.
long long SampleEvery(double voxels)
{
  const long long v = static_cast<long long>(voxels);
  return v <= SampledValues ? 1 : ((v + SampledValues - 1) / SampledValues) | 1;
}

/// The values of the voxels whose centres lie inside the closed mesh (RowCrossings,
/// dsInsideVoxels.h), of those the piece counts (ImagePiece::CountedVoxels: each voxel by one
/// process); of a start enclosing more than SampledValues voxels, those whose voxel id is a
/// multiple of SampleEvery(its volume in voxels), the same on every process.
std::vector<float> ValuesInside(const ImagePiece& piece, const TriangleMesh& mesh)
{
  const ImageGeometry& g = piece.Whole;
  const long long every =
    SampleEvery(std::abs(mesh.SignedVolume()) / (g.Spacing[0] * g.Spacing[1] * g.Spacing[2]));
  const int nx = piece.Whole.Dimensions[0];
  const VoxelBox rows = piece.CountedVoxels();
  const std::size_t rowsY = static_cast<std::size_t>(rows.End[1] - rows.Begin[1]);
  const auto rowIndex = [&](int j, int k)
  { return (j - rows.Begin[1]) + rowsY * static_cast<std::size_t>(k - rows.Begin[2]); };
  std::vector<std::vector<double>> crossings = RowCrossings(piece.Whole, rows, mesh);
  std::vector<float> values;
  ForEachCountedRow(piece, rows,
    [&](int j, int k, const auto* row)
    {
      const std::vector<double>& xs = crossings[rowIndex(j, k)];
      const long long first = (static_cast<long long>(k) * g.Dimensions[1] + j) * nx; // (0, j, k)
      for (std::size_t p = 0; p + 1 < xs.size(); p += 2)
      {
        const int lo = std::max({ 0, ClampedIndex(std::ceil(xs[p]), nx), rows.Begin[0] });
        const int hi =
          std::min({ nx - 1, ClampedIndex(std::floor(xs[p + 1]), nx), rows.End[0] - 1 });
        // The ids that are multiples of `every`, stepped to rather than tested one by one.
        for (long long i = lo + (every - (first + lo) % every) % every; i <= hi; i += every)
        {
          values.push_back(AsFloat(row[i - rows.Begin[0]]));
        }
      }
    });
  return values;
}

/// The image's 1st-99th percentile span, from every 7th voxel (x fastest) of all pieces, or
/// every SampleEvery-th of a larger image.
double RobustSpan(const ImagePiece& piece, const PieceReductions& reduce)
{
  const VoxelBox counted = piece.CountedVoxels();
  const int nx = piece.Whole.Dimensions[0], ny = piece.Whole.Dimensions[1];
  const long long n = std::max(7LL, SampleEvery(static_cast<double>(piece.Whole.NumberOfVoxels())));
  // Every n-th voxel id: a row's are the multiples of n in its ids [a, b).
  const auto multiples = [n](long long a, long long b)
  { return (b + n - 1) / n - (a + n - 1) / n; };
  const auto rowId = [&](int j, int k) { return (static_cast<long long>(k) * ny + j) * nx; };
  // Slice by slice in parallel (in the caller's SMP scope), each written at its own offset.
  const int slices = std::max(0, counted.End[2] - counted.Begin[2]);
  std::vector<long long> offset(slices + 1, 0);
  for (int z = 0; z < slices; ++z)
  {
    long long count = 0;
    for (int j = counted.Begin[1]; j < counted.End[1]; ++j)
    {
      const long long id = rowId(j, counted.Begin[2] + z);
      count += multiples(id + counted.Begin[0], id + counted.End[0]);
    }
    offset[z + 1] = offset[z] + count;
  }
  std::vector<float> sample(static_cast<std::size_t>(offset[slices]));
  vtkSMPTools::For(0, slices,
    [&](int zBegin, int zEnd)
    {
      VoxelBox slab = counted;
      slab.Begin[2] = counted.Begin[2] + zBegin;
      slab.End[2] = counted.Begin[2] + zEnd;
      float* out = sample.data() + offset[zBegin];
      ForEachCountedRow(piece, slab,
        [&](int j, int k, const auto* row)
        {
          const long long first = rowId(j, k);
          for (long long i = (n - first % n) % n; i < counted.End[0]; i += n)
          {
            if (i >= counted.Begin[0])
            {
              *out++ = AsFloat(row[i - counted.Begin[0]]);
            }
          }
        });
    });
  const SharedValues all{ sample, CountOfAll(sample, reduce) };
  const double lo = Quantile(all, 0.01, reduce), hi = Quantile(all, 0.99, reduce);
  return hi - lo;
}

/// The image 1, 2 and 3 voxels outside the surface along the face normals, at about one
/// sample point per voxel of area (at least the triangle's centre): the points whose cell the
/// piece owns.
std::vector<float> ValuesOutside(
  const ImagePiece& piece, const TriangleMesh& mesh, double outwardSign)
{
  const ImageGeometry& g = piece.Whole;
  const double voxel = g.MeanSpacing();
  std::vector<float> values;
  for (const auto& t : mesh.Triangles)
  {
    const Vec3 &a = mesh.Points[t[0]], &b = mesh.Points[t[1]], &c = mesh.Points[t[2]];
    const Vec3 cross = Cross(b - a, c - a);
    const double area2 = Norm(cross);
    if (!(area2 > 0))
    {
      continue;
    }
    const Vec3 n = (outwardSign / area2) * cross;
    // m x m barycentric grid points per triangle, m ~ edge length / voxel (capped).
    const int m = static_cast<int>(std::max(1.0, std::min(16.0, std::sqrt(area2) / voxel)));
    for (int i = 0; i < m; ++i)
    {
      for (int j = 0; i + j < m; ++j)
      {
        const double u = (i + 1.0 / 3.0) / m, v = (j + 1.0 / 3.0) / m;
        const Vec3 x = a + u * (b - a) + v * (c - a);
        for (int k = 1; k <= 3; ++k)
        {
          const Vec3 p = x + (k * voxel) * n;
          bool owned = false;
          const double value = piece.SampleOwned(p.data(), &owned);
          if (owned)
          {
            values.push_back(static_cast<float>(value));
          }
        }
      }
    }
  }
  return values;
}

/// Quantile q of the bin centres weighted by w (bins of `width` from `lo`).
double WeightedQuantile(const std::vector<double>& w, double q, double lo, double width)
{
  double total = 0;
  for (double x : w)
  {
    total += x;
  }
  double acc = 0;
  for (std::size_t b = 0; b < w.size(); ++b)
  {
    acc += w[b];
    if (acc >= q * total)
    {
      return lo + (b + 0.5) * width;
    }
  }
  return lo + (w.size() - 0.5) * width;
}

/// The most frequent bin centre of w after a 5-bin moving average (the level a class sits
/// at; a median would be pulled by the partial-volume values between the classes).
double SmoothedMode(const std::vector<double>& w, double lo, double width)
{
  const int n = static_cast<int>(w.size());
  int best = 0;
  double bestValue = -1;
  for (int b = 0; b < n; ++b)
  {
    double sum = 0;
    for (int k = std::max(0, b - 2); k <= std::min(n - 1, b + 2); ++k)
    {
      sum += w[k];
    }
    if (sum > bestValue)
    {
      bestValue = sum;
      best = b;
    }
  }
  return lo + (best + 0.5) * width;
}

/// Otsu's threshold (IEEE Trans. SMC 9, 1979): the bin t that maximises the between-class
/// variance of the bins [0, t] and (t, end) of the histogram w.
int OtsuSplit(const std::vector<double>& w)
{
  double total = 0, moment = 0;
  for (std::size_t b = 0; b < w.size(); ++b)
  {
    total += w[b];
    moment += b * w[b];
  }
  double w0 = 0, m0 = 0, best = -1;
  int split = 0;
  for (std::size_t b = 0; b + 1 < w.size(); ++b)
  {
    w0 += w[b];
    m0 += b * w[b];
    const double w1 = total - w0;
    if (w0 > 0 && w1 > 0)
    {
      const double d = m0 / w0 - (moment - m0) / w1;
      if (w0 * w1 * d * d > best)
      {
        best = w0 * w1 * d * d;
        split = static_cast<int>(b);
      }
    }
  }
  return split;
}

/// The histograms (bins of equal width over the values' common span) of the inside and outside
/// shares, each normalised to 1. False when all the values are equal.
bool ShareHistograms(const SharedValues& in, const SharedValues& out, const PieceReductions& reduce,
  int bins, double& lo, double& width, std::vector<double>& pIn, std::vector<double>& pOut)
{
  float low = std::numeric_limits<float>::max(), high = std::numeric_limits<float>::lowest();
  for (const auto* v : { &in.Values, &out.Values })
  {
    for (float x : *v)
    {
      low = std::min(low, x);
      high = std::max(high, x);
    }
  }
  low = static_cast<float>(-reduce.Max(-static_cast<double>(low)));
  high = static_cast<float>(reduce.Max(high));
  if (!(high > low))
  {
    return false;
  }
  lo = low;
  width = (static_cast<double>(high) - low) / bins;
  // Each share's bin counts, summed over the processes, then divided by the share's size: the
  // histogram does not depend on how the values were split.
  std::vector<double> counts(2 * bins, 0.0);
  for (int side = 0; side < 2; ++side)
  {
    for (float x : side == 0 ? in.Values : out.Values)
    {
      counts[side * bins + std::min(bins - 1, static_cast<int>((x - low) / width))] += 1.0;
    }
  }
  reduce.Sum(counts);
  pIn.assign(bins, 0.0);
  pOut.assign(bins, 0.0);
  for (int b = 0; b < bins; ++b)
  {
    pIn[b] = counts[b] / static_cast<double>(in.Count);
    pOut[b] = counts[bins + b] / static_cast<double>(out.Count);
  }
  return true;
}

/// The object against its background, from the histograms (256 bins) of the image inside the
/// start and just outside it. Otsu's threshold of the two pooled (each weighted equally) splits
/// the intensities into two classes; the one more frequent inside than outside is the object's.
/// The object's level is the smoothed mode of the inside values on its side, the background's
/// that of the outside values on the other. Taken within the split classes, a long
/// partial-volume tail next to a spike (a blurred ball in an empty image: a thousand voxels
/// just above 0) stays on the background's side instead of passing for the object's level.
/// The boundary, the levels' midpoint, lies on the true edge for any symmetric blur; the range
/// runs from there to the object's level + 3 s_obj (s_obj from the object's interquartile
/// range, floored like s), or to the object's 99.5 % quantile when that is nearer. A class
/// share that differs by less than 0.1 between inside and outside, or levels within 2 s_obj of
/// each other, mean both sides look alike (a click inside one region): the estimate then
/// keeps m -+ 3 s.
void ObjectAgainstBackground(const SharedValues& in, const SharedValues& out, double floor,
  const PieceReductions& reduce, RangeEstimate& estimate)
{
  constexpr int B = 256;
  double lo = 0, width = 0;
  std::vector<double> pIn, pOut;
  if (!ShareHistograms(in, out, reduce, B, lo, width, pIn, pOut))
  {
    return;
  }
  std::vector<double> pooled(B);
  for (int b = 0; b < B; ++b)
  {
    pooled[b] = pIn[b] + pOut[b];
  }
  const int t = OtsuSplit(pooled);
  double inHigh = 0, outHigh = 0;
  for (int b = t + 1; b < B; ++b)
  {
    inHigh += pIn[b];
    outHigh += pOut[b];
  }
  estimate.Separation = std::abs(inHigh - outHigh);
  if (estimate.Separation < 0.1)
  {
    return;
  }
  const bool bright = inHigh > outHigh;
  std::vector<double> object(B, 0.0), background(B, 0.0);
  for (int b = 0; b < B; ++b)
  {
    ((b > t) == bright ? object[b] : background[b]) = ((b > t) == bright ? pIn[b] : pOut[b]);
  }
  const double mObject = SmoothedMode(object, lo, width);
  const double mBackground = SmoothedMode(background, lo, width);
  const double s = std::max(floor,
    (WeightedQuantile(object, 0.75, lo, width) - WeightedQuantile(object, 0.25, lo, width)) /
      1.349);
  if (std::abs(mObject - mBackground) < 2.0 * s)
  {
    return;
  }
  const double mid = 0.5 * (mObject + mBackground);
  estimate.Contrast = true;
  estimate.ObjectMedian = mObject;
  estimate.BackgroundMedian = mBackground;
  // The far end: 3 s beyond the object's level, but not past the last 0.5 % of the object's
  // own intensities (the bin's far edge). A wide object class (a brain's grey and white
  // matter, s ~ 20) would otherwise reach the brighter tissue next to it (orbital fat at
  // 130-200 in Colin27, the brain's own values ending at ~120): docs/METHOD.md §9.3.
  const double top =
    std::min(mObject + 3.0 * s, WeightedQuantile(object, 0.995, lo, width) + 0.5 * width);
  const double bottom =
    std::max(mObject - 3.0 * s, WeightedQuantile(object, 0.005, lo, width) - 0.5 * width);
  estimate.Range[0] = bright ? mid : bottom;
  estimate.Range[1] = bright ? top : mid;
}

/// A class less frequent around a click than this share of the click's own class, lying between
/// it and a further class on the same side, and at least as spread as the narrower of the two,
/// is the partial volume between them (a dark body's rim in a bright surround), not a
/// competitor: as one it cut the range short of horns whose voxels are three quarters body (the
/// committed horned phantom's range ended at 26 for a body of 20 in a surround of 70). The class
/// beyond competes instead. The spread tells a blend from a tissue: a blend of two classes has
/// their noise and the spread of its mixing fractions on top (the horned phantom's rim: s.d. 11.8
/// between classes of 2.2 and 3.9), while a tissue of its own can be narrower than both (Colin27's
/// white matter beside a caudate click: s.d. 3.9 between grey matter of 14 and a bright class of
/// 7.3; taken for a blend, the range ran over it to 139 and the caudate leaked over the brain).
constexpr double PartialVolumeShare = 1.0;

/// A class whose mean lies within this many of the narrower s.d. of its own and the object's class
/// o makes one mode with o: two Gaussians of one s.d. have a single mode for every weight exactly
/// when their means lie within two s.d. (Robertson and Fryer, Scand. Actuarial J. 1969), so no
/// image shows them as two tissues. The histogram fit splits a large class in two such halves (a
/// slab of 120, noise s.d. 4: 118.3 and 121.9, s.d. 3.6 and 3.4); a click whose median fell to the
/// lower half took the upper for a competitor, its range ended at its own median, and the surface
/// shrank.
constexpr double OneModeSds = 2.0;

/// Whether class k, on side `direction` (-1 below, +1 above) of the object's class o, competes.
bool Competes(const Mixture& m, int o, int k, double direction)
{
  const double offset = direction * (m.Mean[k] - m.Mean[o]);
  if (k == o || !(offset > OneModeSds * std::min(m.Sd[o], m.Sd[k])))
  {
    return false;
  }
  if (m.Weight[k] >= PartialVolumeShare * m.Weight[o])
  {
    return true;
  }
  for (int j = 0; j < m.Size(); ++j)
  {
    if (direction * (m.Mean[j] - m.Mean[o]) > offset && m.Sd[k] >= std::min(m.Sd[o], m.Sd[j]))
    {
      return false; // a class beyond k: k is the partial volume between o and it
    }
  }
  return true;
}

/// The end of the object's class o on one side (direction -1: below its level, +1: above):
/// the first intensity from `start` on where a class that competes on that side (Competes)
/// explains the image better (Mixture::LogDensity), or NaN when none does before `stop`.
double CompetitorBoundary(const Mixture& m, int o, double start, double stop, double step)
{
  if (!(step > 0) || !std::isfinite(start) || !std::isfinite(stop))
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const double direction = stop < start ? -1.0 : 1.0;
  const long long steps = static_cast<long long>(std::ceil(std::abs(stop - start) / step));
  for (long long i = 0; i <= steps; ++i)
  {
    const double x = start + direction * static_cast<double>(i) * step;
    for (int k = 0; k < m.Size(); ++k)
    {
      if (Competes(m, o, k, direction) && m.LogDensity(k, x) > m.LogDensity(o, x))
      {
        return x;
      }
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// The share of a click's neighbourhood below and above the span of its mixture's histogram
/// (piled into the end bins). A rare class must lie mostly within the span: the horned phantom's
/// dark body is 1.2 % of its click's neighbourhood, and with half of it piled into the first bin
/// (at 0.5 %) the rest fits a class of s.d. 2.2 where its noise is 4, whose range ends (37.8, not
/// ~44) before the voxels of a two-voxel horn, partly surround (docs/METHOD.md §9.3).
constexpr double MixtureTailShare = 0.002;

/// Bins of the histogram a click's mixture is fitted to (CompetitorsAround).
constexpr int MixtureBins = 256;

/// A click's class narrower than this many bins of its histogram is not resolved from the
/// classes next to it: a CT's neighbourhood spans air (-1000 HU) to bone (2000 HU), 8-12 HU a bin,
/// and the soft tissues (fat -100, vitreous 10-20, muscle 50) fall into a few bins each, where
/// the fit merges them into one class or into spreads of hundreds of HU. The histogram is then
/// fitted again over the click's median +- ZoomSds of that class (ZoomedMixture).
constexpr double ZoomBins = 3.0;
constexpr double ZoomSds = 10.0;

/// The histogram (MixtureBins bins from `low`, of `width`) of the values in [low, low + width *
/// MixtureBins), summed across processes.
std::vector<double> MixtureHistogram(
  const std::vector<float>& values, double low, double width, const PieceReductions& reduce)
{
  std::vector<double> counts(MixtureBins, 0.0);
  for (float v : values)
  {
    counts[static_cast<int>(std::min(MixtureBins - 1.0, std::max(0.0, (v - low) / width)))] += 1.0;
  }
  reduce.Sum(counts);
  return counts;
}

/// A click's mixture fitted again near its class (ZoomedMixture): the fit, the click's class in
/// it (-1: no refit) and the window [Low, Low + MixtureBins * Width) it spans.
struct ZoomedFit
{
  Mixture Fit;
  int Object = -1;
  double Low = 0, Width = 0;
};

/// The mixture of the values within the click's median m0 +- ZoomSds s.d. of its class o in
/// `coarse` (clipped to [low, high]; the values beyond are left out, not piled into the end
/// bins: a pile of air or bone would pass for a class). No refit (Object -1) when the class is
/// resolved (at least ZoomBins bins wide), the window is not narrower than half the span or,
/// clipped to the span, does not hold the median (a rare class beyond a quantile: the search for
/// its ends would run the wrong way), or the click's class is no better resolved in the window:
/// a class narrow in itself (a CT's air, -1024 HU and a few integers above) splits there into a
/// spike per value, and the value next to the click's would compete. Every process fits the
/// same one: the window comes from the shared fit and median.
ZoomedFit ZoomedMixture(const std::vector<float>& values, const Mixture& coarse, int o, double m0,
  double low, double high, const PieceReductions& reduce)
{
  const double width = (high - low) / MixtureBins;
  ZoomedFit zoom;
  zoom.Low = std::max(low, m0 - ZoomSds * coarse.Sd[o]);
  const double zoomHigh = std::min(high, m0 + ZoomSds * coarse.Sd[o]);
  zoom.Width = (zoomHigh - zoom.Low) / MixtureBins;
  if (!(coarse.Sd[o] < ZoomBins * width) || !(zoomHigh - zoom.Low < 0.5 * (high - low)) ||
    !(zoom.Low < m0 && m0 < zoomHigh))
  {
    return zoom;
  }
  std::vector<float> within;
  for (float v : values)
  {
    if (v >= zoom.Low && v < zoomHigh)
    {
      within.push_back(v);
    }
  }
  zoom.Fit = FitHistogramMixture(
    MixtureHistogram(within, zoom.Low, zoom.Width, reduce), zoom.Low, zoom.Width, 4);
  const int object = zoom.Fit.Size() > 1 ? zoom.Fit.Likeliest(m0) : -1;
  zoom.Object = object >= 0 && zoom.Fit.Sd[object] >= ZoomBins * zoom.Width ? object : -1;
  return zoom;
}

/// Whether the click's class o in `fit` (bins of `binWidth`) merges the click's tissue with
/// others: the click's own voxels (median m0, robust s.d. `clickSpread`) are narrower than the
/// class, which the histogram resolves (at least ZoomBins bins), and their median lies more than
/// OneModeSds of their s.d. from the class's mean, beyond the bound within which the two would
/// be one mode (see OneModeSds), as two tissues' classes are. A small tissue among larger ones
/// is not a class of its own in a fit of at most four: a CT's ventricle (CSF, 0 +- 7 HU, about
/// 1 % of a whole head's neighbourhood) merged with the brain's partial volumes into a class of
/// 21 +- 18, and the range took in the brain (docs/METHOD.md §9.3). A click near its class's centre
/// (Colin27's caudate: 1.4 from its class's mean, s.d. 1.5 against 14) keeps the class: a tissue's
/// spread over the image is wider than one spot's.
bool MergesClickTissue(const Mixture& fit, int o, double m0, double clickSpread, double binWidth)
{
  return clickSpread > 0.0 && clickSpread < fit.Sd[o] && fit.Sd[o] >= ZoomBins * binWidth &&
    std::abs(m0 - fit.Mean[o]) > OneModeSds * clickSpread;
}

/// The ends of a click's range on either side of its median m0 (NaN: no competitor on that side):
/// its decision boundaries with the competing classes of the whole span's fit `m` (the click's
/// class o; searched out to reachLow and reachHigh, in steps of an eighth of a bin of `width`), or
/// of the zoomed fit within its window where that finds one. The click's class in the fit that
/// decides (the zoomed one where there is one) gives way to the click's own model where it merges
/// the click's tissue with others (MergesClickTissue); a side on which the zoomed window finds no
/// competitor keeps the whole span's end, that of its own class.
std::array<double, 2> ClickRangeEnds(Mixture& m, int o, ZoomedFit& zoom, double m0,
  double clickSpread, double width, double reachLow, double reachHigh)
{
  Mixture& fit = zoom.Object >= 0 ? zoom.Fit : m;
  const int object = zoom.Object >= 0 ? zoom.Object : o;
  const double binWidth = zoom.Object >= 0 ? zoom.Width : width;
  if (MergesClickTissue(fit, object, m0, clickSpread, binWidth))
  {
    fit.Mean[object] = m0;
    fit.Sd[object] = std::max(clickSpread, binWidth); // no class narrower than a bin (dsMixture.h)
  }
  // From the click's median, where its class is the likeliest (not always at the class's mean:
  // a narrow neighbour can win there).
  double lo = CompetitorBoundary(m, o, m0, reachLow, width / 8);
  double hi = CompetitorBoundary(m, o, m0, reachHigh, width / 8);
  // A class the histogram does not resolve: its neighbours within the zoomed window decide the
  // ends they reach.
  if (zoom.Object >= 0)
  {
    const double zoomHigh = zoom.Low + MixtureBins * zoom.Width;
    const double zlo = CompetitorBoundary(zoom.Fit, zoom.Object, m0, zoom.Low, zoom.Width / 8);
    const double zhi = CompetitorBoundary(zoom.Fit, zoom.Object, m0, zoomHigh, zoom.Width / 8);
    lo = std::isnan(zlo) ? lo : zlo;
    hi = std::isnan(zhi) ? hi : zhi;
  }
  return { lo, hi };
}

/// The class of `fit` whose mean lies nearest the object's class's (fit has two classes or more).
int NearestClass(const Mixture& fit, int object)
{
  int nearest = object == 0 ? 1 : 0;
  for (int k = 0; k < fit.Size(); ++k)
  {
    if (k != object &&
      std::abs(fit.Mean[k] - fit.Mean[object]) < std::abs(fit.Mean[nearest] - fit.Mean[object]))
    {
      nearest = k;
    }
  }
  return nearest;
}

/// A start inside one region (a click): its competitors are the other classes of intensity
/// around it. The voxels within `reach` of the start's bounding box are fitted as a Gaussian
/// mixture (dsMixture.h, 256 bins between their MixtureTailShare quantiles); the object's class
/// is the one likeliest at the inside median, and the range runs from there, on each side, to where
/// a class lying on that side explains the image better: the decision boundary of region
/// competition (Zhu and Yuille, IEEE PAMI 18(9), 1996) between the object's model and its
/// neighbour's. A side without a competitor stays open (to beyond the neighbourhood's extreme
/// value, so the speed's ramp lies outside the data). Nothing changes when the neighbourhood holds
/// one class. Where the click's class merges its tissue with others (MergesClickTissue), the
/// click's own model, N(m0, clickSpread) with the class's weight, competes in its place
/// (ClickRangeEnds).
void CompetitorsAround(const ImagePiece& piece, const TriangleMesh& mesh, double reach,
  const PieceReductions& reduce, double clickSpread, RangeEstimate& estimate)
{
  const VoxelBox around = SurfaceNeighbourhood(mesh, piece.Whole, reach);
  const VoxelBox counted = piece.CountedVoxels();
  VoxelBox box;
  for (int a = 0; a < 3; ++a)
  {
    box.Begin[a] = std::max(around.Begin[a], counted.Begin[a]);
    box.End[a] = std::max(box.Begin[a], std::min(around.End[a], counted.End[a]));
  }
  // Every n-th voxel id of the neighbourhood (n from its whole size, so every process takes
  // the same voxels), at most ~2^24 values; non-finite values (a float image's NaN background)
  // belong to no class.
  const long long every = 1 + around.NumberOfVoxels() / (1LL << 24);
  const long long nx = piece.Whole.Dimensions[0], ny = piece.Whole.Dimensions[1];
  std::vector<float> values;
  values.reserve(static_cast<std::size_t>(box.NumberOfVoxels() / every + 1));
  ForEachCountedRow(piece, box,
    [&](int j, int k, const auto* row)
    {
      const long long first = (static_cast<long long>(k) * ny + j) * nx + box.Begin[0];
      for (int i = 0; i < box.End[0] - box.Begin[0]; ++i)
      {
        const float v = AsFloat(row[i]);
        if ((first + i) % every == 0 && std::isfinite(v))
        {
          values.push_back(v);
        }
      }
    });
  const SharedValues all{ values, CountOfAll(values, reduce) };
  if (all.Count < 64)
  {
    return;
  }
  const double low = Quantile(all, MixtureTailShare, reduce),
               high = Quantile(all, 1.0 - MixtureTailShare, reduce);
  if (!(high > low))
  {
    estimate.Classes = 1; // one value around the click
    return;
  }
  const double width = (high - low) / MixtureBins;
  const std::vector<double> counts = MixtureHistogram(values, low, width, reduce);
  // One class when BIC says so with the tails beyond the quantiles in the end bins modelled
  // (IsOneClass): the mixture below takes them for spikes and split a noisy ball's one class
  // into four, two of them halves of the click's own class (one a "competitor" at its median).
  Mixture m = FitHistogramMixture(counts, low, width, 4);
  estimate.Classes = IsOneClass(counts, low, width, 4) ? 1 : m.Size();
  if (estimate.Classes < 2)
  {
    return;
  }
  const int o = m.Likeliest(estimate.Median);
  double reachLow = low, reachHigh = high;
  for (int k = 0; k < m.Size(); ++k)
  {
    reachLow = std::min(reachLow, m.Mean[k] - 5.0 * m.Sd[k]);
    reachHigh = std::max(reachHigh, m.Mean[k] + 5.0 * m.Sd[k]);
  }
  const double m0 = estimate.Median;
  ZoomedFit zoom = ZoomedMixture(values, m, o, m0, low, high, reduce);
  const std::array<double, 2> ends =
    ClickRangeEnds(m, o, zoom, m0, clickSpread, width, reachLow, reachHigh);
  const double lo = ends[0], hi = ends[1];
  if ((std::isnan(lo) && std::isnan(hi)) || !(std::isnan(lo) || lo < m0) ||
    !(std::isnan(hi) || hi > m0))
  {
    return; // no competitor, or none that leaves the click in its range: m -+ 3 s, grow only
  }
  float lowest = std::numeric_limits<float>::max(), highest = std::numeric_limits<float>::lowest();
  for (float v : values)
  {
    lowest = std::min(lowest, v);
    highest = std::max(highest, v);
  }
  const double minimum = -reduce.Max(-static_cast<double>(lowest));
  const double maximum = reduce.Max(highest);
  const double closedLow = std::isnan(lo) ? m0 : lo;
  const double closedHigh = std::isnan(hi) ? m0 : hi;
  estimate.Range[0] = std::isnan(lo) ? minimum - 0.25 * (closedHigh - minimum) : lo;
  estimate.Range[1] = std::isnan(hi) ? maximum + 0.25 * (maximum - closedLow) : hi;
  estimate.Contrast = true;
  const Mixture& fit = zoom.Object >= 0 ? zoom.Fit : m;
  const int object = zoom.Object >= 0 ? zoom.Object : o;
  estimate.ObjectMedian = fit.Mean[object];
  estimate.BackgroundMedian = fit.Mean[NearestClass(fit, object)];
}
} // namespace

bool EstimateIntensityRange(const ImageView& image, const TriangleMesh& mesh, double outwardSign,
  RangeEstimate& estimate, std::string* error, double competitorReach)
{
  return EstimatePieceIntensityRange(WholeImagePiece(image), mesh, outwardSign,
    SingleProcessReductions(), estimate, error, competitorReach);
}

bool EstimatePieceIntensityRange(const ImagePiece& piece, const TriangleMesh& mesh,
  double outwardSign, const PieceReductions& reduce, RangeEstimate& estimate, std::string* error,
  double competitorReach)
{
  estimate = RangeEstimate();
  std::vector<float> values = ValuesInside(piece, mesh);
  long long count = CountOfAll(values, reduce);
  if (count < 16)
  {
    estimate.FromVertices = true;
    values.clear();
    for (const Vec3& p : mesh.Points)
    {
      bool owned = false;
      const double v = piece.SampleOwned(p.data(), &owned);
      if (owned)
      {
        values.push_back(static_cast<float>(v));
      }
    }
    count = CountOfAll(values, reduce);
  }
  if (count == 0)
  {
    if (error)
    {
      *error =
        "the start surface encloses no voxel of the image and none of its vertices lies in it";
    }
    return false;
  }
  estimate.Samples = count;
  const std::vector<float> insideValues = values;
  estimate.Median = Quantile({ values, count }, 0.5, reduce);
  for (float& v : values)
  {
    v = static_cast<float>(std::abs(v - estimate.Median));
  }
  const double mad = Quantile({ values, count }, 0.5, reduce);
  const double floor = 0.05 * RobustSpan(piece, reduce);
  estimate.Spread = std::max(1.4826 * mad, floor);
  if (!(estimate.Spread > 0))
  {
    estimate.Spread = 1e-6 * std::max(1.0, std::abs(estimate.Median));
  }
  const double m = estimate.Median, s = estimate.Spread;
  estimate.Range[0] = m - 3.0 * s;
  estimate.Range[1] = m + 3.0 * s;

  if (competitorReach > 0 && count < ClickVoxels)
  {
    // A click: a few voxels inside and a shell of three voxels around them cannot tell the
    // object from its background (the shell of a click near a bone's cortex is brighter than
    // the click, which then passed for a dark object); the classes around it can.
    CompetitorsAround(piece, mesh, competitorReach, reduce, 1.4826 * mad, estimate);
    return true;
  }
  const std::vector<float> outside = ValuesOutside(piece, mesh, outwardSign);
  estimate.OutsideSamples = CountOfAll(outside, reduce);
  if (estimate.OutsideSamples >= 16)
  {
    ObjectAgainstBackground(
      { insideValues, count }, { outside, estimate.OutsideSamples }, floor, reduce, estimate);
  }
  return true;
}

bool AnyVoxelInRange(const ImageView& image, double lo, double hi)
{
  bool found = false;
  const int nx = image.Geometry.Dimensions[0];
  ForEachRow(image,
    [&](int, int, const auto* row)
    {
      for (int i = 0; i < nx && !found; ++i)
      {
        const float v = AsFloat(row[i]);
        found = v >= lo && v <= hi;
      }
    });
  return found;
}

long long CountVoxelsInRange(const ImageView& image, double lo, double hi)
{
  long long count = 0;
  const int nx = image.Geometry.Dimensions[0];
  ForEachRow(image,
    [&](int, int, const auto* row)
    {
      for (int i = 0; i < nx; ++i)
      {
        const float v = AsFloat(row[i]);
        count += (v >= lo && v <= hi) ? 1 : 0;
      }
    });
  return count;
}
} // namespace dsurf
