// SPDX-License-Identifier: BSD-3-Clause
#include "dsPieceInitialSigma.h"

#include "dsFieldGrid.h"
#include "dsGaussianSmoother.h"
#include "dsMemory.h"
#include "dsVoxelSet.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dsurf
{
namespace
{
/// The fine probe's ghosts along axis a: its two Gaussians' (see InitialSigmaProbeGhostVoxels).
int FineProbeGhostVoxels(const ImageGeometry& whole, int a)
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
    const int ghost = FineProbeGhostVoxels(piece.Whole, a);
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

/// Linear ids in `region` of a box's voxels, x fastest (the probe's values).
struct RegionIds
{
  std::ptrdiff_t Increments[3];
  explicit RegionIds(const VoxelBox& region)
  {
    const std::ptrdiff_t nx = region.End[0] - region.Begin[0];
    this->Increments[0] = 1;
    this->Increments[1] = nx;
    this->Increments[2] = nx * (region.End[1] - region.Begin[1]);
  }
};

/// The voxels of `region` whose probe values a ray may read: the corners of the owned cells of
/// every point of every ray, each walked its whole reach both ways (the walk of
/// ChooseInitialSigmaWith on strengths that never make an edge; a real walk reads a prefix of
/// each of its two directions). Empty when the region is.
VoxelSet RayVoxels(
  const ImagePiece& piece, const TriangleMesh& mesh, double paperSigma, const VoxelBox& region)
{
  VoxelSet wanted(region.NumberOfVoxels());
  if (region.NumberOfVoxels() > 0)
  {
    const RegionIds ids(region);
    const EdgeStrengthSampler mark =
      [&](const std::vector<Vec3>& points, std::vector<double>& strengths)
    {
      for (const Vec3& x : points)
      {
        TrilinearCell c;
        if (piece.LocateOwnedCell(x.data(), region.Begin, ids.Increments, c))
        {
          for (int corner = 0; corner < 8; ++corner)
          {
            wanted.Insert(c.Corner(corner));
          }
        }
      }
      strengths.assign(points.size(), 0.0);
    };
    InitialSigmaChoice unused;
    ChooseInitialSigmaWith(piece.Whole, mesh, paperSigma, mark, StepsPerRound, unused);
  }
  wanted.Finish();
  return wanted;
}

/// The probe's potential at the `wanted` voxels of `region` of the piece (LocalPotentialAt:
/// the field slab by slab, never whole), normalised as the whole reach's (both maxima over the
/// `reached` voxels of every process). A process that fails makes the reductions it has not
/// made with an infinite maximum, which the others' fields then carry; one the rays do not
/// reach computes nothing and makes them with 0 (FinishProbeReductions). The caller agrees on
/// the outcome.
bool PieceProbe(const ImagePiece& piece, const VoxelBox& reached, const VoxelBox& region,
  const VoxelSet& wanted, int numberOfThreads, const PieceReductions& reduce,
  std::vector<float>& probe, std::string& problem)
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
  const bool ok = problem.empty() &&
    LocalPotentialAt(piece.Image.Box(inHeld), parameters, wanted, probe, &problem);
  if (!ok)
  {
    FinishProbeReductions(
      reduce, reductions, firstMaximum, std::numeric_limits<double>::infinity());
  }
  return ok;
}

/// The trilinear sample of the probe in `cell` (ids of the region), read from the wanted
/// voxels' values in SampleCell's order, so it equals the whole field's sample bit for bit.
double SampleProbe(
  const std::vector<float>& probe, const VoxelSet& wanted, const TrilinearCell& cell)
{
  double v = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    const long long id = cell.Corner(corner);
    v += cell.Weight(corner) * (wanted.Contains(id) ? probe[wanted.Rank(id)] : 0.0f);
  }
  return v;
}
} // namespace

int InitialSigmaProbeGhostVoxels(const ImageGeometry& whole, int a)
{
  // The coarse probe's blocks are averaged by the piece counting their first voxel (2 f).
  const int coarse = 2 * CoarseProbeBlock(whole, whole.MeanExtent() / 6.0);
  return std::min(whole.Dimensions[a], std::max(FineProbeGhostVoxels(whole, a), coarse));
}

int CoarseProbeBlock(const ImageGeometry& whole, double paperSigma)
{
  return DecimationFactor(CoarseProbeSigmaShare * paperSigma, whole);
}

namespace
{
/// The probe on the block means of f^3 blocks (PieceBlockMeans): the whole coarse grid on every
/// process, so each walks the rays on it alone, as a single process would, and all choose alike.
/// One that fails (its memory, its field) tells the others, which fail with it.
bool CoarseProbe(const ImagePiece& piece, const TriangleMesh& mesh, double paperSigma, int f,
  int numberOfThreads, const PieceReductions& reduce, InitialSigmaChoice& choice,
  std::string* error)
{
  std::vector<float> means;
  ImageGeometry geometry;
  std::string problem;
  if (!PieceBlockMeans(piece, VoxelBox::Whole(piece.Whole), f, numberOfThreads, reduce, means,
        geometry, &problem)) // false on every process alike
  {
    if (error)
    {
      *error = "the coarse probe of sigma_0: " + problem;
    }
    return false;
  }
  const bool ok = ChoosePieceInitialSigma(WholeImagePiece(ImageView::Of(means.data(), geometry)),
    mesh, paperSigma, numberOfThreads, SingleProcessReductions(), choice, &problem);
  if (reduce.Max(ok ? 0.0 : 1.0) > 0.0)
  {
    if (error)
    {
      *error = ok ? std::string("another process could not compute its coarse probe of sigma_0")
                  : "the coarse probe of sigma_0: " + problem;
    }
    return false;
  }
  // The coarse grid reaches half a block past the image: a start it spans may not span the
  // image, whose check came first.
  choice.SpansVolume = false;
  return true;
}
} // namespace

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
  // A large image is probed coarse first (docs/METHOD.md §9.7): a start that lies several
  // blocks from its edges has its distance measured to well within the share of it that
  // matters (a fraction of one halving of the hierarchy), at 1/f^3 of the fine probe's cost.
  // Nearer, the fine probe decides. Every process takes the same branch: the coarse choice is
  // the same on all of them.
  const int f = CoarseProbeBlock(piece.Whole, paperSigma);
  if (f > 1)
  {
    if (!CoarseProbe(piece, mesh, paperSigma, f, numberOfThreads, reduce, choice, error))
    {
      return false;
    }
    // In blocks along the axis with the largest spacing, which sets f (DecimationFactor).
    const double* s = piece.Whole.Spacing;
    if (choice.Sigma >= CoarseProbeKeptBlocks * f * std::max({ s[0], s[1], s[2] }))
    {
      choice.ProbeBlock = f;
      return true;
    }
    choice = InitialSigmaChoice();
    choice.Sigma = paperSigma;
  }
  const VoxelBox reached = ReachedOwnedVoxels(piece, mesh, paperSigma);
  const VoxelBox region = ProbeRegion(piece, reached);
  std::string problem = region.NumberOfVoxels() == 0 || piece.Held.Contains(region)
    ? std::string()
    : "the piece holds too few ghost layers for "
      "the probe of sigma_0 (" +
      std::to_string(FineProbeGhostVoxels(piece.Whole, 0)) + " voxels needed)";
  const VoxelSet wanted = RayVoxels(piece, mesh, paperSigma, problem.empty() ? region : VoxelBox());
  if (problem.empty() && region.NumberOfVoxels() > 0)
  {
    ImageGeometry probed = piece.Whole;
    for (int a = 0; a < 3; ++a)
    {
      probed.Dimensions[a] = region.End[a] - region.Begin[a];
    }
    problem = MemoryShortfall(
      LocalPotentialBytes(probed, InitialSigmaProbeParameters(piece.Whole, 1), wanted),
      "holding a slab and the voxels its rays read (docs/METHOD.md §9.7)");
  }
  std::vector<float> probe;
  const bool ok =
    PieceProbe(piece, reached, region, wanted, numberOfThreads, reduce, probe, problem);
  if (reduce.Max(ok ? 0.0 : 1.0) > 0.0)
  {
    if (error)
    {
      *error = ok ? std::string("another process could not compute its probe of sigma_0")
                  : "the probe of sigma_0: " + problem;
    }
    return false;
  }
  const RegionIds ids(region);
  // Each strength from the process owning its cell, 0 from the others: the sum is the serial
  // sample exactly. Whether a point lies in the image the whole image's geometry says alike.
  const EdgeStrengthSampler sample =
    [&](const std::vector<Vec3>& points, std::vector<double>& strengths)
  {
    strengths.assign(points.size(), 0.0);
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      TrilinearCell c;
      // Every ray's samples lie within its reach, so an owned cell they fall in was reached,
      // and its corners were wanted (RayVoxels).
      if (wanted.Size() > 0 &&
        piece.LocateOwnedCell(points[i].data(), region.Begin, ids.Increments, c))
      {
        strengths[i] = -SampleProbe(probe, wanted, c);
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
