// SPDX-License-Identifier: BSD-3-Clause
// Shared by the fuzzers: a check that aborts (libFuzzer then saves the input as a crash), and
// the surface checks the filters promise, on dsurf::TriangleMesh.
#ifndef FuzzCheck_h
#define FuzzCheck_h

#include "dsTriangleMesh.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

/// FUZZ_CHECK(cond, message): a broken promise is a finding: print it and abort.
#define FUZZ_CHECK(cond, msg)                                                                      \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::fprintf(stderr, "%s:%d: FUZZ_CHECK(%s) failed: %s\n", __FILE__, __LINE__, #cond,        \
        std::string(msg).c_str());                                                                 \
      std::abort();                                                                                \
    }                                                                                              \
  } while (0)

namespace fuzzcheck
{
/// Every coordinate finite.
inline bool AllFinite(const dsurf::TriangleMesh& mesh)
{
  for (const auto& p : mesh.Points)
  {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      return false;
    }
  }
  return true;
}

/// Euler characteristic of the triangles alone: points no triangle uses do not count.
/// Needs BuildTopology().
inline int SurfaceEuler(const dsurf::TriangleMesh& mesh)
{
  int used = 0;
  for (int v = 0; v < mesh.NumberOfPoints(); ++v)
  {
    used += mesh.VertexTriangleOffsets[v + 1] > mesh.VertexTriangleOffsets[v] ? 1 : 0;
  }
  return used - static_cast<int>(mesh.Edges.size()) + mesh.NumberOfTriangles();
}

/// The topology of a surface a filter returns: builds it, then manifold edges and vertices,
/// consistent orientation, no unused point; closed when asked. Returns "" or what is wrong.
inline std::string SurfaceProblem(dsurf::TriangleMesh& mesh, bool mustBeClosed)
{
  std::string error;
  if (!mesh.BuildTopology(&error))
  {
    return "not a manifold triangle mesh: " + error;
  }
  if (!AllFinite(mesh))
  {
    return "a non-finite point coordinate";
  }
  if (mustBeClosed && !mesh.IsClosed())
  {
    return "not closed";
  }
  if (!mesh.IsConsistentlyOriented())
  {
    return "inconsistently oriented";
  }
  if (mesh.CountNonManifoldVertices() != 0)
  {
    return "non-manifold vertices";
  }
  for (int v = 0; v < mesh.NumberOfPoints(); ++v)
  {
    if (mesh.VertexTriangleOffsets[v + 1] == mesh.VertexTriangleOffsets[v])
    {
      return "point " + std::to_string(v) + " is used by no triangle";
    }
  }
  return "";
}
} // namespace fuzzcheck

#endif
