// SPDX-License-Identifier: BSD-3-Clause
#include "dsPieceInitialSigma.h"

#include "dsFieldGrid.h"
#include "dsGaussianSmoother.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dsurf
{
namespace
{
/// Rays' steps sampled per round on a distributed image: one sum of this many strengths per
/// ray still walking (a ray of 2 * extent / 6 each way takes up to ~8 extent / 6 voxels of
/// steps; most end at their first edge, a few voxels out).
constexpr int StepsPerRound = 16;

/// The owned voxels the rays can reach (InitialSigmaProbeReach of the start); none (an empty
/// box) when they reach none of the piece's.
VoxelBox ReachedOwnedVoxels(const ImagePiece& piece, const TriangleMesh& mesh, double paperSigma)
{
  const VoxelBox near =
    SurfaceNeighbourhood(mesh, piece.Whole, InitialSigmaProbeReach(piece.Whole, paperSigma));
  VoxelBox reached;
  for (int a = 0; a < 3; ++a)
  {
    reached.Begin[a] = std::max(piece.Owned.Begin[a], near.Begin[a]);
    reached.End[a] = std::min(piece.Owned.End[a], near.End[a]);
    if (reached.End[a] <= reached.Begin[a])
    {
      return VoxelBox();
    }
  }
  return reached;
}

/// `reached` and the probe's ghosts around it, within the image (empty when reached is).
VoxelBox ProbeRegion(const ImagePiece& piece, const VoxelBox& reached)
{
  VoxelBox region = reached;
  for (int a = 0; a < 3 && reached.NumberOfVoxels() > 0; ++a)
  {
    const int ghost = InitialSigmaProbeGhostVoxels(piece.Whole, a);
    region.Begin[a] = std::max(0, region.Begin[a] - ghost);
    region.End[a] = std::min(piece.Whole.Dimensions[a], region.End[a] + ghost);
  }
  return region;
}

/// The probe's normalisation reductions this process has not made (`made` of them, the first
/// giving `firstMaximum`), each with `value`: the largest g, then the largest locally normalised
/// g only when the first maximum is positive, as ComputeScaleSpaceForce skips the second when
/// it is 0 (a probe that failed after it must not make a reduction the others do not).
void FinishProbeReductions(
  const PieceReductions& reduce, int made, double firstMaximum, double value)
{
  if (made == 0)
  {
    firstMaximum = reduce.Max(value);
    made = 1;
  }
  if (made == 1 && firstMaximum > 0.0)
  {
    reduce.Max(value);
  }
}

/// The probe's potential over `region` of the piece, normalised as the whole reach's (both
/// maxima over the `reached` voxels of every process). A process that fails makes the
/// reductions it has not made with an infinite maximum, which the others' fields then carry;
/// one the rays do not reach computes nothing and makes them with 0 (FinishProbeReductions).
/// The caller agrees on the outcome.
bool PieceProbe(const ImagePiece& piece, const VoxelBox& reached, const VoxelBox& region,
  int numberOfThreads, const PieceReductions& reduce, ForceField& probe, std::string& problem)
{
  if (problem.empty() && region.NumberOfVoxels() == 0)
  {
    FinishProbeReductions(reduce, 0, 0.0, 0.0);
    return true;
  }
  ScaleSpaceParameters parameters = InitialSigmaProbeParameters(piece.Whole, numberOfThreads);
  int reductions = 0;
  double firstMaximum = 0.0;
  parameters.GradientMaximum = [&](double ownedMaximum)
  {
    const double maximum = reduce.Max(ownedMaximum);
    firstMaximum = reductions++ == 0 ? maximum : firstMaximum;
    return maximum;
  };
  for (int a = 0; a < 3; ++a)
  {
    parameters.MaximumBegin[a] = reached.Begin[a] - region.Begin[a];
    parameters.MaximumEnd[a] = reached.End[a] - region.Begin[a];
  }
  VoxelBox inHeld = region;
  for (int a = 0; a < 3; ++a)
  {
    inHeld.Begin[a] -= piece.Held.Begin[a];
    inHeld.End[a] -= piece.Held.Begin[a];
  }
  const bool ok =
    problem.empty() && ComputeScaleSpaceForce(piece.Image.Box(inHeld), parameters, probe, &problem);
  if (!ok)
  {
    FinishProbeReductions(
      reduce, reductions, firstMaximum, std::numeric_limits<double>::infinity());
  }
  return ok;
}
} // namespace

int InitialSigmaProbeGhostVoxels(const ImageGeometry& whole, int a)
{
  // The probe smooths each piece on its own (its Gaussians are not passed between the pieces,
  // dsPieceGaussian.h): where one is recursive (a very anisotropic grid) it needs the whole axis.
  const double sigma = whole.MeanSpacing();
  const int first = sigma / whole.Spacing[a] < GaussianRecursiveFromSigmaVoxels
    ? PieceGhostVoxels(sigma, whole, a)
    : whole.Dimensions[a];
  const double wide = 2.0 * sigma / whole.Spacing[a];
  const int second = wide < GaussianRecursiveFromSigmaVoxels
    ? static_cast<int>(std::ceil(4.0 * wide))
    : whole.Dimensions[a];
  return std::min(whole.Dimensions[a], first + second);
}

bool ChoosePieceInitialSigma(const ImagePiece& piece, const TriangleMesh& mesh, double paperSigma,
  int numberOfThreads, const PieceReductions& reduce, InitialSigmaChoice& choice,
  std::string* error)
{
  choice = InitialSigmaChoice();
  choice.Sigma = paperSigma;
  if (StartSpansImage(piece.Whole, mesh)) // the same on every process: no reduction
  {
    choice.SpansVolume = true;
    return true;
  }
  const VoxelBox reached = ReachedOwnedVoxels(piece, mesh, paperSigma);
  const VoxelBox region = ProbeRegion(piece, reached);
  std::string problem = region.NumberOfVoxels() == 0 || piece.Held.Contains(region)
    ? std::string()
    : "the piece holds too few ghost layers for "
      "the probe of sigma_0 (" +
      std::to_string(InitialSigmaProbeGhostVoxels(piece.Whole, 0)) + " voxels needed)";
  ForceField probe;
  const bool ok = PieceProbe(piece, reached, region, numberOfThreads, reduce, probe, problem);
  if (reduce.Max(ok ? 0.0 : 1.0) > 0.0)
  {
    if (error)
    {
      *error = ok ? std::string("another process could not compute its probe of sigma_0")
                  : "the probe of sigma_0: " + problem;
    }
    return false;
  }
  const std::ptrdiff_t nx = region.End[0] - region.Begin[0];
  const std::ptrdiff_t increments[3] = { 1, nx, nx * (region.End[1] - region.Begin[1]) };
  const ImageView potential = ImageView::Of(probe.Potential.data(), probe.Geometry);
  // Each strength from the process owning its cell, 0 from the others: the sum is the serial
  // sample exactly. Whether a point lies in the image the whole image's geometry says alike.
  const EdgeStrengthSampler sample =
    [&](const std::vector<Vec3>& points, std::vector<double>& strengths)
  {
    strengths.assign(points.size(), 0.0);
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      TrilinearCell c;
      // Every ray's samples lie within its reach, so an owned cell they fall in was reached.
      if (!probe.Potential.empty() &&
        piece.LocateOwnedCell(points[i].data(), region.Begin, increments, c))
      {
        strengths[i] = -SampleCell(potential, c);
      }
    }
    reduce.Sum(strengths);
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      TrilinearCell c;
      strengths[i] = LocateImageCell(piece.Whole, points[i].data(), c) ? strengths[i] : -1.0;
    }
  };
  ChooseInitialSigmaWith(piece.Whole, mesh, paperSigma, sample, StepsPerRound, choice);
  return true;
}
} // namespace dsurf
