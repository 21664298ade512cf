// SPDX-License-Identifier: BSD-3-Clause
// Several objects that meet but never cross (docs/METHOD.md §9.9; beyond the paper, which
// solves the three parts of its engine one by one). Plain C++.
//
// Before every sweep each vertex gets a longest step. Two triangles of different objects at
// distance g, whose corners each move at most (g - c) / 2, stay at least the clearance c apart
// while they move: every point of a triangle is a convex combination of its corners, so it moves
// at most as far as its farthest corner, and the two triangles close in by at most the sum.
// Checking every pair each sweep would be quadratic; instead the pairs of triangles of different
// objects within R = c + 2 B of each other (B, the travel budget) are listed once, and each vertex
// also moves at most B away from where it stood when the list was made: a pair not listed was R
// apart, and its corners have closed in by at most 2 B since. The list is made again once some
// vertex has travelled B / 2. The limits depend only on the positions at the start of the sweep,
// so the sweep stays bit-identical for any number of threads, and equal under MPI (every process
// holds the whole mesh).
#ifndef dsContact_h
#define dsContact_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTriangleMesh.h"

#include <utility>
#include <vector>

namespace dsurf
{
/// The gap kept between two objects, in voxels (mean spacing): where they meet they rest this
/// far apart, so that touching is never counted as crossing.
constexpr double ContactClearanceVoxels = 0.1;

class DEFORMABLESURFACEFILTERS_EXPORT ContactLimiter
{
public:
  /// The longest step of every point of `mesh` (mesh order; its Objects set, two or more
  /// objects) for the next sweep, keeping triangles of different objects `clearance` apart;
  /// `budget` (B above) trades the length of the list against how often it is made.
  void Limits(
    const TriangleMesh& mesh, double clearance, double budget, std::vector<double>& limits);
  /// Forget the list (a new mesh).
  void Reset()
  {
    this->Anchor.clear();
    this->Measured.clear();
  }
  /// How often the list was made, and its length now.
  int Builds() const { return this->BuildCount; }
  std::size_t Pairs() const { return this->Candidates.size(); }

private:
  void Build(const TriangleMesh& mesh, double reach);
  std::vector<Vec3> Anchor; ///< the points when the list was made
  std::vector<std::pair<int, int>> Candidates;
  /// Measuring every pair every sweep would cost more than the sweep: the distances are
  /// measured when the list is made and again once a vertex has moved B / 8 since, and in
  /// between bounded from below by the distance measured less the corners' moves (which leaves
  /// objects at rest at most c + B / 4 apart).
  void Measure(const TriangleMesh& mesh, double far);
  std::vector<Vec3> Measured; ///< the points when Gaps were measured
  std::vector<double> Gaps;   ///< per candidate, its distance then
  std::vector<double> Moved;  ///< per point, how far from Measured (scratch)
  double Clearance = 0, Budget = 0;
  int BuildCount = 0;
};

/// Triangle pairs of different objects that intersect (mesh.Objects per point; 0 with one
/// object).
DEFORMABLESURFACEFILTERS_EXPORT int CountCrossingPairs(const TriangleMesh& mesh);
} // namespace dsurf

#endif
