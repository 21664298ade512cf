#include "dsPieceInitialSigma.h"

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

/// The owned voxels and the probe's ghosts around them, within the image.
VoxelBox ProbeRegion(const ImagePiece& piece)
{
  VoxelBox region = piece.Owned;
  for (int a = 0; a < 3; ++a)
  {
    const int ghost = InitialSigmaProbeGhostVoxels(piece.Whole, a);
    region.Begin[a] = std::max(0, region.Begin[a] - ghost);
    region.End[a] = std::min(piece.Whole.Dimensions[a], region.End[a] + ghost);
  }
  return region;
}

/// The probe's potential over `region` of the piece, normalised as the whole image's (both
/// maxima over every process). A process that fails still makes both reductions (with an
/// infinite maximum, which the others' fields then carry); the caller agrees on the outcome.
bool PieceProbe(const ImagePiece& piece, const VoxelBox& region, int numberOfThreads,
  const PieceReductions& reduce, ForceField& probe, std::string& problem)
{
  ScaleSpaceParameters parameters = InitialSigmaProbeParameters(piece.Whole, numberOfThreads);
  int reductions = 0;
  parameters.GradientMaximum = [&](double ownedMaximum)
  {
    ++reductions;
    return reduce.Max(ownedMaximum);
  };
  for (int a = 0; a < 3; ++a)
  {
    parameters.MaximumBegin[a] = piece.Owned.Begin[a] - region.Begin[a];
    parameters.MaximumEnd[a] = piece.Owned.End[a] - region.Begin[a];
  }
  VoxelBox inHeld = region;
  for (int a = 0; a < 3; ++a)
  {
    inHeld.Begin[a] -= piece.Held.Begin[a];
    inHeld.End[a] -= piece.Held.Begin[a];
  }
  const bool ok = problem.empty() &&
    ComputeScaleSpaceForce(piece.Image.Box(inHeld), parameters, probe, &problem);
  // The normalisations take the largest g, then the largest locally normalised g; a process
  // that failed before them sends infinity to both, which every process then receives.
  for (; reductions < 2 && !ok; ++reductions)
  {
    reduce.Max(std::numeric_limits<double>::infinity());
  }
  probe.Force.clear(); // only the potential is sampled
  probe.Force.shrink_to_fit();
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
  const int second =
    wide < GaussianRecursiveFromSigmaVoxels ? static_cast<int>(std::ceil(4.0 * wide)) : whole.Dimensions[a];
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
  const VoxelBox region = ProbeRegion(piece);
  std::string problem = piece.Held.Contains(region) ? std::string()
                                                    : "the piece holds too few ghost layers for "
                                                      "the probe of sigma_0 (" +
      std::to_string(InitialSigmaProbeGhostVoxels(piece.Whole, 0)) + " voxels needed)";
  ForceField probe;
  const bool ok = PieceProbe(piece, region, numberOfThreads, reduce, probe, problem);
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
      if (piece.LocateOwnedCell(points[i].data(), region.Begin, increments, c))
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
