#include "dsMultilevel.h"

#include "dsRegion.h"
#include "dsUntangle.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace dsurf
{
std::vector<char> MultilevelSolver::MarkTriangles(
  const TriangleMesh& mesh, const std::vector<double>& estimator, double relativeThreshold, bool uniform)
{
  std::vector<char> marks(mesh.Triangles.size(), uniform ? 1 : 0);
  if (uniform || estimator.size() != mesh.Points.size())
  {
    return marks;
  }
  // The level's mean over the vertices that move (fixed boundary vertices report 0 and
  // would drag the mean down).
  double sum = 0;
  int count = 0;
  for (int v = 0; v < mesh.NumberOfPoints(); ++v)
  {
    if (!mesh.BoundaryVertex[v])
    {
      sum += estimator[v];
      ++count;
    }
  }
  if (count == 0 || !(sum > 0))
  {
    return marks; // nothing moves: nothing to refine
  }
  const double threshold = relativeThreshold * sum / count;
  for (size_t t = 0; t < marks.size(); ++t)
  {
    const auto& tri = mesh.Triangles[t];
    const double e = (estimator[tri[0]] + estimator[tri[1]] + estimator[tri[2]]) / 3.0;
    marks[t] = e > threshold ? 1 : 0;
  }
  return marks;
}

bool MultilevelSolver::FirstSigma(const float* scalars, const ImageGeometry& geometry,
  const TriangleMesh& mesh, double& sigma, std::string* error)
{
  const MultilevelParameters& P = this->Parameters;
  const double paper = geometry.MeanExtent() / 6.0;
  if (P.InitialSigma > 0)
  {
    sigma = P.InitialSigma;
  }
  else if (P.InitialSigmaFraction > 0)
  {
    sigma = P.InitialSigmaFraction * geometry.MeanExtent();
  }
  else if (!ChooseInitialSigma(scalars, geometry, mesh, paper, P.Solver.NumberOfThreads, this->SigmaChoice, error))
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

bool MultilevelSolver::RegionRange(const float* scalars, const ImageGeometry& geometry, const TriangleMesh& mesh)
{
  const MultilevelParameters& P = this->Parameters;
  double lo = P.IntensityRange[0], hi = P.IntensityRange[1];
  if (!std::isfinite(lo) || !std::isfinite(hi) || !std::isfinite(hi - lo))
  {
    this->Warnings.push_back("the region force is off: the intensity range must be finite");
    return false;
  }
  if (!(lo < hi) && StartSpansImage(geometry, mesh))
  {
    // A box around the whole volume has no outside to tell its object from: without a
    // given range the region force stays off (the paper's edge-only method).
    this->Warnings.push_back("the region force is off: a start spanning the whole image has no "
                             "outside to estimate the object's intensity range from; give IntensityRange");
    return false;
  }
  if (!(lo < hi))
  {
    RangeEstimate estimate;
    std::string msg;
    if (!EstimateIntensityRange(scalars, geometry, mesh, 1.0, estimate, &msg))
    {
      this->Warnings.push_back("the region force is off: no intensity range was given and none could be "
                               "estimated (" + msg + ")");
      return false;
    }
    lo = estimate.Range[0];
    hi = estimate.Range[1];
    // Without a background to compare with (a click inside one region), the range's end is
    // not where the boundary lies: the region force only grows the surface through its
    // region, and the edge force finds the boundary beyond.
    this->RegionOutwardOnly = !estimate.Contrast;
  }
  if (CountVoxelsInRange(scalars, geometry, lo, hi) == 0)
  {
    this->Warnings.push_back("the region force is off: the intensity range [" + std::to_string(lo) + ", " +
      std::to_string(hi) + "] matches no voxel of the image");
    return false;
  }
  this->UsedRange[0] = lo;
  this->UsedRange[1] = hi;
  return true;
}

bool MultilevelSolver::PrepareStart(const float* scalars, const ImageGeometry& geometry, TriangleMesh& mesh,
  RedGreenRefiner& refiner, double sigma, bool& region, std::string* error)
{
  const MultilevelParameters& P = this->Parameters;
  const double voxel = (geometry.Spacing[0] + geometry.Spacing[1] + geometry.Spacing[2]) / 3.0;
  std::string msg;
  if (P.RegionWeight > 0)
  {
    // The region force pushes along the outward normal (and the range estimate looks just
    // outside the start): every closed piece must face out.
    const int flipped = mesh.OrientPiecesOutward();
    if (flipped > 0)
    {
      this->Warnings.push_back("the region force needs outward normals: " + std::to_string(flipped) +
        " triangle(s) of inward-oriented pieces were reversed");
      if (!refiner.Initialize(mesh, &msg))
      {
        *error = "the reoriented initial surface is not a manifold triangle mesh: " + msg;
        return false;
      }
    }
  }
  region = P.RegionWeight > 0 && this->RegionRange(scalars, geometry, mesh);
  if (P.InitialEdgeSigmaRatio > 0)
  {
    // Uniform red refinement with midpoints keeps the start shape; every new vertex is N,
    // and the result is a fresh level-0 mesh for the hierarchy.
    // Edges shorter than two voxels resolve nothing more, whatever sigma is.
    const double target = std::max(P.InitialEdgeSigmaRatio * sigma, 2.0 * voxel);
    bool subdivided = false;
    while (mesh.MeanEdgeLength() > target &&
      4LL * mesh.NumberOfPoints() <= P.MaxVertices)
    {
      const std::vector<char> all(mesh.Triangles.size(), 1);
      const RefinementCounts rc = refiner.Refine(mesh, all, Prolongation::Linear);
      if (!rc.Ok)
      {
        *error = "subdividing the initial surface failed: " + rc.Error;
        return false;
      }
      ++this->InitialSubdivisions;
      subdivided = true;
    }
    if (subdivided)
    {
      mesh.Levels.assign(mesh.Points.size(), 0);
      if (!refiner.Initialize(mesh, &msg))
      {
        *error = "the subdivided initial surface is not a manifold triangle mesh: " + msg;
        return false;
      }
    }
  }
  return true;
}

bool MultilevelSolver::SolveLevel(Solver& solver, TriangleMesh& mesh, LevelRecord& rec, int& sweepCounter)
{
  const MultilevelParameters& P = this->Parameters;
  const int cap = std::max(1, P.MaxSweepsPerLevel);
  const int maxLevels = std::max(0, P.MaxLevels);
  bool stop = false;
  // Sweeps run in batches inside one parallel region (threads start once per batch, not
  // per sweep); convergence is tested after every sweep, progress and abort between
  // batches, and the sweep records are handed on after each batch.
  // Batches shrink on big meshes so that progress moves and an abort is answered within
  // about the time of 16 sweeps of 50 000 vertices (one sweep from 800 000 vertices on).
  const int batchSize = std::max(1, std::min(P.SweepBatch, static_cast<int>(16LL * 50000 / std::max(1, mesh.NumberOfPoints()))));
  std::vector<SweepStatistics> batchStats;
  for (int s = 0; s < cap && !stop && !rec.Converged;)
  {
    // MaxTotalSweeps: the run stops exactly there (the batch is cut short to reach it).
    const int budget = P.MaxTotalSweeps > 0 ? P.MaxTotalSweeps - sweepCounter : cap;
    if (budget <= 0)
    {
      this->Warnings.push_back("stopped after MaxSweeps (" + std::to_string(P.MaxTotalSweeps) + ") sweeps");
      stop = true;
      break;
    }
    batchStats.clear();
    solver.Sweeps(std::min({ batchSize, cap - s, budget }), [&](const SweepStatistics& st) {
      batchStats.push_back(st);
      if (st.MovedVertices == 0 || st.MeanCorrection < P.Tolerance * rec.MeanEdgeLength)
      {
        rec.Converged = true;
        return false;
      }
      return true;
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
        stop = true;
        break;
      }
    }
    if (!stop && !rec.Converged && this->Progress &&
      !this->Progress((rec.Level + std::min(1.0, double(s) / std::min(cap, 400))) / (maxLevels + 1)))
    {
      this->Aborted = true;
      stop = true;
    }
  }
  if (P.MaxTotalSweeps > 0 && sweepCounter >= P.MaxTotalSweeps && !stop)
  {
    this->Warnings.push_back("stopped after MaxSweeps (" + std::to_string(P.MaxTotalSweeps) + ") sweeps");
    stop = true; // no refinement after the budget
  }
  return stop;
}

bool MultilevelSolver::Run(const float* scalars, const ImageGeometry& geometry, TriangleMesh& mesh, std::string* error)
{
  const MultilevelParameters& P = this->Parameters;
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
  this->SigmaChoice = InitialSigmaChoice();
  this->UsedRange[0] = this->UsedRange[1] = 0;
  this->RegionOutwardOnly = false;
  auto fail = [error](const std::string& msg) {
    if (error)
    {
      *error = msg;
    }
    return false;
  };
  if (!scalars || geometry.NumberOfVoxels() <= 0)
  {
    return fail("the volume is empty");
  }
  if (mesh.Triangles.empty())
  {
    return fail("the initial surface has no triangles");
  }

  // The voxel size (mean spacing) bounds how fine the mesh usefully gets.
  const double voxel = (geometry.Spacing[0] + geometry.Spacing[1] + geometry.Spacing[2]) / 3.0;
  RedGreenRefiner refiner;
  std::string msg;
  if (!refiner.Initialize(mesh, &msg))
  {
    return fail("the initial surface is not a manifold triangle mesh: " + msg);
  }
  double sigma = 0;
  if (!this->FirstSigma(scalars, geometry, mesh, sigma, &msg))
  {
    return fail(msg);
  }
  const double firstSigma = sigma;
  bool region = false;
  if (!this->PrepareStart(scalars, geometry, mesh, refiner, sigma, region, &msg))
  {
    return fail(msg);
  }
#ifndef NDEBUG
  const bool checkInvariants = true;
#else
  const bool checkInvariants = P.CheckInvariants;
#endif
  const int eulerStart = mesh.EulerCharacteristic();
  const bool closedStart = mesh.IsClosed();

  Solver solver;
  solver.SetParameters(P.Solver);
  ForceField field;
  ScaleSpaceParameters ssp;
  ssp.EdgeWeight = P.EdgeWeight;
  ssp.ImageWeight = P.ImageWeight;
  ssp.NormalizePotential = true;
  ssp.Normalization = P.Normalization;
  ssp.NumberOfThreads = P.Solver.NumberOfThreads;

  const int maxLevels = std::max(0, P.MaxLevels);
  int sweepCounter = 0;
  bool budgetWarned = false;
  for (int level = 0; level <= maxLevels; ++level)
  {
    // Force field at this level's sigma (rebuilt only when sigma changed).
    if (field.Empty() || std::abs(field.Sigma - sigma) > 1e-12 * sigma)
    {
      ssp.Sigma = sigma;
      if (!ComputeScaleSpaceForce(scalars, geometry, ssp, field, &msg))
      {
        return fail("scale-space force: " + msg);
      }
    }
    const double h = mesh.MeanEdgeLength();
    solver.SetMesh(&mesh);
    solver.SetForceField(&field, P.ForceWeight * h * sigma);
    if (region)
    {
      // The balloon brings the surface to its object at the coarse scales; as sigma shrinks
      // the edge force takes over the detail, so the region force shrinks with sigma (at full
      // strength it presses the surface into every narrow dark gap of the object).
      const double decay = std::min(1.0, sigma / firstSigma);
      solver.SetRegionForce(scalars, geometry, this->UsedRange[0], this->UsedRange[1],
        decay * P.RegionWeight * h, this->RegionOutwardOnly);
    }

    LevelRecord rec;
    rec.Level = level;
    rec.Sigma = sigma;
    rec.Vertices = mesh.NumberOfPoints();
    rec.Triangles = mesh.NumberOfTriangles();
    rec.MeanEdgeLength = h;
    const bool stop = this->SolveLevel(solver, mesh, rec, sweepCounter);
    // With the hierarchical sigma, the level solved at sigma's floor (half a voxel) is the
    // last: further levels would only refine the mesh for detail the image does not show
    // (a start near its object reaches the floor after a few halvings).
    const bool atFloor = P.HierarchicalSigma && !(sigma > 0.5 * voxel * (1 + 1e-9));
    const bool lastLevel = stop || level == maxLevels || atFloor;
    // Folds the forces left (two parts of the surface pushed together) are smoothed open on
    // the surface delivered (dsUntangle.h). Only there: a coarse level's folds are undone by
    // the finer levels' sweeps, while smoothing two rings of a coarse mesh flattens most of it
    // (docs/METHOD.md §9.4).
    if (lastLevel)
    {
      rec.Folds = Untangle(mesh);
    }
    if (rec.Folds.After > 0)
    {
      this->Warnings.push_back(std::to_string(rec.Folds.After) + " pairs of triangles still intersect after level " +
        std::to_string(level) + " (" + std::to_string(rec.Folds.Before) + " before smoothing them)");
    }
    this->ErrorIndicator = solver.ErrorIndicator();
    this->Displacement = solver.Displacement();
    this->ExternalForce = solver.ExternalForceMagnitude();
    if (lastLevel)
    {
      this->Levels.push_back(rec);
      break;
    }

    // Mark, check the vertex budget, refine. Adaptively, triangles whose edges are all
    // shorter than a voxel are not split again: the image has no finer detail for their
    // children to follow. (UniformRefinement splits everything, as asked.)
    std::vector<char> marks =
      MarkTriangles(mesh, this->ErrorIndicator, P.RefinementThreshold, P.UniformRefinement);
    for (size_t t = 0; t < marks.size() && !P.UniformRefinement; ++t)
    {
      if (marks[t])
      {
        const auto& tri = mesh.Triangles[t];
        double longest = 0.0;
        for (int k = 0; k < 3; ++k)
        {
          longest = std::max(longest, Norm(mesh.Points[tri[(k + 1) % 3]] - mesh.Points[tri[k]]));
        }
        if (longest < voxel)
        {
          marks[t] = 0;
        }
      }
    }
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
    bool refine = rec.MarkedTriangles > 0;
    if (refine &&
      static_cast<long long>(mesh.NumberOfPoints()) + static_cast<long long>(splitEdges.size()) > P.MaxVertices)
    {
      if (!budgetWarned)
      {
        this->Warnings.push_back("refinement stopped at level " + std::to_string(level) +
          ": the next step would exceed MaxVertices (" + std::to_string(P.MaxVertices) +
          "); the remaining levels only decrease sigma");
        budgetWarned = true;
      }
      refine = false;
      rec.MarkedTriangles = 0;
    }
    this->Levels.push_back(rec);
    if (refine)
    {
      this->Levels.back().Refinement = refiner.Refine(mesh, marks, P.ProlongationMode);
      const RefinementCounts& rc = this->Levels.back().Refinement;
      if (!rc.Ok)
      {
        return fail("refinement failed: " + rc.Error);
      }
      if (checkInvariants &&
        (!CheckTopologyInvariants(mesh, eulerStart, closedStart, &msg) || refiner.CountTVertices(mesh) != 0))
      {
        return fail("refinement broke a topology invariant at level " + std::to_string(level + 1) + ": " +
          (msg.empty() ? std::string("T-vertex") : msg));
      }
    }
    // The next level's sigma. Even when nothing was refined (nothing marked, the marked
    // triangles already below a voxel, or the vertex budget reached) the schedule goes on
    // with a smaller sigma: otherwise the surface would rest where the coarse, blurred
    // edge lies, voxels off the boundary. Sigma stops at half a voxel, below which the
    // image has nothing more to show; a level that would change neither mesh nor sigma
    // ends the run.
    const double nextSigma = P.HierarchicalSigma ? std::max(0.5 * sigma, std::min(sigma, 0.5 * voxel)) : sigma;
    if (!refine && !(nextSigma < sigma))
    {
      break;
    }
    sigma = nextSigma;
  }
  if (this->Progress)
  {
    this->Progress(1.0);
  }
  return true;
}
} // namespace dsurf
