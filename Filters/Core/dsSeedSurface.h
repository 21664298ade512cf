// SPDX-License-Identifier: BSD-3-Clause
// The plain-C++ core of vtkDelaunaySeedSurface: per-tetrahedron measures, the boundary
// of a set of kept tetrahedra as a closed 2-manifold outward-oriented triangle surface
// (with pinch resolution), and uniform midpoint subdivision to a target edge length.
// No pipeline types: points are xyz triples, tetrahedra are 64-bit index tuples (VTK ids).
// The surface is a TriangleMesh (dsTriangleMesh.h; int point ids), whose mean edge length
// and 1 -> 4 subdivision it uses.
#ifndef dsSeedSurface_h
#define dsSeedSurface_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTriangleMesh.h"                 // TriangleMesh, Vec3

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace dsurf
{
using SeedTet = std::array<std::int64_t, 4>;

/// Why a tetrahedron is not part of the seed solid (the `Removed` cell array).
enum SeedTetStatus : unsigned char
{
  SeedKept = 0,
  SeedRemovedById = 1,
  SeedRemovedByAlpha = 2,
  SeedRemovedByIntensity = 3,
  SeedRemovedByPinch = 4,
  SeedRemovedDegenerate = 5
};

/// det[b-a, c-a, d-a] / 6: positive when d lies on the side abc's right-hand normal points to.
DEFORMABLESURFACEFILTERS_EXPORT double SeedTetSignedVolume(
  const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Radius of the sphere through the four corners; +infinity for a flat tetrahedron.
DEFORMABLESURFACEFILTERS_EXPORT double SeedTetCircumradius(
  const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// What ExtractSeedBoundary did, for the user's warning and for tests.
struct DEFORMABLESURFACEFILTERS_EXPORT SeedBoundaryReport
{
  std::int64_t KeptTetrahedra = 0;
  std::int64_t DegenerateRemoved = 0; ///< flat tetrahedra peeled off the boundary
  std::int64_t PinchedEdges = 0;      ///< edges shared by 4 or more boundary faces
  std::int64_t PinchedVertices = 0;   ///< vertices whose boundary faces form 2+ fans
  std::int64_t VertexCopiesAdded = 0; ///< extra point copies made by splitting pinched vertices
  std::int64_t PinchTetsRemoved = 0;  ///< tetrahedra removed where splitting was not enough
  std::int64_t Components = 0;        ///< connected components of the output surface
  std::string Summary() const;        ///< one human-readable line; empty when nothing happened
};

/// The output surface: a TriangleMesh (points are copies of input points, split pinch
/// vertices slightly moved apart) and, for each point, the index of the input point it came
/// from (-1 for a subdivision midpoint).
struct DEFORMABLESURFACEFILTERS_EXPORT SeedSurface : TriangleMesh
{
  std::vector<std::int64_t> SourcePoint;
};

/**
 * Boundary of the tetrahedra whose status is SeedKept: the faces used by exactly one kept
 * tetrahedron, oriented away from that tetrahedron's fourth corner (outward).
 *
 * Flat tetrahedra (|volume| <= degenerateVolume) that touch the boundary are peeled off first
 * (status SeedRemovedDegenerate) because their faces have no outward side.
 *
 * Pinches are resolved without changing the shape: around every boundary edge the faces are
 * paired by walking through the kept tetrahedra of one solid wedge (so a 4-face edge becomes
 * two 2-face edges), then every vertex gets one copy per fan of faces around it. Copies of a
 * split vertex are moved by 2% of the fan's mean edge length toward the fan's ring centroid so
 * that a later "merge coincident points" does not glue them back. Where two sheets would still
 * share an edge (a pinch along a whole edge whose ends are not pinch vertices), one kept
 * tetrahedron at the edge is removed (status SeedRemovedByPinch) and the extraction repeated.
 *
 * @param status in/out, one entry per tetrahedron.
 */
DEFORMABLESURFACEFILTERS_EXPORT SeedSurface ExtractSeedBoundary(const std::vector<Vec3>& points,
  const std::vector<SeedTet>& tets, std::vector<unsigned char>& status, double degenerateVolume,
  SeedBoundaryReport& report);

/**
 * Repeated 1-to-4 midpoint subdivision of the whole surface (TriangleMesh::SubdivideUniformly)
 * while its mean edge length exceeds sqrt(2) * target, so it ends within a factor sqrt(2) of
 * the target. Keeps the surface closed, manifold and oriented; new points get SourcePoint -1.
 * Stops before exceeding maxTriangles.
 * @return the number of subdivision steps done.
 */
DEFORMABLESURFACEFILTERS_EXPORT int SubdivideSeedSurface(
  SeedSurface& surface, double targetEdgeLength, std::int64_t maxTriangles = 4000000);
} // namespace dsurf

#endif
