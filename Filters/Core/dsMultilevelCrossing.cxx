// SPDX-License-Identifier: BSD-3-Clause
// MultilevelSolver's levels that leave the surface crossing itself: folds smoothed open after a
// level (docs/METHOD.md §9.4), a front level that crossed undone (§9.3, "Front levels"), a level
// that crossed solved again with its parts kept apart (§9.3, "Why one click can fold"), and the
// few pairs a kept-apart level leaves smoothed at once.
#include "dsMultilevel.h"

#include "dsMultilevelRunState.h"
#include "dsSelfIntersectionCount.h"
#include "dsUntangle.h"

#include <string>
#include <vector>

namespace dsurf
{
void MultilevelSolver::SmoothFolds(TriangleMesh& mesh, LevelRecord& rec)
{
  // Folds the forces left (two parts of the surface pushed together) are smoothed open
  // (dsUntangle.h). Its umbrella steps know nothing of other objects: where smoothing one
  // object's folds would pass through another, the folds stay (docs/METHOD.md §9.9). Objects
  // never cross before it (the starts are checked, the sweeps keep the clearance, refinement is
  // guarded): any crossing pair is the smoothing's.
  const bool several = mesh.NumberOfObjects() > 1;
  const std::vector<Vec3> before = several ? mesh.Points : std::vector<Vec3>();
  rec.Folds = Untangle(mesh);
  if (several && CountCrossingPairs(mesh) > 0)
  {
    mesh.Points = before;
    rec.Folds.After = CountSelfIntersections(mesh);
    this->Warnings.push_back("the folds of level " + std::to_string(rec.Level) +
      " were left as they are: smoothing them would pass through another object");
  }
  if (rec.Folds.After > 0)
  {
    this->Warnings.push_back(std::to_string(rec.Folds.After) +
      " pairs of triangles still intersect after level " + std::to_string(rec.Level) + " (" +
      std::to_string(rec.Folds.Before) + " before smoothing them)");
  }
}

bool MultilevelSolver::SolveFrontLevel(
  const ImageView& image, TriangleMesh& mesh, RunState& state, LevelRecord& rec)
{
  // A front level pushes a few thin parts at the floor's sigma with the region force at full
  // strength, and is not kept apart (SolveLevelKeptApart). Where it made the surface cross
  // itself, it pushed it through its own other side, or folded it where the front branched, not
  // into a thin part (docs/METHOD.md §9.3). A click in a head CT's sphenoid sinus, whose surface
  // already met itself around the septum: 0 crossing pairs before its first front level, 130
  // after and 71 at the end, or, from the committed click, a surface inside out. Clicks in
  // Colin27's lateral ventricles, whose fronts branched into the CSF's network: 8-204 pairs
  // after the second front level, 1 000-1 400 at the last, 114-187 left at the end. That level's
  // moves are undone, also when they turned an object inside out (a collapse), and the front is
  // followed no further. Kept apart instead (SelfContact on front levels too), the ventricles
  // ended without crossing pairs as well but took 3-4 times as long, reaching 0.2-0.9 ml
  // further, and the sinus took 9.5 s against 2.4 s.
  const std::vector<Vec3> start = mesh.Points;
  const int crossingBefore = CountSelfIntersections(mesh);
  const bool stop = this->SolveLevel(image, mesh, state, rec);
  const bool collapsed = !this->Collapse.empty();
  const int crossingAfter = collapsed ? crossingBefore : CountSelfIntersections(mesh);
  if (collapsed || crossingAfter > crossingBefore)
  {
    mesh.Points = start;
    state.FrontCrossed = true;
    this->Collapse.clear();
    this->Warnings.push_back("level " + std::to_string(rec.Level) +
      ", which followed thin parts left behind, was undone and no such level follows: its moves " +
      (collapsed ? std::string("turned an object inside out")
                 : "made the surface cross itself (" + std::to_string(crossingAfter) +
            " intersecting pairs of triangles, " + std::to_string(crossingBefore) + " before it)") +
      " (docs/METHOD.md §9.3)");
    return stop && !collapsed;
  }
  return stop;
}

bool MultilevelSolver::SolveLevelKeptApart(
  const ImageView& image, TriangleMesh& mesh, RunState& state, LevelRecord& rec)
{
  // A balloon grows the surface around the dark gaps of its object until their two sides meet,
  // and nothing else keeps them from passing through each other (docs/METHOD.md §9.3). Keeping
  // every level's parts apart costs a pair list kept up to date every few sweeps (dsContact.h),
  // about as much as the sweeps, and most surfaces never come near themselves: so a level
  // is solved as the paper does, and solved again from where it started, its parts kept apart,
  // when its sweeps left more crossing pairs than it began with. From there every level keeps
  // them apart. Not the front levels, which push a few thin parts at the floor's sigma (the
  // walls of a horn face each other all along it) and are undone where they cross
  // (SolveFrontLevel), nor several objects, whose folds within one object are smoothed as
  // before (solved again, the engine phantom's pistons of TestSeveralObjectsMeet ended 0.51
  // voxel from their boundaries, 0.42 without).
  // Every process holds the whole mesh, so every process decides alike.
  const bool watch =
    state.Region && !state.FrontLevel && !state.KeepApart && mesh.NumberOfObjects() == 1;
  this->SelfContact = state.Region && !state.FrontLevel && state.KeepApart;
  if (state.FrontLevel)
  {
    return this->SolveFrontLevel(image, mesh, state, rec);
  }
  if (!watch)
  {
    rec.KeptApart = this->SelfContact;
    const bool stop = this->SolveLevel(image, mesh, state, rec);
    if (this->SelfContact)
    {
      this->SmoothKeptApart(mesh, rec);
    }
    return stop;
  }
  const std::vector<Vec3> start = mesh.Points;
  const int crossingBefore = CountSelfIntersections(mesh);
  const bool stop = this->SolveLevel(image, mesh, state, rec);
  const int crossingAfter = CountSelfIntersections(mesh);
  if (stop || crossingAfter <= crossingBefore)
  {
    return stop;
  }
  // A few pairs on a mesh that resolves its sigma are what the smoothing after the level
  // (EndSweeps) opens: solved again only if it would not. So on the schedule's last level, whose
  // pairs are smoothed now (front levels may follow, refining them first): solved again, the
  // KmeansTest click's last level (tens of pairs on ~7 300 vertices) took about five times as
  // long for a surface 0.01-0.02 mm nearer its mask.
  const bool resolves = rec.MeanEdgeLength <= rec.Sigma;
  if (resolves || this->ScheduleEndsAt(state, rec.Level))
  {
    TriangleMesh trial = mesh;
    const UntangleResult folds = Untangle(trial);
    if (folds.After <= crossingBefore)
    {
      if (!resolves)
      {
        mesh.Points = trial.Points;
        rec.Folds = folds;
      }
      return stop;
    }
  }
  mesh.Points = start;
  rec.Converged = false;
  rec.Stalled = false;
  rec.KeptApart = true;
  state.KeepApart = true;
  this->SelfContact = true;
  const bool again = this->SolveLevel(image, mesh, state, rec);
  this->SmoothKeptApart(mesh, rec);
  return again;
}

void MultilevelSolver::SmoothKeptApart(TriangleMesh& mesh, LevelRecord& rec)
{
  // The bounds leave alone what already crosses and what shares a corner (dsContact.h): the
  // few pairs a kept-apart level still leaves are smoothed open at once, on any mesh. §9.4
  // waits for a mesh that resolves sigma, but refinement splits each crossing pair into pairs
  // whose children still cross: a Colin27 click went 3, 15, 36, 79 to 124 pairs over its levels.
  // Only when the smoothing opens every pair: on a coarse mesh its rings are wide, and where it
  // could not (the engine phantom's seeds run as one object) it left 455 pairs at the end, none
  // without it.
  if (rec.MeanEdgeLength <= rec.Sigma || CountSelfIntersections(mesh) == 0)
  {
    return;
  }
  TriangleMesh trial = mesh;
  const UntangleResult folds = Untangle(trial);
  if (folds.After == 0)
  {
    mesh.Points = trial.Points;
    rec.Folds = folds;
  }
}
} // namespace dsurf
