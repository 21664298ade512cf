// SPDX-License-Identifier: BSD-3-Clause
#include "dsMultilevel.h"

#include "dsGaussianSmoother.h"

#include "dsFieldBricks.h"
#include "dsFrontGrid.h"
#include "dsMemory.h"
#include "dsObjects.h"
#include "dsPieceInitialSigma.h"
#include "dsRegion.h"
#include "dsSelfIntersectionCount.h"
#include "dsThreads.h"
#include "dsUntangle.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <sstream>
#include <unordered_set>

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

std::vector<char> MultilevelSolver::MarkTriangles(
  const TriangleMesh& mesh, const std::vector<double>& estimator, double threshold, bool uniform)
{
  std::vector<char> marks(mesh.Triangles.size(), uniform ? 1 : 0);
  if (uniform || estimator.size() != mesh.Points.size())
  {
    return marks;
  }
  for (size_t t = 0; t < marks.size(); ++t)
  {
    const auto& tri = mesh.Triangles[t];
    const double e = (estimator[tri[0]] + estimator[tri[1]] + estimator[tri[2]]) / 3.0;
    marks[t] = e > threshold ? 1 : 0;
  }
  return marks;
}

bool MultilevelSolver::FirstSigma(
  const ImageView& image, const TriangleMesh& mesh, double& sigma, std::string* error)
{
  const ImageGeometry& geometry = image.Geometry;
  const MultilevelParameters& P = this->Parameters;
  const double paper = geometry.MeanExtent() / 6.0;
  if (P.Sigma > 0)
  {
    sigma = P.Sigma;
  }
  else if (P.SigmaFraction > 0)
  {
    sigma = P.SigmaFraction * geometry.MeanExtent();
  }
  else if (!P.HierarchicalSigma)
  {
    // The constant mode is the paper's small sigma (docs/METHOD.md §6.6): it is chosen for a weak
    // boundary next to a strong one, which a sigma that never shrinks from extent / 6 or from
    // the start's distance would blur together.
    sigma = ConstantSigmaVoxels * geometry.MeanSpacing();
  }
  else if (this->Distributed
      ? !ChoosePieceInitialSigma(this->Piece, mesh, paper, P.Solver.NumberOfThreads, this->Reduce,
          this->SigmaChoice, error)
      : !ChooseInitialSigma(image, mesh, paper, P.Solver.NumberOfThreads, this->SigmaChoice, error))
  {
    return false;
  }
  else
  {
    sigma = this->SigmaChoice.Sigma;
  }
  if (!(sigma > 0) || !std::isfinite(sigma))
  {
    *error = "the initial sigma must be positive";
    return false;
  }
  return true;
}

bool MultilevelSolver::ObjectSigmas(
  const ImageView& image, const TriangleMesh& mesh, double& sigma, std::string* error)
{
  // One object: sigma_0 of the whole start. Several: each object's own (its start's distance
  // to its edges), and the hierarchy begins at the largest, so that every object starts at a
  // sigma that reaches its edges; each is subdivided to its own (PrepareStart).
  this->StartSigmas.clear();
  if (mesh.NumberOfObjects() == 1)
  {
    return this->FirstSigma(image, mesh, sigma, error);
  }
  InitialSigmaChoice largest;
  sigma = 0;
  for (int o = 0; o < mesh.NumberOfObjects(); ++o)
  {
    double own = 0;
    if (!this->FirstSigma(image, ObjectSurface(mesh, o), own, error))
    {
      return false;
    }
    this->StartSigmas.push_back(own);
    if (own > sigma)
    {
      sigma = own;
      largest = this->SigmaChoice;
    }
  }
  this->SigmaChoice = largest;
  return true;
}

void MultilevelSolver::GivenRange(const TriangleMesh& mesh, int object, double range[2]) const
{
  const MultilevelParameters& P = this->Parameters;
  range[0] = P.IntensityRange[0];
  range[1] = P.IntensityRange[1];
  const std::vector<double>& table = P.ObjectIntensityRanges;
  for (std::size_t i = 0; i + 2 < table.size() && object < static_cast<int>(mesh.ObjectIds.size());
       i += 3)
  {
    if (table[i] == static_cast<double>(mesh.ObjectIds[object]) && table[i + 1] < table[i + 2])
    {
      range[0] = table[i + 1];
      range[1] = table[i + 2];
    }
  }
}

bool MultilevelSolver::ObjectRange(const ImageView& image, const TriangleMesh& mesh,
  double firstSigma, const std::string& which, const double given[2], ObjectRegion& model)
{
  const ImageGeometry& geometry = image.Geometry;
  double lo = given[0], hi = given[1];
  if (!std::isfinite(lo) || !std::isfinite(hi) || !std::isfinite(hi - lo))
  {
    this->Warnings.push_back(
      "the region force" + which + " is off: the intensity range must be finite");
    return false;
  }
  if (!(lo < hi) && (StartSpansImage(geometry, mesh) || !mesh.IsClosed()))
  {
    // A box around the whole volume has no outside to tell its object from, an open surface
    // no inside: without a given range the region force stays off, as documented, without a
    // warning (the paper's edge-only method; the output then has no IntensityRange field).
    return false;
  }
  if (!(lo < hi))
  {
    RangeEstimate estimate;
    std::string msg;
    const double reach = CompetitorReachSigmas * firstSigma;
    bool estimated = false;
    // The estimate's histograms are counted on the solver's threads.
    vtkSMPTools::LocalScope(
      vtkSMPTools::Config{
        ResolveThreads(this->Parameters.Solver.NumberOfThreads), "STDThread", false },
      [&]
      {
        estimated = this->Distributed
          ? EstimatePieceIntensityRange(this->Piece, mesh, 1.0, this->Reduce, estimate, &msg, reach)
          : EstimateIntensityRange(image, mesh, 1.0, estimate, &msg, reach);
      });
    if (!estimated)
    {
      this->Warnings.push_back("the region force" + which +
        " is off: no intensity range was given and none could be estimated (" + msg + ")");
      return false;
    }
    lo = estimate.Range[0];
    hi = estimate.Range[1];
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi))
    {
      this->Warnings.push_back("the region force" + which +
        " is off: the estimated intensity range is empty or not finite");
      return false;
    }
    // Without a background to compare with (a click inside one region), the range's end is
    // not where the boundary lies: the region force only grows the surface through its
    // region, and the edge force finds the boundary beyond.
    model.OutwardOnly = !estimate.Contrast;
    model.FollowsFront = estimate.Classes > 1 && estimate.Contrast;
  }
  const bool matching = this->Distributed
    ? CountPieceVoxelsInRange(this->Piece, lo, hi, this->Reduce) > 0
    : AnyVoxelInRange(image, lo, hi);
  if (!matching)
  {
    this->Warnings.push_back("the region force" + which + " is off: the intensity range [" +
      std::to_string(lo) + ", " + std::to_string(hi) + "] matches no voxel of the image");
    return false;
  }
  model.Low = lo;
  model.High = hi;
  model.On = true;
  return true;
}

bool MultilevelSolver::RegionRange(
  const ImageView& image, const TriangleMesh& mesh, double firstSigma)
{
  // One object: its range from the whole start; several: each from its own start surface
  // (its own click, its own seed), so each region competes with what lies around it.
  const int objects = mesh.NumberOfObjects();
  this->ObjectRegions.assign(objects, ObjectRegion());
  bool any = false;
  for (int o = 0; o < objects; ++o)
  {
    ObjectRegion& model = this->ObjectRegions[o];
    // Each click looks for its competitors within reach of its own sigma_0.
    const double own =
      o < static_cast<int>(this->StartSigmas.size()) ? this->StartSigmas[o] : firstSigma;
    double given[2];
    this->GivenRange(mesh, o, given);
    any = (objects == 1 ? this->ObjectRange(image, mesh, firstSigma, "", given, model)
                        : this->ObjectRange(image, ObjectSurface(mesh, o), own,
                            " of object " + std::to_string(o), given, model)) ||
      any;
  }
  for (const ObjectRegion& model : this->ObjectRegions)
  {
    if (model.On)
    {
      this->UsedRange[0] = model.Low; // the first object's, for the IntensityRange field
      this->UsedRange[1] = model.High;
      break;
    }
  }
  return any;
}

namespace
{
/// The start's subdivision (PrepareStart) of one surface: its elongated edges split, then
/// uniform 1 -> 4 subdivisions while its mean edge exceeds sqrt 2 x target.
bool SubdivideStart(TriangleMesh& mesh, double target, long long maxVertices, int& subdivisions,
  bool& subdivided, std::string* error)
{
  // Elongated triangles first (a long box's faces: 12 x 84 voxels, 3 x 21 after the splits
  // below): at their creases the umbrella points along the crease, §5's rule turns the
  // region force into a slide along it, and the faces overtake the crease until they fold
  // (docs/METHOD.md §7). Their edges longer than sqrt 2 x the target and twice the shortest
  // edge of a triangle they border are halved; a start of about isotropic triangles is left
  // as it is.
  std::string msg;
  const int split = mesh.SplitElongatedEdges(std::sqrt(2.0) * target, maxVertices, &msg);
  if (split < 0)
  {
    *error = "splitting the initial surface's elongated triangles failed: " + msg;
    return false;
  }
  subdivided = split > 0;
  while (
    mesh.MeanEdgeLength() > std::sqrt(2.0) * target && 4LL * mesh.NumberOfPoints() <= maxVertices)
  {
    if (!mesh.SubdivideUniformly(&msg))
    {
      *error = "subdividing the initial surface failed: " + msg;
      return false;
    }
    ++subdivisions;
    subdivided = true;
  }
  return true;
}

/// `part` (points and triangles) appended to `all` as object `object`.
void AppendObject(TriangleMesh& all, const TriangleMesh& part, int object)
{
  const int offset = all.NumberOfPoints();
  all.Points.insert(all.Points.end(), part.Points.begin(), part.Points.end());
  all.Objects.resize(all.Points.size(), object);
  for (const auto& t : part.Triangles)
  {
    all.Triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
  }
}
} // namespace

bool MultilevelSolver::PrepareRegions(const ImageView& image, TriangleMesh& mesh,
  RedGreenRefiner& refiner, double sigma, bool& region, std::string* error)
{
  const MultilevelParameters& P = this->Parameters;
  std::string msg;
  if (P.RegionWeight > 0)
  {
    // The region force pushes along the outward normal (and the range estimate looks just
    // outside the start): every closed piece must face out.
    const int flipped = mesh.OrientPiecesOutward();
    if (flipped > 0)
    {
      this->Warnings.push_back("the region force needs outward normals: " +
        std::to_string(flipped) + " triangle(s) of inward-oriented pieces were reversed");
      if (!refiner.Initialize(mesh, &msg))
      {
        *error = "the reoriented initial surface is not a manifold triangle mesh: " + msg;
        return false;
      }
    }
  }
  region = P.RegionWeight > 0 && this->RegionRange(image, mesh, sigma);
  return true;
}

bool MultilevelSolver::PrepareStart(const ImageView& image, TriangleMesh& mesh,
  RedGreenRefiner& refiner, double sigma, bool& region, std::string* error)
{
  const ImageGeometry& geometry = image.Geometry;
  const MultilevelParameters& P = this->Parameters;
  const double voxel = geometry.MeanSpacing();
  std::string msg;
  if (!this->PrepareRegions(image, mesh, refiner, sigma, region, error))
  {
    return false;
  }
  if (P.SubdivideInitialSurface)
  {
    // Uniform 1 -> 4 subdivision at the midpoints keeps the start shape; every vertex is N,
    // and the result is a fresh level-0 mesh for the hierarchy.
    // Edges shorter than two voxels resolve nothing more, whatever sigma is. A split halves
    // the edges, so the split whose mean edge is nearest the target (within a factor sqrt 2
    // either way) is taken: stopping at the first below it would quadruple the start's
    // triangles for a sigma_0 a little smaller.
    const double target = std::max(InitialEdgeSigmaRatio * sigma, 2.0 * voxel);
    // Several objects are subdivided one by one, each to its own edges: a seed of picks around
    // a large part has edges tens of voxels long, a click's sphere edges of a voxel, and the
    // mean of both would leave the large one as it is.
    bool subdivided = false;
    if (mesh.NumberOfObjects() == 1)
    {
      int subdivisions = 0;
      if (!SubdivideStart(mesh, target, P.MaxVertices, subdivisions, subdivided, error))
      {
        return false;
      }
      this->InitialSubdivisions = subdivisions;
    }
    else
    {
      TriangleMesh all;
      for (int o = 0; o < mesh.NumberOfObjects(); ++o)
      {
        TriangleMesh part = ObjectSurface(mesh, o);
        int subdivisions = 0;
        bool split = false;
        const double own = std::max(InitialEdgeSigmaRatio * this->StartSigmas[o], 2.0 * voxel);
        if (!SubdivideStart(
              part, own, P.MaxVertices / mesh.NumberOfObjects(), subdivisions, split, error))
        {
          return false;
        }
        this->InitialSubdivisions = std::max(this->InitialSubdivisions, subdivisions);
        subdivided = subdivided || split;
        AppendObject(all, part, o);
      }
      if (subdivided)
      {
        all.ObjectIds = mesh.ObjectIds;
        mesh = std::move(all);
      }
    }
    if (subdivided)
    {
      if (!refiner.Initialize(mesh, &msg))
      {
        *error = "the subdivided initial surface is not a manifold triangle mesh: " + msg;
        return false;
      }
    }
  }
  return true;
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
  /// A level's sweeps made the surface cross itself: from that level on, its parts are kept
  /// apart (SolveLevelKeptApart).
  bool KeepApart = false;
  /// A front level made such a surface cross itself or turned an object inside out: its moves
  /// were undone and no front level follows (SolveFrontLevelOfKeptApart).
  bool FrontCrossed = false;
};

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

bool MultilevelSolver::CoarsenStart(TriangleMesh& mesh, RunState& state, std::string* error)
{
  // A start far finer than sigma_0 (a million-triangle iso-surface) moves by a fraction of its
  // tiny edges per sweep: level 0 alone took the 2000-sweep cap (docs/METHOD.md §9.5). The
  // hierarchy starts coarse instead, and refines again where the image has detail.
  // MaxLevels 0 asks for one level on the given mesh: nothing would refine a copy back.
  // Several objects are not coarsened: the copy would have to keep each one apart.
  if (!this->Coarsen || this->Parameters.MaxLevels < 1 || mesh.NumberOfObjects() > 1 ||
    mesh.NumberOfTriangles() <= CoarsenAboveTriangles ||
    !(mesh.MeanEdgeLength() < 0.5 * state.Sigma))
  {
    return true;
  }
  TriangleMesh coarse;
  std::string msg;
  const bool kept = this->Coarsen(mesh, state.Sigma, coarse) && coarse.BuildTopology(&msg) &&
    coarse.IsClosed() == mesh.IsClosed() &&
    coarse.EulerCharacteristic() == mesh.EulerCharacteristic() && coarse.IsConsistentlyOriented() &&
    (coarse.SignedVolume() > 0) == (mesh.SignedVolume() > 0);
  if (!kept)
  {
    this->Warnings.push_back("a coarse copy of the start (" +
      std::to_string(mesh.NumberOfTriangles()) +
      " triangles) would change its topology: it is solved as given, which can take long");
    return true;
  }
  this->Warnings.push_back("the start's " + std::to_string(mesh.NumberOfTriangles()) +
    " triangles (mean edge " + std::to_string(mesh.MeanEdgeLength()) + ") were coarsened to " +
    std::to_string(coarse.NumberOfTriangles()) + " (mean edge " +
    std::to_string(coarse.MeanEdgeLength()) + ", about sigma_0) for the first level");
  mesh = std::move(coarse);
  if (!state.Refiner.Initialize(mesh, &msg))
  {
    *error = "the coarsened initial surface is not a manifold triangle mesh: " + msg;
    return false;
  }
  return true;
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

std::vector<Solver::RegionModel> MultilevelSolver::LevelRegionModels(
  const RunState& state, double sigma) const
{
  const bool own = this->StartSigmas.size() == this->ObjectRegions.size();
  std::vector<Solver::RegionModel> models;
  for (std::size_t o = 0; o < this->ObjectRegions.size(); ++o)
  {
    const ObjectRegion& r = this->ObjectRegions[o];
    Solver::RegionModel m;
    m.On = r.On;
    m.Low = r.Low;
    m.High = r.High;
    m.OutwardOnly = r.OutwardOnly;
    // On a front level the objects whose front is not followed keep their fade.
    const bool followed = o < state.FrontObjects.size() && state.FrontObjects[o];
    const double fade = RegionFade(sigma, own ? this->StartSigmas[o] : state.FirstSigma);
    m.Scale = state.FrontLevel ? (followed ? 1.0 : fade) : (own ? fade : 1.0);
    // A click's seed lies inside its object, in the basin of the face nearest it, which its
    // sigma_0 was chosen to span: while sigma is that large (the object's first levels, its
    // force not yet faded) that edge pulls the seed's far side back across the object's own
    // voxels. Smaller sigmas rest on the boundary, where the edge must hold; with a constant
    // sigma nothing fades and the rule never applies (docs/METHOD.md §9.3).
    m.DropInwardEdgePull =
      r.FollowsFront && !state.FrontLevel && this->Parameters.HierarchicalSigma && fade >= 1.0;
    m.MidpointVoxel = state.MidpointLevel && r.FollowsFront ? state.Voxel : 0.0;
    models.push_back(m);
  }
  return models;
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
    state.LevelSolver.SetRegionForce(
      this->Distributed ? this->Piece.Image : image, std::move(models), decay * P.RegionWeight * h);
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

double RegionFade(double sigma, double firstSigma)
{
  return std::min(1.0, sigma / firstSigma);
}

double UnsplitEdgeLength(double voxel, double sigma, double firstSigma, bool region)
{
  // Adaptively, triangles whose edges are all shorter than a voxel are not split again: the
  // image has no finer detail for their children to follow. With the region force, nor are
  // triangles whose edges are all shorter than this level's sigma: the image at sigma shows
  // nothing finer, and the next level (sigma / 2) is still sampled at least once per sigma.
  // The region force carries the surface far (a clicked 5 mm seed grows ~14-fold), so its
  // edges follow the growth, not sigma; at a coarse sigma the estimator, a distance in voxels,
  // marks nearly everything and each split of such a mesh multiplies vertices the image cannot
  // use. Once the force has faded the edge force holds the surface, and the bound doubles
  // (docs/METHOD.md §9.3). Without the region force the schedule is the paper's: the box
  // shrunk onto the cube phantom has edges near sigma too, and its early splits are what
  // resolve its corners.
  if (!region)
  {
    return voxel;
  }
  // The 1e-9: sigma_0 / 8 reached by three halvings is exact, but a sigma_0 / 8 written by hand
  // (or a ratio rounded once) must count as faded too.
  const bool faded = RegionFade(sigma, firstSigma) <= RegionFadedShare * (1 + 1e-9);
  return std::max(voxel, (faded ? FadedEdgeSigmaRatio : 1.0) * sigma);
}

namespace
{
double LongestEdge(const TriangleMesh& mesh, std::size_t t)
{
  const auto& tri = mesh.Triangles[t];
  double longest = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    longest = std::max(longest, Norm(mesh.Points[tri[(k + 1) % 3]] - mesh.Points[tri[k]]));
  }
  return longest;
}
} // namespace

std::vector<char> MultilevelSolver::MarkForRefinement(const TriangleMesh& mesh,
  const LevelRecord& rec, double voxel, double unsplit, const std::vector<char>& front) const
{
  const MultilevelParameters& P = this->Parameters;
  // The front (docs/METHOD.md §9.3): after sigma's floor only the front is refined (whatever
  // UniformRefinement says), every triangle with a corner on a front triangle down to half a
  // voxel (FrontEdgeVoxels), whatever its internal force, so the front fits into a horn or a
  // tube as narrow as the image shows. The rest of the surface was done at the floor, and the
  // estimator would mark its corners and edges again at every front level.
  if (!front.empty())
  {
    std::vector<char> marks(mesh.NumberOfTriangles(), 0);
    for (int t = 0; t < mesh.NumberOfTriangles(); ++t)
    {
      const auto& tri = mesh.Triangles[t];
      marks[t] = (front[tri[0]] || front[tri[1]] || front[tri[2]]) &&
          LongestEdge(mesh, t) > FrontEdgeVoxels * voxel
        ? 1
        : 0;
    }
    return marks;
  }
  // UniformRefinement splits everything, as asked; adaptively, a triangle whose edges are all
  // shorter than `unsplit` (UnsplitEdgeLength) is not split.
  // Detail is present where a large internal force balances an equal external one
  // (docs/METHOD.md §6.2). The external force is F = h sigma (-grad P) (§6b), which grows as
  // about h d / sigma with the distance d from the edge it pulls to: at rest the estimator
  // gamma |internal| (Solver::ErrorIndicator) thus says that the surface rests
  // d = |internal| sigma / h from where the image alone would put it. The threshold is on d in
  // voxels, the same at every level and resolution.
  const double scale = P.Solver.Gamma * rec.MeanEdgeLength / rec.Sigma;
  std::vector<char> marks = MarkTriangles(
    mesh, this->ErrorIndicator, P.RefinementThreshold * voxel * scale, P.UniformRefinement);
  for (size_t t = 0; t < marks.size() && !P.UniformRefinement; ++t)
  {
    if (marks[t])
    {
      if (LongestEdge(mesh, t) < unsplit)
      {
        marks[t] = 0;
      }
    }
  }
  return marks;
}

bool MultilevelSolver::Refine(TriangleMesh& mesh, RunState& state, const std::vector<char>& marks,
  Prolongation prolongation, bool& refined, std::string* error)
{
  // Several objects: a green pair refined red gets triangles that cut across its crease, off
  // the surface by the crease's bend, which within the clearance could make two objects cross;
  // such a refinement is undone (docs/METHOD.md §9.9). Objects never cross before it (see
  // SmoothFolds): any crossing pair is the refinement's.
  const bool several = mesh.NumberOfObjects() > 1;
  const TriangleMesh before = several ? mesh : TriangleMesh();
  const RedGreenRefiner refinerBefore = several ? state.Refiner : RedGreenRefiner();
  LevelRecord& rec = this->Levels.back();
  rec.Refinement = state.Refiner.Refine(mesh, marks, prolongation);
  if (!rec.Refinement.Ok)
  {
    *error = "refinement failed: " + rec.Refinement.Error;
    return false;
  }
  mesh.ExtendObjects();
  if (several && CountCrossingPairs(mesh) > 0)
  {
    mesh = before;
    state.Refiner = refinerBefore;
    rec.Refinement = RefinementCounts();
    rec.MarkedTriangles = 0;
    this->Warnings.push_back("the refinement after level " + std::to_string(rec.Level) +
      " was undone: it would have made two objects cross");
    refined = false;
  }
  return true;
}

bool MultilevelSolver::RefineLevel(
  TriangleMesh& mesh, RunState& state, LevelRecord& rec, bool& refined, std::string* error)
{
  const MultilevelParameters& P = this->Parameters;
  const std::vector<char> marks = this->MarkForRefinement(mesh, rec, state.Voxel,
    UnsplitEdgeLength(state.Voxel, rec.Sigma, state.FirstSigma, state.Region), state.Front);
  std::unordered_set<int> splitEdges;
  for (size_t t = 0; t < marks.size(); ++t)
  {
    if (marks[t])
    {
      ++rec.MarkedTriangles;
      for (int e : mesh.TriangleEdges[t])
      {
        splitEdges.insert(e);
      }
    }
  }
  // The vertex budget: each split edge adds a vertex.
  refined = rec.MarkedTriangles > 0;
  if (refined &&
    static_cast<long long>(mesh.NumberOfPoints()) + static_cast<long long>(splitEdges.size()) >
      P.MaxVertices)
  {
    if (!state.BudgetWarned)
    {
      this->Warnings.push_back("refinement stopped at level " + std::to_string(rec.Level) +
        ": the next step would exceed MaxVertices (" + std::to_string(P.MaxVertices) +
        "); the remaining levels only decrease sigma");
      state.BudgetWarned = true;
    }
    refined = false;
    rec.MarkedTriangles = 0;
  }
  this->Levels.push_back(rec);
  if (!refined)
  {
    return true;
  }
  // Several objects, and one kept off itself (the region force on: SelfContact), refine at edge
  // midpoints: the surface keeps its shape (but where a green pair turns red, which Refine checks
  // for several objects), so a refinement does not bring two sheets nearer than their sweeps did
  // (a butterfly point can bulge out by a share of the edge, through a sheet resting the
  // clearance away; dsContact.h). With butterfly points a Colin27 click kept 104 intersecting
  // pairs where midpoints left none.
  const Prolongation prolongation =
    P.ButterflyProlongation && mesh.NumberOfObjects() == 1 && !state.KeepApart
    ? Prolongation::Butterfly
    : Prolongation::Linear;
  if (!this->Refine(mesh, state, marks, prolongation, refined, error))
  {
    return false;
  }
  if (!refined)
  {
    return true;
  }
  std::string msg;
  if (state.CheckTopology &&
    (!CheckTopologyInvariants(mesh, state.EulerStart, state.ClosedStart, &msg) ||
      state.Refiner.CountTVertices(mesh) != 0))
  {
    *error = "refinement broke a topology invariant at level " + std::to_string(rec.Level + 1) +
      ": " + (msg.empty() ? std::string("T-vertex") : msg);
    return false;
  }
  return true;
}

bool MultilevelSolver::SolveFrontLevelOfKeptApart(
  const ImageView& image, TriangleMesh& mesh, RunState& state, LevelRecord& rec)
{
  // A surface already kept apart has met itself around a gap of its object (a sinus's bony
  // septa, docs/METHOD.md §9.3). A front level pushes at the floor's sigma with the region force
  // at full strength and is not kept apart (SolveLevelKeptApart): where it made such a surface
  // cross itself, it pushed through its own other side, not into a thin part (a click in a
  // head CT's sphenoid sinus: 0 crossing pairs before its first front level, 130 after and 71
  // at the end, or, from the committed click, a surface inside out). That level's moves are
  // undone, also when they turned an object inside out (a collapse), and the front is followed
  // no further; kept apart, it ran all 64 front levels (37 s against 1.6 s) and never ended.
  const std::vector<Vec3> start = mesh.Points;
  const int crossingBefore = CountSelfIntersections(mesh);
  const bool stop = this->SolveLevel(image, mesh, state, rec);
  const bool collapsed = !this->Collapse.empty();
  if (collapsed || CountSelfIntersections(mesh) > crossingBefore)
  {
    mesh.Points = start;
    state.FrontCrossed = true;
    this->Collapse.clear();
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
  // walls of a horn face each other all along it, and horns did not fold), nor several objects,
  // whose folds within one object are smoothed as before (solved again, the engine phantom's
  // pistons of TestSeveralObjectsMeet ended 0.51 voxel from their boundaries, 0.42 without).
  // Every process holds the whole mesh, so every process decides alike.
  const bool watch =
    state.Region && !state.FrontLevel && !state.KeepApart && mesh.NumberOfObjects() == 1;
  this->SelfContact = state.Region && !state.FrontLevel && state.KeepApart;
  if (state.FrontLevel && state.KeepApart)
  {
    return this->SolveFrontLevelOfKeptApart(image, mesh, state, rec);
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
      state.Front = this->FrontOf(mesh, this->FrontTriangles(image, mesh), state.FrontObjects);
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

namespace
{
/// The region of triangle t's object (its first corner's; the last region for an object
/// beyond them).
const ObjectRegion& RegionOfTriangle(
  const std::vector<ObjectRegion>& regions, const TriangleMesh& mesh, int t)
{
  const int v = mesh.Triangles[t][0];
  return regions[mesh.Objects.empty() ? 0
                                      : std::min<std::size_t>(mesh.Objects[v], regions.size() - 1)];
}
} // namespace

bool MultilevelSolver::InObjectAt(
  const ImageView& image, const Vec3& x, const ObjectRegion& region) const
{
  // Distributed, only the process that owns x's cell samples it (inside false elsewhere).
  bool inside = false;
  const double value = this->Distributed ? this->Piece.SampleOwned(x.data(), &inside)
                                         : SampleVolume(image, x.data(), &inside);
  return inside && RegionSpeed(value, region.Low, region.High) >= FrontSpeed;
}

std::vector<double> MultilevelSolver::FrontSamples(const ImageView& image, const TriangleMesh& mesh,
  const std::vector<int>& divisions, const std::vector<long long>& first) const
{
  // Each sample is taken by the process that owns its cell and the samples in the object summed
  // (the others add 0), so every process sees the same sums.
  const double voxel = image.Geometry.MeanSpacing();
  std::vector<double> inObject(static_cast<std::size_t>(first.back()), 0.0);
  std::vector<Vec3> points;
  for (int t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    if (divisions[t] == 0)
    {
      continue;
    }
    const auto& c = mesh.Triangles[t];
    FrontSamplePoints(
      mesh.Points[c[0]], mesh.Points[c[1]], mesh.Points[c[2]], divisions[t], voxel, points);
    const ObjectRegion& region = RegionOfTriangle(this->ObjectRegions, mesh, t);
    for (std::size_t s = 0; s < points.size(); ++s)
    {
      inObject[first[t] + s] = this->InObjectAt(image, points[s], region) ? 1.0 : 0.0;
    }
  }
  if (this->Distributed)
  {
    this->Reduce.Sum(inObject);
  }
  return inObject;
}

std::vector<char> MultilevelSolver::FrontTriangles(
  const ImageView& image, const TriangleMesh& mesh) const
{
  // Looking beyond the triangles (dsFrontGrid.h) rather than at their vertices: a surface
  // resting on its object's edge has the competitor, not the object, beyond it (a vertex's own
  // value is noise around the range's end there); and the object must go on from the surface
  // out, not lie behind a gap (the engine's pistons have their block beyond a voxel of air, which
  // blurs to values in their range but for a dip a voxel wide).
  const int count = mesh.NumberOfTriangles();
  const double voxel = image.Geometry.MeanSpacing();
  std::vector<int> divisions(count, 0);       // per side of the grid (0: not looked beyond)
  std::vector<long long> first(count + 1, 0); // the triangle's first sample
  for (int t = 0; t < count; ++t)
  {
    const auto& c = mesh.Triangles[t];
    const ObjectRegion& region = RegionOfTriangle(this->ObjectRegions, mesh, t);
    divisions[t] = region.On && region.FollowsFront
      ? FrontGridDivisions(mesh.Points[c[0]], mesh.Points[c[1]], mesh.Points[c[2]], voxel)
      : 0;
    first[t + 1] = first[t] + FrontGridSamples(divisions[t]);
  }
  const std::vector<double> inObject = this->FrontSamples(image, mesh, divisions, first);
  std::vector<char> front(count, 0);
  for (int t = 0; t < count; ++t)
  {
    front[t] = ObjectBeyond(inObject.data() + first[t], first[t + 1] - first[t]) ? 1 : 0;
  }
  return front;
}

std::vector<char> MultilevelSolver::FrontOf(
  const TriangleMesh& mesh, const std::vector<char>& triangles, std::vector<char>& followed) const
{
  // Per object: its front triangles against all of its triangles.
  const int objects = mesh.NumberOfObjects();
  std::vector<long long> all(objects, 0), onFront(objects, 0);
  auto objectOf = [&](int t)
  { return mesh.Objects.empty() ? 0 : mesh.Objects[mesh.Triangles[t][0]]; };
  for (int t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    ++all[objectOf(t)];
    onFront[objectOf(t)] += triangles[t] ? 1 : 0;
  }
  followed.assign(objects, 0);
  bool any = false;
  for (int o = 0; o < objects; ++o)
  {
    followed[o] = onFront[o] > 0 && onFront[o] <= FrontShare * all[o] ? 1 : 0;
    any = any || followed[o];
  }
  std::vector<char> front(any ? mesh.NumberOfPoints() : 0, 0);
  for (int t = 0; t < mesh.NumberOfTriangles() && any; ++t)
  {
    if (triangles[t] && followed[objectOf(t)])
    {
      for (int v : mesh.Triangles[t])
      {
        front[v] = 1;
      }
    }
  }
  return front;
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
  return std::min(ghost, whole.Dimensions[a]);
}

bool MultilevelSolver::EstimateRegions(
  const ImageView& image, TriangleMesh& mesh, std::string* error)
{
  this->ClearResults();
  std::string msg;
  RedGreenRefiner refiner;
  double sigma = 0;
  bool region = false;
  const bool ok = image.Data && !mesh.Triangles.empty() && refiner.Initialize(mesh, &msg) &&
    this->ObjectSigmas(image, mesh, sigma, &msg) &&
    this->PrepareRegions(image, mesh, refiner, sigma, region, &msg);
  if (!ok && error)
  {
    *error = msg.empty() ? std::string("no volume or no initial surface") : msg;
  }
  return ok;
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

bool MultilevelSolver::CheckStartsApart(const TriangleMesh& mesh, std::string* error)
{
  // The contact keeps objects apart; it cannot pull crossing starts apart (dsContact.h).
  const int crossing = mesh.NumberOfObjects() > 1 ? CountCrossingPairs(mesh) : 0;
  if (crossing > 0)
  {
    *error = "the start surfaces of different objects cross (" + std::to_string(crossing) +
      " pairs of triangles): move their seeds apart or make them smaller";
    return false;
  }
  return true;
}
} // namespace dsurf
