// The plain-C++ core of vtkDelaunaySeedSurface: per-tetrahedron measures, the boundary
// of a set of kept tetrahedra as a closed 2-manifold outward-oriented triangle surface
// (with pinch resolution), and uniform midpoint subdivision to a target edge length.
// No pipeline types: points are xyz triples, cells are index tuples (64-bit: the seed is
// built from VTK ids; the solver's TriangleMesh uses int). Edge keys, mean edge length and
// the 1 -> 4 split are shared with TriangleMesh (dsTriangleMesh.h).
#ifndef dsSeedSurface_h
#define dsSeedSurface_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTriangleMesh.h"                 // Vec3

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace dsurf
{
using SeedPoint = Vec3; ///< the point type of TriangleMesh, with its arithmetic
using SeedTet = std::array<std::int64_t, 4>;
using SeedTriangle = std::array<std::int64_t, 3>;

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
  const SeedPoint& a, const SeedPoint& b, const SeedPoint& c, const SeedPoint& d);

/// Radius of the sphere through the four corners; +infinity for a flat tetrahedron.
DEFORMABLESURFACEFILTERS_EXPORT double SeedTetCircumradius(
  const SeedPoint& a, const SeedPoint& b, const SeedPoint& c, const SeedPoint& d);

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

/// The output surface: points (copies of input points, split pinch vertices slightly moved
/// apart), triangles, and for each output point the index of the input point it came from.
struct DEFORMABLESURFACEFILTERS_EXPORT SeedSurface
{
  std::vector<SeedPoint> Points;
  std::vector<SeedTriangle> Triangles;
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
DEFORMABLESURFACEFILTERS_EXPORT SeedSurface ExtractSeedBoundary(
  const std::vector<SeedPoint>& points, const std::vector<SeedTet>& tets,
  std::vector<unsigned char>& status, double degenerateVolume, SeedBoundaryReport& report);

/**
 * Repeated 1-to-4 midpoint subdivision of the whole surface while the mean edge length exceeds
 * sqrt(2) * target, so it ends within a factor sqrt(2) of the target. Keeps the surface closed,
 * manifold and oriented (shared edge midpoints). Stops before exceeding maxTriangles.
 * @return the number of subdivision steps done.
 */
DEFORMABLESURFACEFILTERS_EXPORT int SubdivideSeedSurface(
  SeedSurface& surface, double targetEdgeLength, std::int64_t maxTriangles = 4000000);

/// Mean length of the undirected edges of a triangle surface.
DEFORMABLESURFACEFILTERS_EXPORT double SeedMeanEdgeLength(const SeedSurface& surface);
} // namespace dsurf

#endif
