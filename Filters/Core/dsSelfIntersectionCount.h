// SPDX-License-Identifier: BSD-3-Clause
// Counting self-intersections of a triangle mesh (docs/METHOD.md §5, ours; the count behind
// the SelfIntersections field; the rule that keeps the force from folding the surface is
// dsSelfIntersectionRule.h): a bounding-volume
// hierarchy over the triangles' bounding boxes finds candidate pairs (not O(n^2), and
// bounded memory for any mix of triangle sizes), Moeller's interval test decides each
// pair. Plain C++, no pipeline types.
#ifndef dsSelfIntersectionCount_h
#define dsSelfIntersectionCount_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTriangleMesh.h"

#include <utility>
#include <vector>

namespace dsurf
{
/// True when the closed triangles (a0,a1,a2) and (b0,b1,b2) share a point (Moeller 1997,
/// with a 2-D edge/containment test for coplanar pairs). Distances to the other plane
/// within a tiny relative tolerance count as zero, so touching counts as intersecting.
/// Nearly coplanar pairs (planes within an angle whose sine is 1e-6) are decided in 2-D too:
/// the 3-D test cannot place the common line of nearly parallel planes.
DEFORMABLESURFACEFILTERS_EXPORT bool TrianglesIntersect(
  const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2);

/// Triangles (s,a1,a2) and (s,b1,b2) share the vertex s: true when they overlap in more
/// than s, i.e. one folds through the other. (Nearly) coplanar pairs overlap when their
/// wedges at s do, projected onto the plane: a triangle folded flat onto its neighbour counts,
/// neighbours side by side in a flat patch do not.
DEFORMABLESURFACEFILTERS_EXPORT bool SharedVertexTrianglesOverlap(
  const Vec3& s, const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2);

/// Number of intersecting triangle pairs of the mesh (needs only Points and Triangles).
/// Pairs sharing an edge are skipped (they touch by construction); pairs sharing one
/// vertex count only when they overlap beyond it. `pairs`, when given, receives them
/// (t1 < t2, sorted).
DEFORMABLESURFACEFILTERS_EXPORT int CountSelfIntersections(
  const TriangleMesh& mesh, std::vector<std::pair<int, int>>* pairs = nullptr);
} // namespace dsurf

#endif
