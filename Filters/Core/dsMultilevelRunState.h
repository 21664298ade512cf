// SPDX-License-Identifier: BSD-3-Clause
// MultilevelSolver's state across the levels of one run, shared by its source files
// (dsMultilevel.cxx, dsMultilevelStart.cxx, dsMultilevelRegion.cxx, dsMultilevelRefine.cxx).
#ifndef dsMultilevelRunState_h
#define dsMultilevelRunState_h

#include "dsMultilevel.h"

#include <string>
#include <vector>

namespace dsurf
{
/// What the levels of one run share: the refiner, the solver and the force field, this
/// level's sigma, and the facts about the start the schedule keeps checking.
struct MultilevelSolver::RunState
{
  RedGreenRefiner Refiner;
  Solver LevelSolver;
  ForceField Field;
  VoxelBox FieldBox; ///< the image's voxels Field covers
  ScaleSpaceParameters FieldParameters;
  /// Field was made at FieldParameters.Sigma over FieldBox. Distributed, a piece that holds
  /// nothing of the box has an empty field of its own: whether to make the field again is
  /// decided on this and the box, which every process shares, so that all take part.
  bool FieldMade = false;
  /// The level's field is on the image's own grid over a box that follows the surface (a first
  /// level: FollowSurface).
  bool FieldFollows = false;
  /// The level's field is kept in bricks around the surface (FieldInBricks; the same on every
  /// process, whether its piece holds bricks or not).
  bool FieldBricked = false;
  /// Why the field could not follow the surface (FollowSurface); the run ends with it.
  std::string FieldError;
  /// Field misses (LevelRecord::FieldMisses) of the fields this level made before its current
  /// one, and the current field's count when the level's sweeps began or it was made.
  long long EarlierMisses = 0, MissesBase = 0;
  double Voxel = 0; ///< mean spacing: the finest detail the image shows
  double Sigma = 0; ///< this level's
  double FirstSigma = 0;
  bool Region = false;        ///< the region force is on
  bool CheckTopology = false; ///< CheckTopology, always on in Debug builds
  int EulerStart = 0;
  bool ClosedStart = false;
  /// A closed start's enclosed volume per object (ObjectVolumes), and a voxel's: a surface that
  /// collapses fails the run (CollapsedObject).
  std::vector<double> StartVolumes;
  double VoxelVolume = 0;
  bool BudgetWarned = false; ///< the MaxVertices warning is given once
  int SweepCounter = 0;
  /// Per vertex: a corner of a triangle the object lies beyond (FrontTriangles); after sigma's
  /// floor the levels go on there (a front level).
  std::vector<char> Front;
  bool FrontLevel = false; ///< this level follows the front at sigma's floor
  /// This level rests a click's surface at the local midpoint (after the schedule and the front
  /// levels; MidpointLevelWanted).
  bool MidpointLevel = false;
  /// Per object, on a front level: whether its front is followed (FrontOf).
  std::vector<char> FrontObjects;
  /// Per object: its front's triangles at each front level so far (FrontOf, FrontGrows).
  std::vector<std::vector<long long>> FrontHistory;
  bool FrontGrowthWarned = false; ///< the warning that a front grew is given once
  /// A level's sweeps made the surface cross itself: from that level on, its parts are kept
  /// apart (SolveLevelKeptApart).
  bool KeepApart = false;
  /// A front level made the surface cross itself or turned an object inside out: its moves were
  /// undone and no front level follows (SolveFrontLevel).
  bool FrontCrossed = false;
};
} // namespace dsurf

#endif
