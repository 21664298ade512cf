// SPDX-License-Identifier: BSD-3-Clause
#include "dsObjects.h"

#include <algorithm>

namespace dsurf
{
TriangleMesh ObjectSurface(const TriangleMesh& mesh, int object)
{
  TriangleMesh out;
  std::vector<int> index(mesh.Points.size(), -1);
  for (const auto& tri : mesh.Triangles)
  {
    if (mesh.Objects.empty() ? object != 0 : mesh.Objects[tri[0]] != object)
    {
      continue;
    }
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k)
    {
      int& i = index[tri[k]];
      if (i < 0)
      {
        i = out.NumberOfPoints();
        out.Points.push_back(mesh.Points[tri[k]]);
      }
      t[k] = i;
    }
    out.Triangles.push_back(t);
  }
  std::string ignored;
  out.BuildTopology(&ignored);
  return out;
}

bool AssignObjects(TriangleMesh& mesh, const std::vector<long long>& triangleLabels,
  std::vector<long long>& ids, std::string* error)
{
  ids = triangleLabels;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  if (static_cast<int>(ids.size()) > MaxObjects)
  {
    if (error)
    {
      *error = "the start has " + std::to_string(ids.size()) + " ObjectId values; at most " +
        std::to_string(MaxObjects) + " objects are solved in one run";
    }
    return false;
  }
  mesh.Objects.assign(mesh.Points.size(), -1);
  for (std::size_t t = 0; t < mesh.Triangles.size(); ++t)
  {
    const int object =
      static_cast<int>(std::lower_bound(ids.begin(), ids.end(), triangleLabels[t]) - ids.begin());
    for (int v : mesh.Triangles[t])
    {
      if (mesh.Objects[v] >= 0 && mesh.Objects[v] != object)
      {
        if (error)
        {
          *error = "point " + std::to_string(v) + " belongs to triangles of ObjectId " +
            std::to_string(ids[mesh.Objects[v]]) + " and " + std::to_string(triangleLabels[t]) +
            ": objects must not share points";
        }
        mesh.Objects.clear();
        return false;
      }
      mesh.Objects[v] = object;
    }
  }
  std::replace(mesh.Objects.begin(), mesh.Objects.end(), -1, 0); // points of no triangle
  return true;
}

std::vector<double> ObjectVolumes(const TriangleMesh& mesh)
{
  std::vector<double> volumes(static_cast<std::size_t>(mesh.NumberOfObjects()), 0.0);
  for (const auto& t : mesh.Triangles)
  {
    const std::size_t o = mesh.Objects.empty() ? 0 : static_cast<std::size_t>(mesh.Objects[t[0]]);
    volumes[o] += Dot(mesh.Points[t[0]], Cross(mesh.Points[t[1]], mesh.Points[t[2]]));
  }
  for (double& v : volumes)
  {
    v /= 6.0;
  }
  return volumes;
}
} // namespace dsurf
