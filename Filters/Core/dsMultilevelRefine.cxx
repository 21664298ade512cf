// SPDX-License-Identifier: BSD-3-Clause
// MultilevelSolver's refinement between levels: the triangles the error estimator marks, the
// edges the region force leaves unsplit, the red-green split and the butterfly prolongation
// (docs/METHOD.md §6.2-6.5, §9.3).
#include "dsMultilevel.h"

#include "dsMultilevelRunState.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace dsurf
{
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
} // namespace dsurf
