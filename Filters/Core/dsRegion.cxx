#include "dsRegion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dsurf
{
namespace
{
/// Value at fraction q in [0, 1] of `v` (reorders v).
double Quantile(std::vector<float>& v, double q)
{
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

/// The voxels whose centres lie inside the closed mesh. For every voxel row (j, k) the
/// crossings of the row's line with the triangles are sorted and the centres between the
/// 1st and 2nd, 3rd and 4th... crossing are inside (parity). Works in continuous index space,
/// so spacing and direction are honoured.
std::vector<float> ValuesInside(const float* scalars, const ImageGeometry& g, const TriangleMesh& mesh)
{
  const int nx = g.Dimensions[0], ny = g.Dimensions[1], nz = g.Dimensions[2];
  std::vector<Vec3> ijk(mesh.Points.size());
  for (std::size_t i = 0; i < ijk.size(); ++i)
  {
    g.WorldToIndex(mesh.Points[i].data(), ijk[i].data());
  }
  // Crossings per row, rows indexed j + ny * k.
  std::vector<std::vector<double>> crossings(static_cast<std::size_t>(ny) * nz);
  for (const auto& t : mesh.Triangles)
  {
    const Vec3 &a = ijk[t[0]], &b = ijk[t[1]], &c = ijk[t[2]];
    const int j0 = std::max(0, static_cast<int>(std::ceil(std::min({ a[1], b[1], c[1] }))));
    const int j1 = std::min(ny - 1, static_cast<int>(std::floor(std::max({ a[1], b[1], c[1] }))));
    const int k0 = std::max(0, static_cast<int>(std::ceil(std::min({ a[2], b[2], c[2] }))));
    const int k1 = std::min(nz - 1, static_cast<int>(std::floor(std::max({ a[2], b[2], c[2] }))));
    // Barycentric coordinates of (y, z) in the triangle's projection onto the y-z plane.
    const double det = (b[1] - a[1]) * (c[2] - a[2]) - (c[1] - a[1]) * (b[2] - a[2]);
    if (det == 0.0)
    {
      continue; // edge-on: the row lines graze it, the neighbours count the crossing
    }
    for (int k = k0; k <= k1; ++k)
    {
      for (int j = j0; j <= j1; ++j)
      {
        // The row's line is moved by a tiny irrational offset, so it never passes exactly
        // through a vertex or an edge (picked points often lie on whole voxel indices): every
        // crossing then belongs to exactly one triangle.
        const double y = j + 1.1e-7 * M_SQRT2, z = k + 1.3e-7 * M_PI;
        const double u = ((y - a[1]) * (c[2] - a[2]) - (c[1] - a[1]) * (z - a[2])) / det;
        const double v = ((b[1] - a[1]) * (z - a[2]) - (y - a[1]) * (b[2] - a[2])) / det;
        if (u >= 0 && v >= 0 && u + v <= 1)
        {
          crossings[j + static_cast<std::size_t>(ny) * k].push_back(a[0] + u * (b[0] - a[0]) + v * (c[0] - a[0]));
        }
      }
    }
  }
  std::vector<float> values;
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      std::vector<double>& xs = crossings[j + static_cast<std::size_t>(ny) * k];
      std::sort(xs.begin(), xs.end());
      for (std::size_t p = 0; p + 1 < xs.size(); p += 2)
      {
        const int i0 = std::max(0, static_cast<int>(std::ceil(xs[p])));
        const int i1 = std::min(nx - 1, static_cast<int>(std::floor(xs[p + 1])));
        const float* row = scalars + (static_cast<std::size_t>(k) * ny + j) * nx;
        values.insert(values.end(), row + std::max(i0, 0), row + std::max(i0, i1 + 1));
      }
    }
  }
  return values;
}

/// The image's 1st-99th percentile span, from every 7th voxel.
double RobustSpan(const float* scalars, const ImageGeometry& g)
{
  std::vector<float> sample;
  const long long n = g.NumberOfVoxels();
  sample.reserve(static_cast<std::size_t>(n / 7 + 1));
  for (long long i = 0; i < n; i += 7)
  {
    sample.push_back(scalars[i]);
  }
  const double lo = Quantile(sample, 0.01), hi = Quantile(sample, 0.99);
  return hi - lo;
}

/// The image 1, 2 and 3 voxels outside the surface along the face normals, at about one
/// sample point per voxel of area (at least the triangle's centre).
std::vector<float> ValuesOutside(
  const float* scalars, const ImageGeometry& g, const TriangleMesh& mesh, double outwardSign)
{
  const double voxel = (g.Spacing[0] + g.Spacing[1] + g.Spacing[2]) / 3.0;
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
    const int m = std::max(1, std::min(16, static_cast<int>(std::sqrt(area2) / voxel)));
    for (int i = 0; i < m; ++i)
    {
      for (int j = 0; i + j < m; ++j)
      {
        const double u = (i + 1.0 / 3.0) / m, v = (j + 1.0 / 3.0) / m;
        const Vec3 x = a + u * (b - a) + v * (c - a);
        for (int k = 1; k <= 3; ++k)
        {
          const Vec3 p = x + (k * voxel) * n;
          bool inside = false;
          const double value = SampleVolume(scalars, g, p.data(), &inside);
          if (inside)
          {
            values.push_back(static_cast<float>(value));
          }
        }
      }
    }
  }
  return values;
}
} // namespace

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

/// The object against its background, from the two histograms (256 bins): the intensities
/// more frequent inside than outside (d = p_in - p_out > 0) are the object's, those more
/// frequent outside are the background's. Their levels (smoothed modes) m_obj and m_bg give the
/// boundary, (m_obj + m_bg) / 2, which lies on the true edge for any symmetric blur; the
/// range runs from there to m_obj + 3 s_obj on the object's side (s_obj from the object's
/// interquartile range, floored like s). The total
/// variation sum(max(d, 0)) below 0.1 means both sides look alike (a click inside one region):
/// the estimate then keeps m -+ 3 s.
void ObjectAgainstBackground(const std::vector<float>& in, const std::vector<float>& out, double floor,
  RangeEstimate& estimate)
{
  constexpr int B = 256;
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (const auto* v : { &in, &out })
  {
    for (float x : *v)
    {
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  if (!(hi > lo))
  {
    return;
  }
  const double width = (static_cast<double>(hi) - lo) / B;
  std::vector<double> object(B, 0.0), background(B, 0.0);
  for (float x : in)
  {
    object[std::min(B - 1, static_cast<int>((x - lo) / width))] += 1.0 / in.size();
  }
  for (float x : out)
  {
    background[std::min(B - 1, static_cast<int>((x - lo) / width))] += 1.0 / out.size();
  }
  double tv = 0;
  for (int b = 0; b < B; ++b)
  {
    const double d = object[b] - background[b];
    object[b] = std::max(d, 0.0);
    background[b] = std::max(-d, 0.0);
    tv += object[b];
  }
  estimate.Separation = tv;
  if (tv < 0.1)
  {
    return;
  }
  const double mObject = SmoothedMode(object, lo, width);
  const double mBackground = SmoothedMode(background, lo, width);
  const double s = std::max(floor,
    (WeightedQuantile(object, 0.75, lo, width) - WeightedQuantile(object, 0.25, lo, width)) / 1.349);
  const double mid = 0.5 * (mObject + mBackground);
  estimate.Contrast = true;
  estimate.ObjectMedian = mObject;
  estimate.BackgroundMedian = mBackground;
  estimate.Range[0] = mObject > mBackground ? mid : mObject - 3.0 * s;
  estimate.Range[1] = mObject > mBackground ? mObject + 3.0 * s : mid;
}

bool EstimateIntensityRange(const float* scalars, const ImageGeometry& geometry, const TriangleMesh& mesh,
  double outwardSign, RangeEstimate& estimate, std::string* error)
{
  estimate = RangeEstimate();
  std::vector<float> values = ValuesInside(scalars, geometry, mesh);
  if (values.size() < 16)
  {
    estimate.FromVertices = true;
    values.clear();
    for (const Vec3& p : mesh.Points)
    {
      bool inside = false;
      const double v = SampleVolume(scalars, geometry, p.data(), &inside);
      if (inside)
      {
        values.push_back(static_cast<float>(v));
      }
    }
  }
  if (values.empty())
  {
    if (error)
    {
      *error = "the start surface encloses no voxel of the image and none of its vertices lies in it";
    }
    return false;
  }
  estimate.Samples = static_cast<long long>(values.size());
  const std::vector<float> insideValues = values;
  estimate.Median = Quantile(values, 0.5);
  for (float& v : values)
  {
    v = static_cast<float>(std::abs(v - estimate.Median));
  }
  const double mad = Quantile(values, 0.5);
  const double floor = 0.05 * RobustSpan(scalars, geometry);
  estimate.Spread = std::max(1.4826 * mad, floor);
  if (!(estimate.Spread > 0))
  {
    estimate.Spread = 1e-6 * std::max(1.0, std::abs(estimate.Median));
  }
  const double m = estimate.Median, s = estimate.Spread;
  estimate.Range[0] = m - 3.0 * s;
  estimate.Range[1] = m + 3.0 * s;

  std::vector<float> outside = ValuesOutside(scalars, geometry, mesh, outwardSign);
  estimate.OutsideSamples = static_cast<long long>(outside.size());
  if (outside.size() >= 16)
  {
    ObjectAgainstBackground(insideValues, outside, floor, estimate);
  }
  return true;
}

long long CountVoxelsInRange(const float* scalars, const ImageGeometry& geometry, double lo, double hi)
{
  long long count = 0;
  const long long n = geometry.NumberOfVoxels();
  for (long long i = 0; i < n; ++i)
  {
    count += (scalars[i] >= lo && scalars[i] <= hi) ? 1 : 0;
  }
  return count;
}
} // namespace dsurf
