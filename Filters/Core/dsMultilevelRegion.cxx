// SPDX-License-Identifier: BSD-3-Clause
// MultilevelSolver's region force: each object's range (given, or estimated from its start or
// click), the models a level's solver gets, and the front of a thin part the surface has not
// reached (docs/METHOD.md §9.3).
#include "dsMultilevel.h"

#include "dsFrontGrid.h"
#include "dsMultilevelRunState.h"
#include "dsObjects.h"
#include "dsRegion.h"
#include "dsThreads.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

namespace dsurf
{
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
  // A click given its range pulls harder than a start near its object (dsRegion.h).
  const bool givenClick = given[0] < given[1] &&
    (this->Distributed
        ? PieceStartIsClick(this->Piece, mesh, this->Reduce)
        : PieceStartIsClick(WholeImagePiece(image), mesh, SingleProcessReductions()));
  const double weight = this->Parameters.RegionWeight;
  model.Weight = givenClick ? std::max(weight, GivenRangeClickWeight) : weight;
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

double MultilevelSolver::GetRegionWeight() const
{
  for (const ObjectRegion& r : this->ObjectRegions)
  {
    if (r.On)
    {
      return r.Weight;
    }
  }
  return this->Parameters.RegionWeight;
}

std::vector<Solver::RegionModel> MultilevelSolver::LevelRegionModels(
  const RunState& state, double sigma) const
{
  const bool own = this->StartSigmas.size() == this->ObjectRegions.size();
  const double weight = this->GetRegionWeight();
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
    // The level's force scale holds the first object's weight (GetRegionWeight); an object
    // that pulls with another (a click given its range among other objects) scales its own.
    if (r.On && r.Weight != weight)
    {
      m.Scale *= r.Weight / weight;
    }
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

double RegionFade(double sigma, double firstSigma)
{
  return std::min(1.0, sigma / firstSigma);
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

bool FrontGrows(const std::vector<long long>& sizes)
{
  const std::size_t n = sizes.size();
  if (n <= static_cast<std::size_t>(FrontGrowthLevels))
  {
    return false;
  }
  for (std::size_t i = n - FrontGrowthLevels; i < n; ++i)
  {
    if (!(sizes[i] > sizes[i - 1]))
    {
      return false;
    }
  }
  return static_cast<double>(sizes[n - 1]) >
    FrontGrowthFactor * static_cast<double>(sizes[n - 1 - FrontGrowthLevels]);
}

std::vector<char> MultilevelSolver::FrontOf(const TriangleMesh& mesh,
  const std::vector<char>& triangles, std::vector<char>& followed,
  std::vector<std::vector<long long>>& history) const
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
  history.resize(objects);
  bool any = false;
  for (int o = 0; o < objects; ++o)
  {
    followed[o] = onFront[o] > 0 && onFront[o] <= FrontShare * all[o] ? 1 : 0;
    // A thin part's front is about its tip; one that branches on at every level is a network of
    // thin parts (FrontGrowthLevels): pushing on would spread the surface through it. An object
    // stopped so is not followed again.
    if (followed[o] && !FrontGrows(history[o]))
    {
      history[o].push_back(onFront[o]);
    }
    followed[o] = followed[o] && !FrontGrows(history[o]) ? 1 : 0;
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

void MultilevelSolver::WarnOfGrowingFront(const TriangleMesh& mesh, RunState& state)
{
  for (std::size_t o = 0; o < state.FrontHistory.size() && !state.FrontGrowthWarned; ++o)
  {
    if (FrontGrows(state.FrontHistory[o]))
    {
      const std::string which = mesh.ObjectIds.size() > o
        ? "object " + std::to_string(mesh.ObjectIds[o]) + "'s surface"
        : "the surface";
      this->Warnings.push_back("the levels that follow thin parts left behind stopped following " +
        which + ": its front grew at each of the last " + std::to_string(FrontGrowthLevels) +
        " of them (" + std::to_string(state.FrontHistory[o].back()) +
        " triangles), a network of thin parts its intensity range runs on through, not the end "
        "of a part left behind (docs/METHOD.md §9.3); a narrower range keeps it in its object");
      state.FrontGrowthWarned = true;
    }
  }
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
} // namespace dsurf
