// SPDX-License-Identifier: BSD-3-Clause
// Several objects that meet but never cross (docs/METHOD.md §9.9; beyond the paper, which
// solves the three parts of its engine one by one). Plain C++.
//
// Before every batch of sweeps each vertex gets bounds on where it may go. Two triangles that do
// not touch lie on either side of a plane (both are convex): take d, the unit vector between
// their nearest points, and the planes normal to d through the corner of each that reaches
// furthest toward the other; the plane midway between those is the pair's. While every corner
// of each stays on its own side, c / 2 off the midway plane, every point of the triangle does (it
// is a convex combination of its corners): they stay at least the clearance c apart, free to
// slide along the plane or to part. Two triangles already nearer than c keep at least their gap
// along d. The bounds are on positions, not steps, so they hold for any number of sweeps; the
// solver shortens (never turns) a step that would leave them (Solver::CorrectVertex).
// Checking every pair each batch would be quadratic; instead the pairs within R = c + 2 B of each
// other (B, the travel budget) are listed once, and each vertex stays within B of where it stood
// when the list was made: a pair not listed was R apart, and its corners have closed in by at
// most 2 B since. The list is made again once some vertex has travelled B / 2. Listed are pairs
// of different objects and, to keep one surface off itself, pairs of one object that face each
// other (Facing in dsContact.cxx). The bounds depend only on the positions at the start of the
// batch and each vertex's own, so the sweeps stay bit-identical for any number of threads, and
// equal under MPI (every process holds the whole mesh).
#ifndef dsContact_h
#define dsContact_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTriangleMesh.h"

#include <array>
#include <utility>
#include <vector>

namespace dsurf
{
/// The gap kept between two objects, in voxels (mean spacing): where they meet they rest this
/// far apart, so that touching is never counted as crossing.
constexpr double ContactClearanceVoxels = 0.1;

/// Per vertex (mesh order), where it may go in the next sweeps: within Radii[v] of Anchors[v],
/// and in the half-spaces Dot(x, Normals[e]) <= Limits[e] for e in [Offsets[v], Offsets[v + 1]).
/// Each contains the vertex where it stands when they are made; a step that would leave one is
/// shortened, not turned, so it stays in all of them (they are convex).
struct ContactBounds
{
  std::vector<Vec3> Anchors;
  std::vector<double> Radii;
  std::vector<int> Offsets;
  std::vector<Vec3> Normals;
  std::vector<double> Limits;
  bool Empty() const { return this->Radii.empty(); }
};

/// How far a vertex at `point` may step along `step` within `bounds` (vertex `v`, mesh order):
/// the largest s in [0, 1] that keeps point + s step in all of them.
DEFORMABLESURFACEFILTERS_EXPORT double ContactStepScale(
  const ContactBounds& bounds, int v, const Vec3& point, const Vec3& step);

class DEFORMABLESURFACEFILTERS_EXPORT ContactLimiter
{
public:
  /// The bounds of every point of `mesh` (mesh order) for the next sweeps, keeping triangles of
  /// different objects (mesh.Objects) `clearance` apart, and with `self` also the parts of one
  /// object that face each other (two triangles sharing no corner, their normals against each
  /// other: the two sides of a gap the surface grows around, which would fold it); `budget` (B
  /// above) trades the length of the list against how often it is made. A pair of one object
  /// that already intersects (a refinement's fold) is left to the smoothing; the corners of two
  /// objects' triangles that intersect stay where they are.
  void Limits(
    const TriangleMesh& mesh, double clearance, double budget, bool self, ContactBounds& bounds);
  /// Forget the list (a new mesh).
  void Reset() { this->Anchor.clear(); }
  /// How often the list was made, and its length now.
  int Builds() const { return this->BuildCount; }
  std::size_t Pairs() const { return this->Candidates.size(); }

private:
  void Build(const TriangleMesh& mesh, double reach);
  /// Per candidate pair, the unit vector between its triangles' nearest points now (0 when they
  /// intersect; for a pair whose boxes lie `far` apart, the axis along which they lie apart).
  void Measure(const TriangleMesh& mesh, double far);
  std::vector<Vec3> Anchor; ///< the points when the list was made
  std::vector<std::pair<int, int>> Candidates;
  std::vector<Vec3> Directions; ///< per candidate (Measure)
  std::vector<int> PlaneCount;  ///< scratch of Limits
  double Clearance = 0, Budget = 0;
  bool Self = false;
  int BuildCount = 0;
};

/// Triangle pairs of different objects that intersect (mesh.Objects per point; 0 with one
/// object).
DEFORMABLESURFACEFILTERS_EXPORT int CountCrossingPairs(const TriangleMesh& mesh);
} // namespace dsurf

#endif
