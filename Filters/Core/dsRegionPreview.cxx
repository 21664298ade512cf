// SPDX-License-Identifier: BSD-3-Clause
#include "dsRegionPreview.h"

#include "dsInsideVoxels.h"
#include "dsObjects.h"

#include <cmath>

namespace dsurf
{
namespace
{
/// The value of voxel v (x fastest over the image's own dimensions).
double ValueAt(const ImageView& image, long long v)
{
  const int nx = image.Geometry.Dimensions[0], ny = image.Geometry.Dimensions[1];
  const int i = static_cast<int>(v % nx), j = static_cast<int>((v / nx) % ny),
            k = static_cast<int>(v / (static_cast<long long>(nx) * ny));
  double value = 0;
  VisitValues(image, [&](const auto* values) { value = values[image.RowOffset(j, k) + i]; });
  return value;
}

/// The seeds of one object: the voxels inside its start in its range, else the voxels nearest
/// its points in its range.
std::vector<long long> Seeds(
  const ImageView& image, const TriangleMesh& surface, double lo, double hi)
{
  const ImageGeometry& g = image.Geometry;
  const int nx = g.Dimensions[0], ny = g.Dimensions[1];
  const auto in = [&](long long v)
  {
    const double x = ValueAt(image, v);
    return x >= lo && x <= hi;
  };
  std::vector<long long> seeds;
  const VoxelBox whole = VoxelBox::Whole(g);
  const std::vector<std::vector<double>> crossings = RowCrossings(g, whole, surface);
  for (int k = 0; k < g.Dimensions[2]; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      const std::vector<double>& xs = crossings[j + static_cast<std::size_t>(ny) * k];
      for (std::size_t p = 0; p + 1 < xs.size(); p += 2)
      {
        const int i0 = std::max(0, ClampedIndex(std::ceil(xs[p]), nx));
        const int i1 = std::min(nx - 1, ClampedIndex(std::floor(xs[p + 1]), nx));
        for (int i = i0; i <= i1; ++i)
        {
          const long long v = i + static_cast<long long>(nx) * (j + static_cast<long long>(ny) * k);
          if (in(v))
          {
            seeds.push_back(v);
          }
        }
      }
    }
  }
  for (std::size_t p = 0; seeds.empty() && p < surface.Points.size(); ++p)
  {
    double ijk[3];
    g.WorldToIndex(surface.Points[p].data(), ijk);
    long long v = 0, stride = 1;
    bool inside = true;
    for (int a = 0; a < 3; ++a)
    {
      const double r = std::round(ijk[a]);
      inside = inside && r >= 0 && r < g.Dimensions[a];
      v += inside ? static_cast<long long>(r) * stride : 0;
      stride *= g.Dimensions[a];
    }
    if (inside && in(v))
    {
      seeds.push_back(v);
    }
  }
  return seeds;
}
} // namespace

std::vector<unsigned short> RegionPreview(const ImageView& image, const TriangleMesh& start,
  const std::vector<ObjectRegion>& regions, std::vector<long long>& counts)
{
  const ImageGeometry& g = image.Geometry;
  const long long n = g.NumberOfVoxels();
  std::vector<unsigned short> label(static_cast<std::size_t>(n), 0);
  counts.assign(regions.size(), 0);
  // Breadth first from every object's seeds at once: ring by ring, so each voxel goes to the
  // object whose start is nearest (in steps through accepted voxels).
  std::vector<long long> front, next;
  for (std::size_t o = 0; o < regions.size() && o < 65535; ++o)
  {
    if (!regions[o].On)
    {
      continue;
    }
    const TriangleMesh surface =
      regions.size() == 1 ? start : ObjectSurface(start, static_cast<int>(o));
    for (long long v : Seeds(image, surface, regions[o].Low, regions[o].High))
    {
      if (label[v] == 0)
      {
        label[v] = static_cast<unsigned short>(o + 1);
        ++counts[o];
        front.push_back(v);
      }
    }
  }
  const int nx = g.Dimensions[0], ny = g.Dimensions[1], nz = g.Dimensions[2];
  const long long slice = static_cast<long long>(nx) * ny;
  while (!front.empty())
  {
    next.clear();
    for (long long v : front)
    {
      const int o = label[v] - 1;
      const int i = static_cast<int>(v % nx), j = static_cast<int>((v / nx) % ny),
                k = static_cast<int>(v / slice);
      const long long neighbours[6] = { i > 0 ? v - 1 : -1, i + 1 < nx ? v + 1 : -1,
        j > 0 ? v - nx : -1, j + 1 < ny ? v + nx : -1, k > 0 ? v - slice : -1,
        k + 1 < nz ? v + slice : -1 };
      for (long long w : neighbours)
      {
        if (w < 0 || label[w] != 0)
        {
          continue;
        }
        const double x = ValueAt(image, w);
        if (x >= regions[o].Low && x <= regions[o].High)
        {
          label[w] = static_cast<unsigned short>(o + 1);
          ++counts[o];
          next.push_back(w);
        }
      }
    }
    front.swap(next);
  }
  return label;
}
} // namespace dsurf
