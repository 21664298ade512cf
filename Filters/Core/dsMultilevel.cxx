// SPDX-License-Identifier: BSD-3-Clause
#include "dsMultilevel.h"
#include "dsMultilevelRunState.h"

#include "dsClickCompetition.h"

#include "dsGaussianSmoother.h"

#include "dsFieldBricks.h"
#include "dsMemory.h"
#include "dsObjects.h"
#include "dsPieceInitialSigma.h"
#include "dsRegion.h"
#include "dsThreads.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <sstream>

namespace dsurf
{
const char* StopReasonName(StopReason reason)
{
  switch (reason)
  {
    case StopReason::SigmaFloor:
      return "sigma floor";
    case StopReason::NoDetail:
      return "no detail";
    case StopReason::MaxLevels:
      return "MaxLevels";
    case StopReason::MaxSweeps:
      return "MaxSweeps";
    case StopReason::Aborted:
      return "aborted";
    default:
      return "none";
  }
}

double PotentialEdgeWidth(double sigma, double voxel)
{
  return std::sqrt(sigma * sigma + voxel * voxel);
}

double NextHierarchicalSigma(double sigma, double floor)
{
  // Half of sigma, unless the half would lie less than a third of an octave above the floor: a
  // level that little coarser than the floor's costs a field and the finest mesh's sweeps for
  // what the floor's level redoes (docs/METHOD.md §6.6).
  return 0.5 * sigma < std::cbrt(2.0) * floor ? std::min(sigma, floor) : 0.5 * sigma;
}

bool MultilevelSolver::GoOn(bool here) const
{
  // Distributed, every process answers the same: one stops, all stop (one maximum per batch).
  return this->Distributed ? this->Reduce.Max(here ? 0.0 : 1.0) == 0.0 : here;
}

namespace
{
/// The longest batch of sweeps between two makings of the contact bounds (LimitSteps).
constexpr int ContactBatchSweeps = 4;
}

namespace
{
/// Why the surface cannot go on: an object of a closed start whose enclosed volume fell below
/// half a voxel or changed sign (it passed through a point and turned inside out); empty when
/// none did. No force held it where it started: the region force pulled it in everywhere (a
/// range that leaves out the voxels around it) or was too weak against the edges that dragged it
/// off its object, and the internal force shrinks any surface nothing holds. Sweeps on would
/// turn it inside out and grow it again, its normals inward (docs/METHOD.md §9.3).
std::string CollapsedObject(
  const TriangleMesh& mesh, const std::vector<double>& startVolumes, double voxelVolume)
{
  const std::vector<double> volumes = ObjectVolumes(mesh);
  for (std::size_t o = 0; o < volumes.size() && o < startVolumes.size(); ++o)
  {
    const double v = volumes[o], v0 = startVolumes[o];
    if (!(v * v0 > 0) || std::abs(v) < 0.5 * std::min(voxelVolume, std::abs(v0)))
    {
      const std::string which = mesh.ObjectIds.size() > o
        ? "object " + std::to_string(mesh.ObjectIds[o]) + "'s surface"
        : "the surface";
      return which +
        " collapsed (it enclosed less than half a voxel, or turned inside out): nothing held it "
        "where it started. With a click, its intensity range may leave out the object's voxels "
        "around it (Preview Region shows what the region force grows through), or the region "
        "force may be too weak against the edges (raise Region Weight)";
    }
  }
  return std::string();
}
} // namespace

int MultilevelSolver::LimitSteps(const TriangleMesh& mesh, double lastStep)
{
  // The budget follows the steps: eight times the last sweep's longest (a list made for long
  // steps would be made again every sweep), from a quarter voxel (a surface at rest: a short
  // list) to half the mean edge; in powers of two of the voxel, so that it changes, and the list
  // is made again, only when the steps change by a factor of two.
  const double most = std::max(0.25 * this->Voxel, 0.5 * mesh.MeanEdgeLength());
  double budget = 0.25 * this->Voxel;
  while (budget < std::min(most, 8 * lastStep))
  {
    budget *= 2;
  }
  this->Contact.Limits(
    mesh, ContactClearanceVoxels * this->Voxel, budget, this->SelfContact, this->Bounds);
  // As many sweeps as travel half the budget at the last pace (the list is made again after
  // them): a vertex held back by the budget rather than by another part would pass for one at
  // rest, and a level whose fast vertices wait ends short of its object.
  return lastStep > 0
    ? std::max(1, std::min(ContactBatchSweeps, static_cast<int>(0.5 * budget / lastStep)))
    : 1;
}

namespace
{
/// Tells a level whose vertices step back and forth in place (StallWindowSweeps, StallNetShare,
/// StallVolumeShare): the mean net displacement since the window began against the mean
/// corrections summed over it, and each object's enclosed volume then and now (a closed start
/// only). Checked between batches, where the mesh holds the solver's positions; the same on
/// every process of a distributed solve (each holds the whole mesh and the reduced statistics).
class StallWatch
{
public:
  StallWatch(const TriangleMesh& mesh, double sigma, bool closed)
    : Anchor(mesh.Points)
    , Sigma(sigma)
    , Closed(closed)
    , Volumes(closed ? ObjectVolumes(mesh) : std::vector<double>())
  {
  }
  void Add(const SweepStatistics& st)
  {
    ++this->Sweeps;
    this->Travel += st.MeanCorrection;
    this->Moved = st.MovedVertices;
  }
  /// After a batch that ended at the level's sweep `s`: true when a window ended there (s a
  /// multiple of StallWindowSweeps) with the vertices back near where it began and, for a closed
  /// start, no object's volume changed by more than StallVolumeShare; else a window that ended
  /// starts again from here.
  bool Rests(const TriangleMesh& mesh, int s)
  {
    if (s % StallWindowSweeps != 0 || this->Sweeps == 0)
    {
      return false;
    }
    double net = 0;
    for (std::size_t v = 0; v < mesh.Points.size() && v < this->Anchor.size(); ++v)
    {
      net += Norm(mesh.Points[v] - this->Anchor[v]);
    }
    net /= std::max(1, this->Moved);
    bool rests = net < StallNetShare * this->Travel && net < StallSigmaShare * this->Sigma;
    if (this->Closed)
    {
      const std::vector<double> volumes = ObjectVolumes(mesh);
      for (std::size_t o = 0; o < volumes.size() && o < this->Volumes.size(); ++o)
      {
        rests = rests &&
          std::abs(volumes[o] - this->Volumes[o]) <= StallVolumeShare * std::abs(this->Volumes[o]);
      }
      this->Volumes = volumes;
    }
    this->Anchor = mesh.Points;
    this->Sweeps = 0;
    this->Travel = 0;
    return rests;
  }

private:
  std::vector<Vec3> Anchor;
  double Sigma;
  bool Closed;
  std::vector<double> Volumes;
  int Sweeps = 0, Moved = 0;
  double Travel = 0;
};
} // namespace

bool MultilevelSolver::SolveLevel(
  const ImageView& image, TriangleMesh& mesh, RunState& state, LevelRecord& rec)
{
  const MultilevelParameters& P = this->Parameters;
  Solver& solver = state.LevelSolver;
  const ForceField& field = state.Field; // made again in place when it follows the surface
  int& sweepCounter = state.SweepCounter;
  const int cap = rec.FrontRest > 0 ? std::min(FrontLevelSweeps, std::max(1, P.MaxSweepsPerLevel))
                                    : std::max(1, P.MaxSweepsPerLevel);
  const int plannedLevels = std::max(rec.Level, this->PlannedLevels);
  bool stop = false;
  // Sweeps run in batches inside one parallel region (threads start once per batch, not
  // per sweep); convergence is tested after every sweep, progress and abort between
  // batches, and the sweep records are handed on after each batch.
  // Batches shrink on big meshes so that progress moves and an abort is answered within
  // about the time of 16 sweeps of 50 000 vertices (one sweep from 800 000 vertices on).
  // Several objects, or one kept off itself: the contact bounds are made before each batch, and
  // a batch is at most ContactBatchSweeps (dsContact.h: the list is made again once a vertex has
  // travelled half its budget, four of the steps the budget was made for).
  const bool contact = mesh.NumberOfObjects() > 1 || this->SelfContact;
  const int batchSize = std::max(1,
    std::min({ P.SweepBatch, contact ? ContactBatchSweeps : P.SweepBatch,
      static_cast<int>(16LL * 50000 / std::max(1, mesh.NumberOfPoints())) }));
  solver.SetContactBounds(contact ? &this->Bounds : nullptr);
  this->Contact.Reset(); // the mesh may have changed since the last level (refinement, smoothing)
  std::vector<SweepStatistics> batchStats;
  state.EarlierMisses = 0;
  state.MissesBase = field.Bricks ? field.Bricks->Misses() : 0;
  StallWatch stall(mesh, rec.Sigma, state.ClosedStart);
  for (int s = 0; s < cap && !stop && !rec.Converged;)
  {
    // MaxSweeps: the run stops exactly there (the batch is cut short to reach it).
    const int budget = P.MaxSweeps > 0 ? P.MaxSweeps - sweepCounter : cap;
    if (budget <= 0)
    {
      this->Warnings.push_back(
        "stopped after MaxSweeps (" + std::to_string(P.MaxSweeps) + ") sweeps");
      this->Stop = StopReason::MaxSweeps;
      stop = true;
      break;
    }
    if (!this->FollowSurface(image, mesh, state, rec))
    {
      stop = true;
      break;
    }
    if (field.Bricks)
    {
      field.Bricks->Cover(mesh); // the bricks the surface has come within reach of
      if (!field.Bricks->Shortfall().empty())
      {
        // Serial only: a piece's bricks were counted whole before (PieceFieldBytes) and never
        // checked here, so no process leaves the others' reductions.
        assert(!this->Distributed);
        state.FieldError = "level " + std::to_string(rec.Level) +
          ": the force field could not follow the surface: " + field.Bricks->Shortfall();
        stop = true;
        break;
      }
    }
    int sweepsNow = batchSize;
    if (contact)
    {
      sweepsNow = std::min(batchSize,
        this->LimitSteps(
          mesh, this->Sweeps.empty() || s == 0 ? 0.0 : this->Sweeps.back().MaxCorrection));
    }
    batchStats.clear();
    double batchTravel = 0; // the sum of the batch's largest corrections: no vertex moved more
    // A batch ends at each stall window's end, so that the window's check (StallWatch) sees the
    // same sweeps whatever the batches (bricks and a following field end them early).
    solver.Sweeps(
      std::min({ sweepsNow, cap - s, budget, StallWindowSweeps - s % StallWindowSweeps }),
      [&](const SweepStatistics& st)
      {
        batchStats.push_back(st);
        // A front level rests when its fastest vertex does: the front is a few vertices, and
        // the mean over a whole surface at rest says nothing of them.
        const bool rests =
          rec.FrontRest > 0 ? st.MaxCorrection < rec.FrontRest : st.MeanCorrection < rec.Tolerance;
        if (st.MovedVertices == 0 || rests)
        {
          rec.Converged = true;
          return false;
        }
        // With bricks, the batch ends once a vertex may have moved half their reach, so that
        // Cover follows the surface before a sweep could take a vertex out of them; so does a
        // field that follows the surface. Decided on what every process shares (a piece holding
        // nothing of the box has no bricks): the boxes and the batches must be the same.
        batchTravel += st.MaxCorrection;
        return !(state.FieldBricked || state.FieldFollows) ||
          batchTravel < 0.5 * BrickReachSigmas * rec.Sigma;
      });
    for (const SweepStatistics& st : batchStats)
    {
      ++s;
      ++sweepCounter;
      ++rec.Sweeps;
      SweepRecord sr;
      sr.Sweep = sweepCounter;
      sr.Level = rec.Level;
      sr.Sigma = rec.Sigma;
      sr.Vertices = mesh.NumberOfPoints();
      sr.Triangles = mesh.NumberOfTriangles();
      sr.MeanCorrection = st.MeanCorrection;
      sr.MaxCorrection = st.MaxCorrection;
      this->Sweeps.push_back(sr);
      this->MaxOutsideVertices = std::max(this->MaxOutsideVertices, st.OutsideVertices);
      this->FinalOutsideVertices = st.OutsideVertices;
      if (this->OnSweep && !this->OnSweep(sr, mesh))
      {
        this->Stop = StopReason::Aborted;
        stop = true;
        break;
      }
      stall.Add(st);
    }
    if (!stop && !state.StartVolumes.empty())
    {
      this->Collapse = CollapsedObject(mesh, state.StartVolumes, state.VoxelVolume);
      stop = !this->Collapse.empty();
    }
    // A front level has its own rest (its fastest vertex) and cap. An open start has no volume
    // to tell stepping in place from slow drift that gains ground: its first level only.
    if (!stop && !rec.Converged && rec.FrontRest <= 0 && (rec.Level == 0 || state.ClosedStart) &&
      stall.Rests(mesh, s))
    {
      rec.Converged = true;
      rec.Stalled = true;
    }
    // Every process of a distributed solve reaches GoOn's reduction here, with or without a
    // progress callback of its own (a process without one votes to go on).
    // Never backwards: front levels come after the planned ones (their share stays at the top).
    const double fraction = std::max(this->ProgressReached,
      std::min(
        1.0, (rec.Level + std::min(1.0, double(s) / std::min(cap, 400))) / (plannedLevels + 1)));
    this->ProgressReached = fraction;
    if (!stop && !rec.Converged && (this->Progress || this->Distributed) &&
      !this->GoOn(!this->Progress || this->Progress(fraction)))
    {
      this->Aborted = true;
      this->Stop = StopReason::Aborted;
      stop = true;
    }
  }
  solver.SetContactBounds(nullptr);
  rec.FieldMisses =
    state.EarlierMisses + (field.Bricks ? field.Bricks->Misses() - state.MissesBase : 0);
  rec.FieldVoxels = state.FieldBox.NumberOfVoxels();
  if (P.MaxSweeps > 0 && sweepCounter >= P.MaxSweeps && !stop)
  {
    this->Warnings.push_back(
      "stopped after MaxSweeps (" + std::to_string(P.MaxSweeps) + ") sweeps");
    this->Stop = StopReason::MaxSweeps;
    stop = true; // no refinement after the budget
  }
  return stop;
}

void MultilevelSolver::ClearResults()
{
  this->Sweeps.clear();
  this->Levels.clear();
  this->Warnings.clear();
  this->ErrorIndicator.clear();
  this->Displacement.clear();
  this->ExternalForce.clear();
  this->MaxOutsideVertices = 0;
  this->FinalOutsideVertices = 0;
  this->InitialSubdivisions = 0;
  this->Aborted = false;
  this->Stop = StopReason::None;
  this->PlannedLevels = 0;
  this->SigmaChoice = InitialSigmaChoice();
  this->UsedRange[0] = this->UsedRange[1] = 0;
  this->ObjectRegions.clear();
  this->Contact.Reset();
  this->Bounds = ContactBounds();
  this->Crossings = 0;
  this->ProgressReached = 0.0;
  this->Collapse.clear();
}

bool MultilevelSolver::Start(
  const ImageView& image, TriangleMesh& mesh, RunState& state, std::string* error)
{
  const MultilevelParameters& P = this->Parameters;
  const ImageGeometry& geometry = image.Geometry;
  if (this->Distributed)
  {
    // Collective, first: an empty or invalid piece fails every process here; what follows
    // depends only on the mesh, the parameters and the whole image, the same on all of them.
    const std::string problem = CheckPieces(this->Piece, this->Reduce);
    if (!problem.empty())
    {
      *error = "distributed image: " + problem;
      return false;
    }
    state.LevelSolver.SetForceExchange(OwnerForceExchange(this->Piece, this->Reduce));
  }
  if (!image.Data || geometry.NumberOfVoxels() <= 0)
  {
    *error = "the volume is empty";
    return false;
  }
  if (mesh.Triangles.empty())
  {
    *error = "the initial surface has no triangles";
    return false;
  }
  if (!mesh.Objects.empty() &&
    (mesh.Objects.size() != mesh.Points.size() ||
      *std::min_element(mesh.Objects.begin(), mesh.Objects.end()) < 0))
  {
    *error = "the objects of the initial surface need one index >= 0 per point";
    return false;
  }
  // The voxel size (mean spacing) bounds how fine the mesh usefully gets.
  state.Voxel = geometry.MeanSpacing();
  this->Voxel = state.Voxel;
  std::string msg;
  if (!state.Refiner.Initialize(mesh, &msg))
  {
    *error = "the initial surface is not a manifold triangle mesh: " + msg;
    return false;
  }
  if (!this->ObjectSigmas(image, mesh, state.Sigma, error))
  {
    return false;
  }
  state.FirstSigma = state.Sigma;
  if (!this->CoarsenStart(mesh, state, error))
  {
    return false;
  }
  if (!this->PrepareStart(image, mesh, state.Refiner, state.Sigma, state.Region, error))
  {
    return false;
  }
  mesh.ExtendObjects(); // the points the start's subdivision added
#ifndef NDEBUG
  state.CheckTopology = true;
#else
  state.CheckTopology = P.CheckTopology;
#endif
  state.EulerStart = mesh.EulerCharacteristic();
  state.ClosedStart = mesh.IsClosed();
  state.StartVolumes = state.ClosedStart ? ObjectVolumes(mesh) : std::vector<double>();
  state.VoxelVolume = geometry.Spacing[0] * geometry.Spacing[1] * geometry.Spacing[2];
  state.LevelSolver.SetParameters(P.Solver);
  state.FieldParameters.EdgeWeight = P.EdgeWeight;
  state.FieldParameters.ImageWeight = P.ImageWeight;
  state.FieldParameters.NormalizePotential = true;
  state.FieldParameters.EdgeNormalization = P.EdgeNormalization;
  state.FieldParameters.NumberOfThreads = P.Solver.NumberOfThreads;
  return true;
}

bool MultilevelSolver::MakeField(const ImageView& image, const TriangleMesh& mesh, RunState& state,
  const VoxelBox& box, std::string* error)
{
  state.FieldMade = false;
  state.FieldBox = box;
  std::string msg;
  // Checked before it is made, the last field released first (docs/METHOD.md §9.6): the check
  // before the solve counts no field. Distributed, each process checks what it would hold, and
  // all agree.
  state.Field = ForceField();
  const double need = this->Distributed
    ? PieceFieldBytes(this->Piece, box, state.FieldParameters)
    : FieldBytes(box, image.Geometry, state.FieldParameters, &mesh);
  std::ostringstream what;
  what.precision(3);
  what << "The force field at sigma " << state.FieldParameters.Sigma << " (world units) over "
       << box.End[0] - box.Begin[0] << "x" << box.End[1] - box.Begin[1] << "x"
       << box.End[2] - box.Begin[2] << " voxels"
       << (this->Distributed ? " (this process's part)" : "");
  msg = MemoryShortfall(need, what.str());
  const double lacking =
    this->Distributed ? this->Reduce.Max(msg.empty() ? 0.0 : need) : (msg.empty() ? 0.0 : need);
  if (lacking > 0.0)
  {
    std::ostringstream other;
    other.precision(3);
    other << "another process's part of the force field at sigma " << state.FieldParameters.Sigma
          << " needs about " << lacking / (1024.0 * 1024.0 * 1024.0)
          << " GiB, more than its memory can give: make the volume smaller first (crop it to the "
             "object with Extract Subset / vtkExtractVOI, or resample it with vtkImageResample)";
    *error = msg.empty() ? other.str() : msg;
    return false;
  }
  // On the image's own grid a field only where the surface is (dsFieldBricks.h), following it
  // batch by batch (SolveLevel); distributed, each piece's part of it (dsPieceField.h).
  state.FieldBricked = FieldInBricks(box, image.Geometry, state.FieldParameters);
  bool computed = this->Distributed
    ? ComputePieceForce(
        this->Piece, box, state.FieldParameters, this->Reduce, state.Field, &msg, &mesh)
    : ComputeForceAtScale(image, box, state.FieldParameters, state.Field, &msg, &mesh);
  // A piece's own checks (a field not finite) can fail on one process alone: all agree, so that
  // none goes on to sweeps the others have left.
  if (this->Distributed && this->Reduce.Max(computed ? 0.0 : 1.0) > 0.0 && computed)
  {
    computed = false;
    msg = "another process's piece failed";
  }
  if (!computed)
  {
    *error = "scale-space force: " + msg;
    return false;
  }
  state.FieldMade = true;
  return true;
}

bool MultilevelSolver::FollowSurface(
  const ImageView& image, const TriangleMesh& mesh, RunState& state, LevelRecord& rec)
{
  // The box is made again once the surface comes within (reach - 1) sigma of its side: a batch
  // moves no vertex more than a sigma (SolveLevel), so the Gaussian's support around every
  // vertex stays inside the box, as on the later levels. The new box also takes in a quarter of
  // the surface's extent on every side: a surface growing from a click is boxed again a
  // logarithmic number of times, and the boxes together cost little more than the last.
  const ImageGeometry& geometry = image.Geometry;
  const double reach = FieldReach(this->Parameters.EdgeNormalization, state.Sigma);
  if (!state.FieldFollows || !state.FieldMade ||
    state.FieldBox.Contains(SurfaceNeighbourhood(mesh, geometry, reach - state.Sigma)))
  {
    return true;
  }
  const VoxelBox own = SurfaceNeighbourhood(mesh, geometry, 0.0);
  double extent = 0;
  for (int a = 0; a < 3; ++a)
  {
    extent = std::max(extent, (own.End[a] - own.Begin[a]) * geometry.Spacing[a]);
  }
  const VoxelBox box = SurfaceNeighbourhood(mesh, geometry, reach + FieldGrowthShare * extent);
  state.EarlierMisses += state.Field.Bricks ? state.Field.Bricks->Misses() - state.MissesBase : 0;
  std::string error;
  if (!this->MakeField(image, mesh, state, box, &error))
  {
    // A box grown past what the memory can give (MakeField's check), or a field not finite.
    // Every process fails alike (MakeField), and the run ends with the error.
    state.FieldError = "level " + std::to_string(rec.Level) +
      ": the force field could not follow the surface: " + error;
    state.FieldFollows = false;
    return false;
  }
  state.MissesBase = 0;
  ++rec.FieldBoxes;
  return true;
}

bool MultilevelSolver::SetUpLevel(
  const ImageView& image, TriangleMesh& mesh, RunState& state, LevelRecord& rec, std::string* error)
{
  const ImageGeometry& geometry = image.Geometry;
  const MultilevelParameters& P = this->Parameters;
  const double sigma = state.Sigma;
  mesh.ExtendObjects(); // the points refinement added
  // Force field at this level's sigma over the surface's neighbourhood (dsFieldGrid.h), rebuilt
  // when sigma changed or the surface needs more than it covers. The first level, whose surface
  // may travel far (grown by the region force), covers the whole image on a coarse grid (block
  // means: a small field); on the image's own grid its box follows the surface (FollowSurface),
  // covering the surface's neighbourhood and no more (docs/METHOD.md §9.7).
  state.FieldFollows = rec.Level == 0 && DecimationFactor(sigma, geometry) <= 1;
  const VoxelBox box = rec.Level == 0 && !state.FieldFollows
    ? VoxelBox::Whole(geometry)
    : SurfaceNeighbourhood(mesh, geometry, FieldReach(P.EdgeNormalization, sigma));
  if (!state.FieldMade || std::abs(state.FieldParameters.Sigma - sigma) > 1e-12 * sigma ||
    !state.FieldBox.Contains(box))
  {
    state.FieldParameters.Sigma = sigma;
    if (!this->MakeField(image, mesh, state, box, error))
    {
      return false;
    }
  }
  const double h = mesh.MeanEdgeLength();
  state.LevelSolver.SetMesh(&mesh);
  state.LevelSolver.SetForceField(&state.Field, P.ForceWeight * h * sigma);
  if (state.Region)
  {
    // The balloon brings the surface to its object at the coarse scales; as sigma shrinks
    // the edge force takes over the detail, so the region force shrinks with sigma (at full
    // strength it presses the surface into every narrow dark gap of the object).
    // A front level pushes the objects it follows at full strength: the parts of the object the
    // surface has not reached (a horn the fading force could not enter against the internal force
    // of its narrow tip); everywhere else the two-sided force of a click's competition range holds
    // the surface where the range ends (docs/METHOD.md §9.3). Several objects fade each by its own
    // sigma_0 (a click beside a large object keeps its force as long as it would alone).
    const bool own = this->StartSigmas.size() == this->ObjectRegions.size();
    const double decay = state.FrontLevel || own ? 1.0 : RegionFade(sigma, state.FirstSigma);
    // Distributed, each process samples its own piece (it owns the vertices it samples).
    std::vector<Solver::RegionModel> models = this->LevelRegionModels(state, sigma);
    state.LevelSolver.SetRegionForce(this->Distributed ? this->Piece.Image : image,
      std::move(models), decay * this->GetRegionWeight() * h);
  }
  rec.Sigma = sigma;
  rec.Vertices = mesh.NumberOfPoints();
  rec.Triangles = mesh.NumberOfTriangles();
  rec.MeanEdgeLength = h;
  // Near its rest the surface moves by about gamma h sigma d / w^2 per sweep, d its distance
  // from the rest and w the width of the edge in the potential: a tolerance of a fixed share of
  // h stops at d ~ tolerance w^2 / (gamma sigma), a fixed share of w only while w ~ sigma. Below
  // a few voxels w is wider than sigma (docs/METHOD.md §6.1): scaled by sigma / w, the
  // tolerance stops every level at the same share of its edge width.
  rec.Tolerance = P.ConvergenceTolerance * h * sigma / PotentialEdgeWidth(sigma, state.Voxel);
  return true;
}

void MultilevelSolver::EndSweeps(
  const Solver& solver, TriangleMesh& mesh, LevelRecord& rec, bool lastLevel)
{
  // Folds are smoothed on the delivered surface and after each level whose mesh resolves its
  // sigma (mean edge <= sigma), where the smoothed rings span about the scale the level sees.
  // On a coarser mesh two rings are most of the surface: smoothing flattened a 105-vertex
  // seed across the torus's hole, while the finer levels undo its folds (docs/METHOD.md §9.4).
  if (lastLevel || rec.MeanEdgeLength <= rec.Sigma)
  {
    this->SmoothFolds(mesh, rec);
  }
  this->ErrorIndicator = solver.ErrorIndicator();
  this->Displacement = solver.Displacement();
  this->ExternalForce = solver.ExternalForceMagnitude();
}

bool MultilevelSolver::MidpointLevelWanted(const RunState& state) const
{
  return state.Region &&
    std::any_of(this->ObjectRegions.begin(), this->ObjectRegions.end(),
      [](const ObjectRegion& o) { return o.On && o.FollowsFront; });
}

bool MultilevelSolver::AtSigmaFloor(const RunState& state) const
{
  return this->Parameters.HierarchicalSigma &&
    !(state.Sigma > SigmaFloorVoxels * state.Voxel * (1 + 1e-9));
}

bool MultilevelSolver::ScheduleEndsAt(const RunState& state, int level) const
{
  return this->AtSigmaFloor(state) || level >= std::max(0, this->Parameters.MaxLevels);
}

bool MultilevelSolver::RunLevels(
  const ImageView& image, TriangleMesh& mesh, RunState& state, std::string* error)
{
  const MultilevelParameters& P = this->Parameters;
  const int maxLevels = std::max(0, P.MaxLevels);
  // Progress is reported against the levels a hierarchical run takes to sigma's floor (halving
  // from sigma_0 to SigmaFloorVoxels), within the cap.
  this->PlannedLevels = maxLevels;
  const double sigmaFloor = SigmaFloorVoxels * state.Voxel;
  if (P.HierarchicalSigma && state.Sigma > sigmaFloor)
  {
    int steps = 0;
    for (double s = state.Sigma; s > sigmaFloor * (1 + 1e-9) && steps < maxLevels; ++steps)
    {
      s = NextHierarchicalSigma(s, sigmaFloor);
    }
    this->PlannedLevels = steps;
  }
  int frontLevels = 0; // taken so far, beyond the cap of MaxLevels
  for (int level = 0;; ++level)
  {
    LevelRecord rec;
    rec.Level = level;
    if (!this->SetUpLevel(image, mesh, state, rec, error))
    {
      return false;
    }
    rec.Front = state.FrontLevel;
    rec.FrontRest = state.FrontLevel ? FrontRestVoxels * state.Voxel : 0.0;
    const bool stop = this->SolveLevelKeptApart(image, mesh, state, rec);
    if (!state.FieldError.empty())
    {
      *error = state.FieldError;
      return false;
    }
    // With the hierarchical sigma, the level solved at sigma's floor (SigmaFloorVoxels) is the
    // last: further levels would only refine the mesh for detail the image does not show
    // (a start near its object reaches the floor after a few halvings).
    const bool atFloor = this->AtSigmaFloor(state);
    // At the floor the levels go on while the object still lies beyond part of the surface (a
    // thin part not yet followed to its end, docs/METHOD.md §9.3): front levels, beyond
    // MaxLevels, at most MaxFrontLevels.
    state.Front.clear();
    state.FrontObjects.clear();
    if (atFloor && !stop && !state.MidpointLevel && !state.FrontCrossed &&
      frontLevels < MaxFrontLevels && state.Region &&
      std::any_of(this->ObjectRegions.begin(), this->ObjectRegions.end(),
        [](const ObjectRegion& o) { return o.On && o.FollowsFront; }))
    {
      // A front of more than FrontShare of an object's triangles is no thin part left behind but
      // an object that runs on beyond its surface: pushing on would only spread it (FrontOf).
      state.Front = this->FrontOf(
        mesh, this->FrontTriangles(image, mesh), state.FrontObjects, state.FrontHistory);
      this->WarnOfGrowingFront(mesh, state);
    }
    state.FrontLevel = !state.Front.empty();
    frontLevels += state.FrontLevel ? 1 : 0;
    const bool scheduleEnds =
      stop || (!state.FrontLevel && (level - frontLevels >= maxLevels || atFloor));
    // A click's surface rests once more at the floor, at the local midpoint (docs/METHOD.md
    // §9.3, "A click's last level"): the same mesh and sigma, one level beyond the schedule.
    const bool midpointNext =
      scheduleEnds && !stop && atFloor && !state.MidpointLevel && this->MidpointLevelWanted(state);
    const bool lastLevel = scheduleEnds && !midpointNext;
    this->EndSweeps(state.LevelSolver, mesh, rec, lastLevel);
    if (lastLevel)
    {
      this->Stop = stop ? this->Stop : (atFloor ? StopReason::SigmaFloor : StopReason::MaxLevels);
      this->Levels.push_back(rec);
      break;
    }
    if (midpointNext)
    {
      this->Levels.push_back(rec);
      state.MidpointLevel = true;
      continue;
    }
    bool refined = false;
    if (!this->RefineLevel(mesh, state, rec, refined, error))
    {
      return false;
    }
    // The next level's sigma. Even when nothing was refined (nothing marked, the marked
    // triangles already below a voxel, or the vertex budget reached) the schedule goes on
    // with a smaller sigma: otherwise the surface would rest where the coarse, blurred
    // edge lies, voxels off the boundary. Sigma stops at its floor, below which the
    // image has nothing more to show; a level that would change neither mesh nor sigma
    // ends the run.
    const double sigma = state.Sigma;
    const double nextSigma = P.HierarchicalSigma ? NextHierarchicalSigma(sigma, sigmaFloor) : sigma;
    if (!refined && !(nextSigma < sigma) && !state.FrontLevel)
    {
      if (!(rec.MeanEdgeLength <= rec.Sigma)) // else EndSweeps has smoothed it
      {
        this->SmoothFolds(mesh, this->Levels.back()); // this level's surface is delivered
      }
      this->Stop = StopReason::NoDetail;
      break;
    }
    state.Sigma = nextSigma;
  }
  return true;
}

int MultilevelSolver::DistributedGhostVoxels(
  const MultilevelParameters& p, const ImageGeometry& whole, int a)
{
  double sigma = p.Sigma > 0 ? p.Sigma
    : p.SigmaFraction > 0    ? p.SigmaFraction * whole.MeanExtent()
    : p.HierarchicalSigma    ? whole.MeanExtent() / 6.0
                             : ConstantSigmaVoxels * whole.MeanSpacing();
  // Every level's sigma lies in (0, sigma] (hierarchical: the levels halve it, and sigma_0 from
  // the start is at most extent / 6; else sigma alone). The coarse levels need twice their
  // block size (dsPieceField.h), at most that of sigma; the fine ones one layer with the
  // recursive Gaussian, whose state passes from piece to piece (dsPieceGaussian.h), and the
  // sampled one's radius and one below 3 voxels, at most that of just under 3 voxels (or of
  // sigma). So the ghosts are bounded without knowing sigma_0. The probe of sigma_0 from the
  // start needs ghosts of its own.
  const bool fromStart = !(p.Sigma > 0) && !(p.SigmaFraction > 0) && p.HierarchicalSigma;
  int ghost = fromStart ? InitialSigmaProbeGhostVoxels(whole, a) : 0;
  const int f = DecimationFactor(sigma, whole);
  ghost = std::max(ghost, f > 1 ? 2 * f : PieceGhostVoxels(sigma, whole, a));
  if (p.HierarchicalSigma)
  {
    // In voxels: a world sigma just under 3 spacings can divide back to 3.0 (spacing 1.05)
    // and read as recursive, one layer.
    const double sampled =
      std::min(sigma / whole.Spacing[a], std::nextafter(GaussianRecursiveFromSigmaVoxels, 0.0));
    ghost = std::max(ghost, FineGhostVoxels(sampled));
  }
  // A click's classes are told from their blends along ramps of a few voxels
  // (dsClickCompetition.h).
  ghost = std::max(ghost, BlendReachVoxels);
  return std::min(ghost, whole.Dimensions[a]);
}

bool MultilevelSolver::Run(const ImageView& image, TriangleMesh& mesh, std::string* error)
{
  this->ClearResults();
  std::string msg;
  RunState state;
  if (!this->Start(image, mesh, state, &msg) || !this->CheckStartsApart(mesh, &msg) ||
    !this->RunLevels(image, mesh, state, &msg) || !(msg = this->Collapse).empty())
  {
    this->Stop = StopReason::None;
    if (error)
    {
      *error = msg;
    }
    return false;
  }
  if (mesh.NumberOfObjects() > 1)
  {
    this->Crossings = CountCrossingPairs(mesh);
    if (this->Crossings > 0)
    {
      this->Warnings.push_back(std::to_string(this->Crossings) +
        " pairs of triangles of different objects intersect on the result");
    }
  }
  if (this->Progress)
  {
    this->Progress(1.0);
  }
  return true;
}

} // namespace dsurf
