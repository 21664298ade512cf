// SPDX-License-Identifier: BSD-3-Clause
// A click's region competition (docs/METHOD.md §9.3): a start inside one region (fewer than
// ClickVoxels inside, dsRegion.h) cannot tell its object from the background just outside it, so
// its range comes from the classes of intensity around it instead: a Gaussian mixture of its
// neighbourhood (dsMixture.h), the click's class in it, and the decision boundaries between that
// class (or the click's own model) and the classes that compete with it on either side. Plain
// C++, used by dsRegion.cxx (and its ghost rule by dsMultilevel.cxx).
#ifndef dsClickCompetition_h
#define dsClickCompetition_h

#include "dsPieceField.h"
#include "dsRegion.h"
#include "dsTriangleMesh.h"

namespace dsurf
{
/// A class of a click's mixture is the partial volume between two others only where its voxels
/// lie on ramps between them: another class's voxel, darker one way and brighter the other, within
/// this many voxels along an axis (dsClickCompetition.cxx, BetweenShares). A distributed image's
/// pieces keep at least this many ghost layers (MultilevelSolver::DistributedGhostVoxels).
constexpr int BlendReachVoxels = 3;

/// A start inside one region (a click): its competitors are the other classes of intensity
/// around it. The voxels within `reach` of the start's bounding box are fitted as a Gaussian
/// mixture (dsMixture.h, 256 bins between their MixtureTailShare quantiles); the object's class
/// is the one likeliest at the inside median, and the range runs from there, on each side, to where
/// a class lying on that side explains the image better: the decision boundary of region
/// competition (Zhu and Yuille, IEEE PAMI 18(9), 1996) between the object's model and its
/// neighbour's. A side without a competitor stays open (to beyond the neighbourhood's extreme
/// value, so the speed's ramp lies outside the data). Nothing changes when the neighbourhood holds
/// one class. Where the click's class merges its tissue with others (MergesClickTissue), the
/// click's own model, N(m0, clickSpread) with the class's weight, competes in its place
/// (ClickRangeEnds).
void CompetitorsAround(const ImagePiece& piece, const TriangleMesh& mesh, double reach,
  const PieceReductions& reduce, double clickSpread, RangeEstimate& estimate);
} // namespace dsurf

#endif
