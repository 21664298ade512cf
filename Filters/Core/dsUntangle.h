// SPDX-License-Identifier: BSD-3-Clause
// Removing folds the forces left (beyond the paper: docs/METHOD.md §9). Plain C++.
//
// The paper's projection rule (§5) keeps the external force from sliding vertices over each
// other, but it cannot stop two parts of the surface from meeting: a region force pulling a
// surface into a narrow dark gap (between the cerebrum and the cerebellum) brings the gap's two
// walls together. Where triangles intersect, their vertices and two rings of neighbours are
// smoothed toward their umbrella centres (x <- x + U(x) / 2, membrane steps that pull a fold
// open and flat) until no pair intersects or the rounds run out. The multilevel solver calls it
// on the delivered surface and after levels whose mesh resolves their sigma: on a coarser mesh
// two rings are most of the surface.
#ifndef dsUntangle_h
#define dsUntangle_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTriangleMesh.h"

namespace dsurf
{
struct DEFORMABLESURFACEFILTERS_EXPORT UntangleResult
{
  int Before = 0; ///< intersecting triangle pairs found first
  int After = 0;  ///< pairs left
  int Moved = 0;  ///< vertices smoothed (counted once per round)
};

/// Smooths the surroundings of intersecting triangle pairs of `mesh` (topology built; only
/// point positions change; open-boundary vertices stay) for at most `rounds` rounds of
/// `steps` umbrella steps each.
DEFORMABLESURFACEFILTERS_EXPORT UntangleResult Untangle(
  TriangleMesh& mesh, int rounds = 8, int steps = 5);
} // namespace dsurf

#endif
