// SPDX-License-Identifier: BSD-3-Clause
#include "dsClickCompetition.h"

#include "dsFieldGrid.h"
#include "dsMixture.h"
#include "dsRegionValues.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace dsurf
{
namespace
{

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

/// A class that PartialVolumeShare and its spread take for the partial volume between two others
/// is one only where its voxels lie between theirs in space: at least this share of them lie on
/// a ramp, a darker class one way along an axis and a brighter one the other way
/// (BetweenShares). A blend exists only where its two classes meet; a tissue lies beside one
/// neighbour at a time, or between two of the same side. Measured (docs/METHOD.md §9.3): the
/// phantoms' blends (the horned body's rim, the capsule's blurred face, the engine's and the
/// assembly's air gaps and glue line) 0.72-0.97; Colin27's dark class (CSF and bone, 22 +- 8.5)
/// around the README's click, between the image's empty margin and the brain, 0.16, and the white
/// matter beside a putamen click, between the putamen and a rare bright class, 0.01.
constexpr double BlendBetweenShare = 0.5;

/// The spatial test reads at most about this many voxels of a click's neighbourhood (every n-th):
/// a class of 1 % of them has some 2 600, which fix its share to about a per cent.
constexpr long long BetweenVoxels = 1LL << 18;

/// Whether class k, on side `direction` (-1 below, +1 above) of the object's class o, competes.
/// between[k]: the share of k's voxels that lie between a darker and a brighter class
/// (BetweenShares).
bool Competes(const Mixture& m, const std::vector<double>& between, int o, int k, double direction)
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
    if (direction * (m.Mean[j] - m.Mean[o]) > offset && m.Sd[k] >= std::min(m.Sd[o], m.Sd[j]) &&
      between[k] >= BlendBetweenShare)
    {
      return false; // a class beyond k: k is the partial volume between o and it
    }
  }
  return true;
}

/// The end of the object's class o on one side (direction -1: below its level, +1: above):
/// the first intensity from `start` on where a class that competes on that side (Competes)
/// explains the image better (Mixture::LogDensity), or NaN when none does before `stop`.
double CompetitorBoundary(const Mixture& m, const std::vector<double>& between, int o, double start,
  double stop, double step)
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
      if (Competes(m, between, o, k, direction) && m.LogDensity(k, x) > m.LogDensity(o, x))
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
  std::vector<double> Between; ///< BetweenShares of Fit's classes
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
std::array<double, 2> ClickRangeEnds(Mixture& m, const std::vector<double>& between, int o,
  ZoomedFit& zoom, double m0, double clickSpread, double width, double reachLow, double reachHigh)
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
  double lo = CompetitorBoundary(m, between, o, m0, reachLow, width / 8);
  double hi = CompetitorBoundary(m, between, o, m0, reachHigh, width / 8);
  // A class the histogram does not resolve: its neighbours within the zoomed window decide the
  // ends they reach.
  if (zoom.Object >= 0)
  {
    const double zoomHigh = zoom.Low + MixtureBins * zoom.Width;
    const double zlo =
      CompetitorBoundary(zoom.Fit, zoom.Between, zoom.Object, m0, zoom.Low, zoom.Width / 8);
    const double zhi =
      CompetitorBoundary(zoom.Fit, zoom.Between, zoom.Object, m0, zoomHigh, zoom.Width / 8);
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

/// The voxels of `around` (whole-image indices) that this process counts
/// (ImagePiece::CountedVoxels).
VoxelBox CountedPart(const ImagePiece& piece, const VoxelBox& around)
{
  const VoxelBox counted = piece.CountedVoxels();
  VoxelBox box;
  for (int a = 0; a < 3; ++a)
  {
    box.Begin[a] = std::max(around.Begin[a], counted.Begin[a]);
    box.End[a] = std::max(box.Begin[a], std::min(around.End[a], counted.End[a]));
  }
  return box;
}

/// The values of the voxels within `reach` of the start's bounding box that this process counts:
/// every n-th voxel id of the neighbourhood (n from its whole size, so every process takes the
/// same voxels), at most ~2^24 values; non-finite values (a float image's NaN background) belong
/// to no class.
std::vector<float> NeighbourhoodValues(
  const ImagePiece& piece, const TriangleMesh& mesh, double reach)
{
  const VoxelBox around = SurfaceNeighbourhood(mesh, piece.Whole, reach);
  const VoxelBox box = CountedPart(piece, around);
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
  return values;
}

/// Per class k of `fit` (fitted on MixtureBins bins of `width` from `low`): the share of the
/// neighbourhood's voxels likeliest in k (every n-th of the voxels within `reach` of the start's
/// bounding box, at most about BetweenVoxels, the same on every process) that lie on a ramp:
/// along some axis, the first voxel of another class within BlendReachVoxels is of a darker class
/// one way and of a brighter class the other way (a value beyond the fit's span counts as darker
/// or brighter than every class). Within a voxel the test missed blurred edges, whose blend spans
/// a few voxels (the capsule of TestFollowingField: 0.00 one voxel away, 0.97 within three).
/// Summed across processes: a counted voxel's ramp lies in its piece's ghost layers
/// (MultilevelSolver::DistributedGhostVoxels keeps BlendReachVoxels of them).
std::vector<double> BetweenShares(const ImagePiece& piece, const TriangleMesh& mesh, double reach,
  const Mixture& fit, double low, double width, const PieceReductions& reduce)
{
  const int n = fit.Size();
  // The likeliest class per eighth of a bin (a value beyond the span: the end's), looked up
  // rather than evaluated: a click in a head CT reads a million voxels and their ramps.
  const int entries = 8 * MixtureBins;
  std::vector<int> likeliest(entries);
  for (int e = 0; e < entries; ++e)
  {
    likeliest[e] = fit.Likeliest(low + (e + 0.5) * width / 8);
  }
  auto entryOf = [&](double v) { return std::floor((v - low) / (width / 8)); };
  auto classOf = [&](double v)
  { return likeliest[static_cast<int>(std::min(entries - 1.0, std::max(0.0, entryOf(v))))]; };
  // Which of two values' classes is darker: their means, beyond the span below or above all.
  const double inf = std::numeric_limits<double>::infinity();
  auto levelOf = [&](double v)
  {
    const double e = entryOf(v);
    return e < 0 ? -inf : (e >= entries ? inf : fit.Mean[likeliest[static_cast<int>(e)]]);
  };
  // Only a class with others darker and brighter than it can be a blend (Competes asks for a
  // class beyond it): the darkest's and the brightest's voxels, most of a neighbourhood, are
  // skipped.
  std::vector<char> maybeBlend(n, 0);
  for (int c = 0; c < n; ++c)
  {
    for (int d = 0; d < n; ++d)
    {
      maybeBlend[c] |= fit.Mean[d] < fit.Mean[c] ? 1 : (fit.Mean[d] > fit.Mean[c] ? 2 : 0);
    }
    maybeBlend[c] = maybeBlend[c] == 3;
  }
  const VoxelBox around = SurfaceNeighbourhood(mesh, piece.Whole, reach);
  const VoxelBox box = CountedPart(piece, around);
  const long long every = 1 + around.NumberOfVoxels() / BetweenVoxels;
  const long long nx = piece.Whole.Dimensions[0], ny = piece.Whole.Dimensions[1];
  const int *h = piece.Held.Begin, *held = piece.Held.End;
  std::vector<double> counts(2 * n, 0.0); // per class: its voxels, and those between
  VisitValues(piece.Image,
    [&](const auto* values)
    {
      auto at = [&](int i, int j, int k) {
        return static_cast<double>(values[piece.Image.RowOffset(j - h[1], k - h[2]) + (i - h[0])]);
      };
      for (int k = box.Begin[2]; k < box.End[2]; ++k)
      {
        for (int j = box.Begin[1]; j < box.End[1]; ++j)
        {
          const long long first = (static_cast<long long>(k) * ny + j) * nx + box.Begin[0];
          for (int i = box.Begin[0] + static_cast<int>((every - first % every) % every);
               i < box.End[0]; i += static_cast<int>(every))
          {
            const double v = at(i, j, k);
            if (!std::isfinite(v))
            {
              continue;
            }
            const int c = classOf(v);
            if (!maybeBlend[c])
            {
              continue;
            }
            const double own = levelOf(v);
            // Along some axis, the first voxel of another class one way is darker and the
            // first the other way brighter (within BlendReachVoxels): v lies on a ramp.
            bool between = false;
            for (int a = 0; a < 3 && !between; ++a)
            {
              int found[2] = { 0, 0 }; // -1 darker, +1 brighter, 0 none within reach
              for (int side = 0; side < 2; ++side)
              {
                for (int t = 1; t <= BlendReachVoxels && found[side] == 0; ++t)
                {
                  int q[3] = { i, j, k };
                  q[a] += side == 0 ? -t : t;
                  if (q[a] < h[a] || q[a] >= held[a])
                  {
                    break;
                  }
                  const double w = at(q[0], q[1], q[2]);
                  if (!std::isfinite(w))
                  {
                    break;
                  }
                  const double other = levelOf(w);
                  found[side] = other < own ? -1 : (other > own ? 1 : 0);
                }
              }
              between = found[0] * found[1] < 0;
            }
            counts[2 * c] += 1;
            counts[2 * c + 1] += between ? 1 : 0;
          }
        }
      }
    });
  reduce.Sum(counts);
  std::vector<double> shares(n, 0.0);
  for (int c = 0; c < n; ++c)
  {
    shares[c] = counts[2 * c] > 0 ? counts[2 * c + 1] / counts[2 * c] : 0.0;
  }
  return shares;
}

/// The click's range from its ends lo and hi (NaN: no competitor on that side) around its median
/// m0: a side without a competitor stays open, beyond the neighbourhood's extreme value (over all
/// processes) by a quarter of the span to the other end, so the speed's ramp lies outside the data.
std::array<double, 2> RangeWithOpenSides(
  const std::vector<float>& values, double lo, double hi, double m0, const PieceReductions& reduce)
{
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
  return { std::isnan(lo) ? minimum - 0.25 * (closedHigh - minimum) : lo,
    std::isnan(hi) ? maximum + 0.25 * (maximum - closedLow) : hi };
}
} // namespace

void CompetitorsAround(const ImagePiece& piece, const TriangleMesh& mesh, double reach,
  const PieceReductions& reduce, double clickSpread, RangeEstimate& estimate)
{
  const std::vector<float> values = NeighbourhoodValues(piece, mesh, reach);
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
  // Only a fit of three classes or more can hold a class between two others.
  const std::vector<double> between = m.Size() > 2
    ? BetweenShares(piece, mesh, reach, m, low, width, reduce)
    : std::vector<double>(m.Size(), 0.0);
  if (zoom.Object >= 0)
  {
    zoom.Between = zoom.Fit.Size() > 2
      ? BetweenShares(piece, mesh, reach, zoom.Fit, zoom.Low, zoom.Width, reduce)
      : std::vector<double>(zoom.Fit.Size(), 0.0);
  }
  const std::array<double, 2> ends =
    ClickRangeEnds(m, between, o, zoom, m0, clickSpread, width, reachLow, reachHigh);
  const double lo = ends[0], hi = ends[1];
  if ((std::isnan(lo) && std::isnan(hi)) || !(std::isnan(lo) || lo < m0) ||
    !(std::isnan(hi) || hi > m0))
  {
    return; // no competitor, or none that leaves the click in its range: m -+ 3 s, grow only
  }
  const std::array<double, 2> range = RangeWithOpenSides(values, lo, hi, m0, reduce);
  estimate.Range[0] = range[0];
  estimate.Range[1] = range[1];
  estimate.Contrast = true;
  const Mixture& fit = zoom.Object >= 0 ? zoom.Fit : m;
  const int object = zoom.Object >= 0 ? zoom.Object : o;
  estimate.ObjectMedian = fit.Mean[object];
  estimate.BackgroundMedian = fit.Mean[NearestClass(fit, object)];
}
} // namespace dsurf
