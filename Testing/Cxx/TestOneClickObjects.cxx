// SPDX-License-Identifier: BSD-3-Clause
// The goals for one click with every default (docs/METHOD.md §9.3), on the phantoms of
// ObjectPhantoms.h, each click scored against its object's label (OneClickScore.h):
// - spine (3 mm CT, one click in the middle of the middle body, the default 5 mm seed sphere):
//   at most 5 % of the enclosed volume outside the middle body, Dice >= 0.9;
// - horned (a dark body with four horns 2-4 voxels wide, one click at the body's centre):
//   reference boundary -> surface mean <= 0.5 voxel, 95 % <= 1.5 voxel, no self-intersections.
// The spine's one-voxel cortex is brighter than the range's far end: without the click's last
// level at the local midpoint (docs/METHOD.md §9.3) 8.5 % lay outside. The committed phantom
// ends 4.6 % outside, the most of noise seeds 2401-2407 (3.7-4.6 %), close to the goal: a
// change that moves it by half a point fails here (that level run to a stricter rest: 5.3 %).
// `scripts/benchmark.sh Objects` prints the numbers beside the goals.
#include "DSTestHelpers.h"
#include "OneClickScore.h"

using namespace dsobjects;

int TestOneClickObjects(int, char*[])
{
  const ObjectScore spine = ScoreOneClick(SpinePhantom()).Score;
  DS_CHECK_LE(spine.OutsideShare, 0.05, "spine: share of the enclosed volume outside the body");
  DS_CHECK_GE(spine.Dice, 0.9, "spine: Dice against the middle body");
  const ObjectScore horned = ScoreOneClick(HornedPhantom()).Score;
  DS_CHECK_LE(horned.ReferenceMean, 0.5, "horned: reference -> surface mean (voxels)");
  DS_CHECK_LE(horned.ReferenceP95, 1.5, "horned: reference -> surface 95 % (voxels)");
  DS_CHECK(horned.SelfIntersections == 0, "horned: no self-intersections");
  return dstest::Result("TestOneClickObjects");
}

int main(int argc, char* argv[])
{
  return TestOneClickObjects(argc, argv);
}
