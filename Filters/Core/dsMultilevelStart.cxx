// SPDX-License-Identifier: BSD-3-Clause
// MultilevelSolver's start: sigma_0 (one object's or each object's), the start subdivided to
// it or a start far finer coarsened, the region ranges estimated, and several objects' starts
// checked apart (docs/METHOD.md §7, §9.1, §9.5, §9.9).
#include "dsMultilevel.h"

#include "dsInitialSigma.h"
#include "dsMultilevelRunState.h"
#include "dsObjects.h"
#include "dsPieceInitialSigma.h"

#include <algorithm>
#include <cmath>

namespace dsurf
{
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
