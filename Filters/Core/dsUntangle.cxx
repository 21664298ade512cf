// SPDX-License-Identifier: BSD-3-Clause
#include "dsUntangle.h"

#include "dsSelfIntersectionCount.h"

#include <utility>
#include <vector>

namespace dsurf
{
UntangleResult Untangle(TriangleMesh& mesh, int rounds, int steps)
{
  UntangleResult result;
  std::vector<std::pair<int, int>> pairs;
  result.Before = result.After = CountSelfIntersections(mesh, &pairs);
  const int n = mesh.NumberOfPoints();
  for (int round = 0; round < rounds && result.After > 0; ++round)
  {
    // The corners of the intersecting triangles, grown by two rings.
    std::vector<char> selected(n, 0);
    for (const auto& p : pairs)
    {
      for (int t : { p.first, p.second })
      {
        for (int v : mesh.Triangles[t])
        {
          selected[v] = 1;
        }
      }
    }
    for (int ring = 0; ring < 2; ++ring)
    {
      std::vector<char> grown = selected;
      for (int v = 0; v < n; ++v)
      {
        if (selected[v])
        {
          for (int i = mesh.NeighborOffsets[v]; i < mesh.NeighborOffsets[v + 1]; ++i)
          {
            grown[mesh.Neighbors[i]] = 1;
          }
        }
      }
      selected.swap(grown);
    }
    std::vector<int> vertices;
    for (int v = 0; v < n; ++v)
    {
      if (selected[v] && !mesh.BoundaryVertex[v] &&
        mesh.NeighborOffsets[v + 1] > mesh.NeighborOffsets[v])
      {
        vertices.push_back(v);
      }
    }
    result.Moved += static_cast<int>(vertices.size());
    for (int s = 0; s < steps; ++s)
    {
      for (int v : vertices)
      {
        Vec3 centre{ 0, 0, 0 };
        const int begin = mesh.NeighborOffsets[v], end = mesh.NeighborOffsets[v + 1];
        for (int i = begin; i < end; ++i)
        {
          centre = centre + mesh.Points[mesh.Neighbors[i]];
        }
        centre = (1.0 / (end - begin)) * centre;
        mesh.Points[v] = mesh.Points[v] + 0.5 * (centre - mesh.Points[v]);
      }
    }
    pairs.clear();
    result.After = CountSelfIntersections(mesh, &pairs);
  }
  return result;
}
} // namespace dsurf
