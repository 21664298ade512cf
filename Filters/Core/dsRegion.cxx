// SPDX-License-Identifier: BSD-3-Clause
#include "dsRegion.h"

#include "dsClickCompetition.h"
#include "dsFieldGrid.h"
#include "dsInsideVoxels.h"
#include "dsRegionValues.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dsurf
{
namespace
{

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

/// Whether every value inside the start, on every process, is a whole number.
bool IntegerValued(const SharedValues& in, const PieceReductions& reduce)
{
  const bool whole =
    std::all_of(in.Values.begin(), in.Values.end(), [](float x) { return x == std::nearbyint(x); });
  return reduce.Max(whole ? 0.0 : 1.0) == 0.0;
}

/// Adds `n` units spread evenly over [x - 0.5, x + 0.5), the values a whole grey level stands
/// for, to the bins (of `width` from `lo`) it overlaps, the parts beyond the ends to the end bins.
/// Each part is n times a multiple of 2^-20, so that sums of them are exact in any order: the
/// counts of a distributed image, summed over the processes, are the serial counts.
void AddSpread(double* counts, int bins, double x, double n, double lo, double width)
{
  constexpr double Grain = 1048576.0; // 2^20
  const double a = (x - 0.5 - lo) / width, b = (x + 0.5 - lo) / width;
  const int first = static_cast<int>(std::floor(a)), last = static_cast<int>(std::floor(b));
  for (int k = first; k <= last; ++k)
  {
    const double overlap = std::min<double>(b, k + 1) - std::max<double>(a, k);
    if (overlap > 0)
    {
      counts[std::clamp(k, 0, bins - 1)] += n * (std::round(Grain * overlap / (b - a)) / Grain);
    }
  }
}

/// AddSpread of every whole value of `values` (all within [lo, lo + bins * width]). Where a unit
/// spans many bins (a 0/1 mask: 256 bins a value) the span holds few whole values, so each is
/// spread once with its tally; elsewhere a unit spans a few bins and each value is spread alone.
void AddSpreadValues(
  double* counts, int bins, const std::vector<float>& values, double lo, double width)
{
  if (!(width < 0.25))
  {
    for (float x : values)
    {
      AddSpread(counts, bins, x, 1.0, lo, width);
    }
    return;
  }
  // At most bins * width + 2 < 66 whole values.
  const double first = std::ceil(lo);
  std::vector<double> tally(static_cast<std::size_t>(bins * width) + 2, 0.0);
  for (float x : values)
  {
    tally[std::min(tally.size() - 1, static_cast<std::size_t>(std::max(0.0, x - first)))] += 1.0;
  }
  for (std::size_t v = 0; v < tally.size(); ++v)
  {
    if (tally[v] > 0)
    {
      AddSpread(counts, bins, first + static_cast<double>(v), tally[v], lo, width);
    }
  }
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
  // Voxel values of whole numbers, each counted over the unit it stands for: bins narrower than
  // a unit held one value or two, and the mode of that comb moved with a start moved by
  // micrometres (docs/METHOD.md §9.1). The outside values are interpolated, continuous already.
  const bool spread = IntegerValued(in, reduce);
  for (int side = 0; side < 2; ++side)
  {
    if (side == 0 && spread)
    {
      AddSpreadValues(counts.data(), bins, in.Values, lo, width);
      continue;
    }
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

bool PieceStartIsClick(
  const ImagePiece& piece, const TriangleMesh& mesh, const PieceReductions& reduce)
{
  if (!mesh.IsClosed())
  {
    return false;
  }
  // A start of many times a click's volume is taken for none (only a slab thinner than a voxel
  // could hold fewer centres): no need to find its voxels (the mesh is every process's, so all
  // skip the count alike).
  const double* s = piece.Whole.Spacing;
  if (std::abs(mesh.SignedVolume()) > 8.0 * ClickVoxels * s[0] * s[1] * s[2])
  {
    return false;
  }
  return CountOfAll(ValuesInside(piece, mesh), reduce) < ClickVoxels;
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
