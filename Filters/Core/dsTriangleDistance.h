// SPDX-License-Identifier: BSD-3-Clause
// Distances between triangles, for the contact of several objects (dsContact.h). Plain C++.
//
// Two triangles that do not intersect are nearest either at a corner of one and a point of the
// other, or at a point of an edge of each (Ericson, Real-Time Collision Detection, 2005, §5.1.5
// and §5.1.9): the distance is the least of six point-triangle and nine segment-segment
// distances, and zero when they intersect (dsSelfIntersectionCount.h's test).
#ifndef dsTriangleDistance_h
#define dsTriangleDistance_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTriangleMesh.h"

namespace dsurf
{
/// The point of triangle (a, b, c) nearest p (Ericson §5.1.5, by the Voronoi regions of the
/// corners and edges); a degenerate triangle gives a point of its nearest edge.
DEFORMABLESURFACEFILTERS_EXPORT Vec3 ClosestPointOnTriangle(
  const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// The distance between the segments [p0, p1] and [q0, q1] (Ericson §5.1.9; degenerate segments
/// are points).
DEFORMABLESURFACEFILTERS_EXPORT double SegmentDistance(
  const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

/// The vector from the point of segment [p0, p1] nearest segment [q0, q1] to that of [q0, q1].
DEFORMABLESURFACEFILTERS_EXPORT Vec3 SegmentSeparation(
  const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

/// The vector between the nearest points of the closed triangles (a0, a1, a2) and (b0, b1, b2),
/// from the first's to the second's; 0 when they intersect. The plane through either point
/// normal to it separates the two (both are convex): dsContact.h limits steps along it.
DEFORMABLESURFACEFILTERS_EXPORT Vec3 TriangleSeparation(
  const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2);

/// The distance between the closed triangles (a0, a1, a2) and (b0, b1, b2); 0 when they
/// intersect.
DEFORMABLESURFACEFILTERS_EXPORT double TriangleDistance(
  const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2);
} // namespace dsurf

#endif
