// SPDX-License-Identifier: BSD-3-Clause
#include "dsInsideVoxels.h"

#include <algorithm>
#include <cmath>

namespace dsurf
{
std::vector<std::vector<double>> RowCrossings(
  const ImageGeometry& g, const VoxelBox& rows, const TriangleMesh& mesh)
{
  const int ny = g.Dimensions[1], nz = g.Dimensions[2];
  const std::size_t rowsY = static_cast<std::size_t>(rows.End[1] - rows.Begin[1]);
  const auto rowIndex = [&](int j, int k)
  { return (j - rows.Begin[1]) + rowsY * static_cast<std::size_t>(k - rows.Begin[2]); };
  std::vector<Vec3> ijk(mesh.Points.size());
  for (std::size_t i = 0; i < ijk.size(); ++i)
  {
    g.WorldToIndex(mesh.Points[i].data(), ijk[i].data());
  }
  std::vector<std::vector<double>> crossings(rowsY * (rows.End[2] - rows.Begin[2]));
  for (const auto& t : mesh.Triangles)
  {
    const Vec3 &a = ijk[t[0]], &b = ijk[t[1]], &c = ijk[t[2]];
    const int j0 = std::max(0, ClampedIndex(std::ceil(std::min({ a[1], b[1], c[1] })), ny));
    const int j1 = std::min(ny - 1, ClampedIndex(std::floor(std::max({ a[1], b[1], c[1] })), ny));
    const int k0 = std::max(0, ClampedIndex(std::ceil(std::min({ a[2], b[2], c[2] })), nz));
    const int k1 = std::min(nz - 1, ClampedIndex(std::floor(std::max({ a[2], b[2], c[2] })), nz));
    // Barycentric coordinates of (y, z) in the triangle's projection onto the y-z plane.
    const double det = (b[1] - a[1]) * (c[2] - a[2]) - (c[1] - a[1]) * (b[2] - a[2]);
    if (det == 0.0)
    {
      continue; // edge-on: the row lines graze it, the neighbours count the crossing
    }
    for (int k = std::max(k0, rows.Begin[2]); k <= std::min(k1, rows.End[2] - 1); ++k)
    {
      for (int j = std::max(j0, rows.Begin[1]); j <= std::min(j1, rows.End[1] - 1); ++j)
      {
        // The row's line is moved by a tiny irrational offset, so it never passes exactly
        // through a vertex or an edge (picked points often lie on whole voxel indices): every
        // crossing then belongs to exactly one triangle.
        const double y = j + 1.1e-7 * M_SQRT2, z = k + 1.3e-7 * M_PI;
        const double u = ((y - a[1]) * (c[2] - a[2]) - (c[1] - a[1]) * (z - a[2])) / det;
        const double v = ((b[1] - a[1]) * (z - a[2]) - (y - a[1]) * (b[2] - a[2])) / det;
        if (u >= 0 && v >= 0 && u + v <= 1)
        {
          crossings[rowIndex(j, k)].push_back(a[0] + u * (b[0] - a[0]) + v * (c[0] - a[0]));
        }
      }
    }
  }
  for (std::vector<double>& xs : crossings)
  {
    std::sort(xs.begin(), xs.end());
  }
  return crossings;
}
} // namespace dsurf
