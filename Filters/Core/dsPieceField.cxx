// SPDX-License-Identifier: BSD-3-Clause
#include "dsPieceField.h"

#include "dsGaussianSmoother.h"
#include "dsPieceGaussian.h"
#include "dsPieceSlabs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace dsurf
{
ImageGeometry ImagePiece::HeldGeometry() const
{
  return BoxGeometry(this->Whole, this->Held);
}

bool ImagePiece::OwnsCell(const double x[3]) const
{
  double ijk[3];
  this->Whole.WorldToIndex(x, ijk);
  for (int a = 0; a < 3; ++a)
  {
    const double lastCell = std::max(0, this->Whole.Dimensions[a] - 2);
    const double c = std::min(lastCell, std::max(0.0, std::floor(ijk[a])));
    // Cells Begin .. End - 2: the cell from the shared border voxel on is the next piece's.
    if (!(c >= this->Owned.Begin[a] && c <= std::max(this->Owned.Begin[a], this->Owned.End[a] - 2)))
    {
      return false;
    }
  }
  return true;
}

bool ImagePiece::LocateOwnedCell(const double x[3], const int begin[3],
  const std::ptrdiff_t increments[3], TrilinearCell& cell) const
{
  if (!this->OwnsCell(x) || !LocateImageCell(this->Whole, x, cell, increments))
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    cell.Base -= static_cast<long long>(begin[a]) * increments[a];
  }
  return true;
}

double ImagePiece::SampleOwned(const double x[3], bool* owned) const
{
  TrilinearCell c;
  const std::ptrdiff_t increments[3] = { 1, this->Image.RowStride, this->Image.SliceStride };
  *owned = this->Image.Data && this->LocateOwnedCell(x, this->Held.Begin, increments, c);
  return *owned ? SampleCell(this->Image, c) : 0.0;
}

PieceReductions SingleProcessReductions()
{
  PieceReductions reduce;
  reduce.Sum = [](std::vector<double>&) {};
  reduce.Max = [](double value) { return value; };
  return reduce;
}

ImagePiece WholeImagePiece(const ImageView& image)
{
  ImagePiece piece;
  piece.Whole = image.Geometry;
  piece.Owned = piece.Held = VoxelBox::Whole(image.Geometry);
  piece.Image = image;
  return piece;
}

VoxelBox ImagePiece::CountedVoxels() const
{
  VoxelBox counted = this->Owned;
  for (int a = 0; a < 3; ++a)
  {
    if (counted.End[a] < this->Whole.Dimensions[a])
    {
      counted.End[a] = std::max(counted.Begin[a], counted.End[a] - 1);
    }
  }
  return counted;
}

int PieceGhostVoxels(double sigma, const ImageGeometry& whole, int a)
{
  // One voxel for the differences of G_sigma * f (g and the force's chain rule read the 3^3
  // voxels around a voxel: dsScaleSpace.h), and the Gaussian's reach (dsGaussianSmoother.h):
  // the sampled kernel's radius, so the owned voxels get the serial values bit for bit. The
  // recursive filter reaches along the whole axis, but its state comes from the neighbouring
  // pieces (dsPieceGaussian.h), so it needs no ghosts of its own.
  return FineGhostVoxels(sigma / whole.Spacing[a]);
}

int FineGhostVoxels(double sigmaVoxels)
{
  if (!(sigmaVoxels < GaussianRecursiveFromSigmaVoxels))
  {
    return 1;
  }
  return static_cast<int>(std::ceil(4.0 * sigmaVoxels)) + 1;
}

namespace
{
/// The voxels of both boxes.
VoxelBox Intersect(const VoxelBox& a, const VoxelBox& b)
{
  VoxelBox r;
  for (int k = 0; k < 3; ++k)
  {
    r.Begin[k] = std::max(a.Begin[k], b.Begin[k]);
    r.End[k] = std::max(r.Begin[k], std::min(a.End[k], b.End[k]));
  }
  return r;
}

/// Calls visit(i, j, k, value) for the piece's voxels in `voxels` (whole-image indices), each
/// value as float (AsFloat), as BlockMeans and CountVoxelsInRange read it.
template <typename Visit>
void ForEachHeldVoxel(const ImagePiece& piece, const VoxelBox& voxels, Visit&& visit)
{
  const int* h = piece.Held.Begin;
  VisitValues(piece.Image,
    [&](const auto* values)
    {
      for (int k = voxels.Begin[2]; k < voxels.End[2]; ++k)
      {
        for (int j = voxels.Begin[1]; j < voxels.End[1]; ++j)
        {
          const auto* row = values + piece.Image.RowOffset(j - h[1], k - h[2]);
          for (int i = voxels.Begin[0]; i < voxels.End[0]; ++i)
          {
            visit(i, j, k, AsFloat(row[i - h[0]]));
          }
        }
      }
    });
}

/// Whether this process counts every voxel of `cut` (a whole image on one process).
bool CountsAll(const ImagePiece& piece, const VoxelBox& cut)
{
  return Intersect(piece.CountedVoxels(), cut).NumberOfVoxels() == cut.NumberOfVoxels() &&
    piece.Held.Contains(cut);
}
} // namespace

bool PieceBlockMeans(const ImagePiece& piece, const VoxelBox& cut, int f, int numberOfThreads,
  const PieceReductions& reduce, std::vector<float>& coarse, ImageGeometry& coarseGeometry,
  std::string* error)
{
  const AxisBlocks blocks[3] = { AxisBlocks(cut.End[0] - cut.Begin[0], f),
    AxisBlocks(cut.End[1] - cut.Begin[1], f), AxisBlocks(cut.End[2] - cut.Begin[2], f) };
  coarseGeometry = piece.Whole;
  double first[3];
  for (int a = 0; a < 3; ++a)
  {
    coarseGeometry.Dimensions[a] = blocks[a].Count;
    coarseGeometry.Spacing[a] = f * piece.Whole.Spacing[a];
    first[a] = cut.Begin[a] + blocks[a].First;
  }
  piece.Whole.IndexToWorld(first, coarseGeometry.Origin);
  const std::size_t m = static_cast<std::size_t>(coarseGeometry.NumberOfVoxels());
  // Every process makes the same one sum below; one that counts the whole cut (a whole image
  // on one process) adds its blocks in parallel (BlockMeans: the same sums in the same order).
  const bool all = CountsAll(piece, cut);
  std::vector<double> means(m + 1, 0.0);
  if (all)
  {
    VoxelBox inHeld = cut;
    for (int a = 0; a < 3; ++a)
    {
      inHeld.Begin[a] -= piece.Held.Begin[a];
      inHeld.End[a] -= piece.Held.Begin[a];
    }
    ImageGeometry ignored;
    BlockMeans(piece.Image.Box(inHeld), f, coarse, ignored, numberOfThreads);
    std::copy(coarse.begin(), coarse.end(), means.begin()); // floats: exact in double
  }
  else
  {
    // Each block's mean comes from the piece counting its first voxel, summed there in the
    // serial order (so in the same double roundings), and 0 from the others: the sum over the
    // processes is the serial mean exactly. The last entry counts the pieces that lacked a block.
    const VoxelBox counted = Intersect(piece.CountedVoxels(), cut);
    std::size_t b = 0;
    for (int K = 0; K < blocks[2].Count; ++K)
      for (int J = 0; J < blocks[1].Count; ++J)
        for (int I = 0; I < blocks[0].Count; ++I, ++b)
        {
          VoxelBox block;
          const int index[3] = { I, J, K };
          for (int a = 0; a < 3; ++a)
          {
            blocks[a].Range(index[a], block.Begin[a], block.End[a]);
            block.Begin[a] += cut.Begin[a];
            block.End[a] += cut.Begin[a];
          }
          VoxelBox corner = block;
          for (int a = 0; a < 3; ++a)
          {
            corner.End[a] = corner.Begin[a] + 1;
          }
          if (!counted.Contains(corner))
          {
            continue;
          }
          if (!piece.Held.Contains(block))
          {
            means[m] = 1.0;
            continue;
          }
          double sum = 0.0;
          int count = 0;
          ForEachHeldVoxel(piece, block,
            [&](int, int, int, float v)
            {
              sum += v;
              ++count;
            });
          means[b] = sum / count;
        }
  }
  reduce.Sum(means);
  if (means[m] > 0.0)
  {
    if (error)
    {
      *error = "a piece holds too few ghost layers for blocks of " + std::to_string(f) +
        " voxels (" + std::to_string(2 * f) + " needed)";
    }
    return false;
  }
  coarse.resize(m);
  for (std::size_t c = 0; c < m; ++c)
  {
    coarse[c] = static_cast<float>(means[c]);
  }
  return true;
}

namespace
{
/// Coarse scales: the block means of every piece, summed over the processes, give each the
/// block means of the cut, and from them the serial coarse field.
bool CoarsePieceForce(const ImagePiece& piece, const VoxelBox& cut, int f,
  const ScaleSpaceParameters& parameters, const PieceReductions& reduce, ForceField& out,
  std::string* error)
{
  std::vector<float> coarse;
  ImageGeometry coarseGeometry;
  std::string message;
  if (!PieceBlockMeans(
        piece, cut, f, parameters.NumberOfThreads, reduce, coarse, coarseGeometry, &message))
  {
    *error = message + " (sigma " + std::to_string(parameters.Sigma) + ")";
    return false;
  }
  ImageGeometry cutGeometry = piece.Whole;
  for (int a = 0; a < 3; ++a)
  {
    cutGeometry.Dimensions[a] = cut.End[a] - cut.Begin[a];
  }
  ScaleSpaceParameters remaining = parameters;
  remaining.Sigma = RemainingSigma(parameters.Sigma, cutGeometry, f);
  if (!ComputeScaleSpaceForce(coarse.data(), coarseGeometry, remaining, out, error))
  {
    return false;
  }
  out.Sigma = parameters.Sigma;
  out.Image = piece.Whole;
  return true;
}

/// The owned voxels of `cut` and their ghosts, or an empty box (with `error`) when the piece
/// does not hold them all.
VoxelBox FineRegion(const ImagePiece& piece, const VoxelBox& cut, double sigma, std::string& error)
{
  VoxelBox region = Intersect(piece.Owned, cut);
  for (int a = 0; a < 3; ++a)
  {
    const int ghost = PieceGhostVoxels(sigma, piece.Whole, a);
    region.Begin[a] = std::max(cut.Begin[a], region.Begin[a] - ghost);
    region.End[a] = std::min(cut.End[a], region.End[a] + ghost);
  }
  if (!piece.Held.Contains(region))
  {
    error = "the piece holds too few ghost layers for sigma " + std::to_string(sigma) + " (" +
      std::to_string(PieceGhostVoxels(sigma, piece.Whole, 0)) + " voxels needed)";
    return VoxelBox();
  }
  return region;
}

/// Whether a fine field over `region` (FineRegion) is smoothed in slabs: when it holds more than
/// SlabSmoothingShare of the piece's voxels, as a serial field is over more than that share of
/// the image (dsFieldGrid.h).
bool PieceFieldInSlabs(const ImagePiece& piece, const VoxelBox& region)
{
  return static_cast<double>(region.NumberOfVoxels()) >
    SlabSmoothingShare * static_cast<double>(piece.Held.NumberOfVoxels());
}

/// Fine scales: the field on the owned voxels and their ghosts, normalised by the largest edge
/// strength of all pieces; with a `surface`, P and -grad P only in the bricks around it (as the
/// serial field's). A failed piece still takes part in the reduction (with an infinite maximum,
/// which tells the others).
bool FinePieceForce(const ImagePiece& piece, const VoxelBox& cut,
  const ScaleSpaceParameters& parameters, const PieceReductions& reduce, ForceField& out,
  std::string* error, const TriangleMesh* surface)
{
  std::string problem;
  double sigmaVoxels[3];
  for (int a = 0; a < 3; ++a)
  {
    sigmaVoxels[a] = parameters.Sigma / piece.Whole.Spacing[a];
  }
  if (Intersect(piece.Owned, cut).NumberOfVoxels() == 0)
  {
    // Nothing of the box here: no field (its vertices are other pieces'), but the sums of the
    // recursive Gaussian and a maximum of 0.
    SmoothPieceGaussian(piece, cut, VoxelBox(), nullptr, sigmaVoxels, reduce);
    const double gMax = reduce.Max(0.0);
    *error = std::isfinite(gMax) ? std::string() : "another process's piece failed";
    return std::isfinite(gMax);
  }
  const VoxelBox region = FineRegion(piece, cut, parameters.Sigma, problem);
  // The region as a view of the piece's values (read in place, in their own type), placed
  // by the whole image's geometry as the serial field's box is.
  VoxelBox inHeld = region;
  for (int a = 0; a < 3; ++a)
  {
    inHeld.Begin[a] = problem.empty() ? region.Begin[a] - piece.Held.Begin[a] : 0;
    inHeld.End[a] = problem.empty() ? region.End[a] - piece.Held.Begin[a] : 0;
  }
  ImageView regionImage = piece.Image.Box(inHeld);
  double first[3];
  for (int a = 0; a < 3; ++a)
  {
    first[a] = region.Begin[a];
  }
  piece.Whole.IndexToWorld(first, regionImage.Geometry.Origin);
  // The serial normalisation: by the largest g of the whole image (of the cut), the largest of
  // every piece's owned voxels (their g is the serial one).
  ScaleSpaceParameters pieceParameters = parameters;
  const VoxelBox owned = Intersect(piece.Owned, cut);
  for (int a = 0; a < 3; ++a)
  {
    pieceParameters.MaximumBegin[a] = owned.Begin[a] - region.Begin[a];
    pieceParameters.MaximumEnd[a] = owned.End[a] - region.Begin[a];
  }
  bool smoothed = false, reduced = false;
  pieceParameters.Smooth = [&](float* volume, const double sv[3])
  {
    smoothed = true;
    SmoothPieceGaussian(piece, cut, region, volume, sv, reduce);
  };
  double gMax = 0.0;
  pieceParameters.GradientMaximum = [&](double ownedMaximum)
  {
    reduced = true;
    gMax = reduce.Max(ownedMaximum);
    return gMax;
  };
  // A region of more than half the piece is smoothed in slabs and kept near the surface only,
  // from the states the pieces pass (the same sums as SmoothPieceGaussian's, so the processes
  // need not agree on which way each takes).
  SlabSource slabs;
  const bool inSlabs = problem.empty() && surface && PieceFieldInSlabs(piece, region);
  if (inSlabs)
  {
    smoothed = true;
    const auto smoothing = std::make_shared<const PieceSmoothing>(GatherPieceSmoothing(
      piece, cut, region, &regionImage, sigmaVoxels, 0, parameters.NumberOfThreads, reduce));
    slabs = [regionImage, smoothing](
              int coreSlices, const std::function<void(const SmoothSlab&)>& visit)
    { SmoothPieceInSlabs(regionImage, *smoothing, coreSlices, visit); };
    pieceParameters.Smooth = nullptr;
  }
  if (problem.empty() && surface)
  {
    ComputeBrickedForce(
      regionImage, pieceParameters, *surface, out, &problem, inSlabs, false, slabs);
  }
  else if (problem.empty())
  {
    ComputeScaleSpaceForce(regionImage, pieceParameters, out, &problem);
  }
  // Failed before smoothing or the normalisation: the others still wait for these sums.
  if (!smoothed)
  {
    SmoothPieceGaussian(piece, cut, VoxelBox(), nullptr, sigmaVoxels, reduce);
  }
  if (!reduced)
  {
    gMax = reduce.Max(std::numeric_limits<double>::infinity());
  }
  if (!problem.empty() || !std::isfinite(gMax))
  {
    *error = problem.empty() ? "another process's piece failed" : problem;
    out = ForceField();
    return false;
  }
  out.Sigma = parameters.Sigma;
  out.Image = piece.Whole;
  return true;
}
} // namespace

bool ComputePieceForce(const ImagePiece& piece, const VoxelBox& box,
  const ScaleSpaceParameters& parameters, const PieceReductions& reduce, ForceField& out,
  std::string* error, const TriangleMesh* surface)
{
  out = ForceField();
  std::string problem = ScaleSpaceProblem(piece.Whole, parameters.Sigma);
  if (problem.empty() &&
    (parameters.ImageWeight != 0.0 || !(parameters.EdgeWeight > 0.0) ||
      !parameters.NormalizePotential ||
      parameters.EdgeNormalization != EdgeNormalization::GlobalMaximum))
  {
    problem = "a distributed image supports the default potential only (EdgeWeight > 0, "
              "ImageWeight 0, the global maximum normalisation)";
  }
  if (!problem.empty()) // the same on every process: none makes a reduction
  {
    if (error)
    {
      *error = problem;
    }
    return false;
  }
  VoxelBox cut;
  const int f = FieldCutFactor(box, piece.Whole, parameters.Sigma, cut);
  std::string message;
  const bool ok = f > 1 ? CoarsePieceForce(piece, cut, f, parameters, reduce, out, &message)
                        : FinePieceForce(piece, cut, parameters, reduce, out, &message, surface);
  if (!ok && error)
  {
    *error = message;
  }
  return ok;
}

double PieceFieldBytes(
  const ImagePiece& piece, const VoxelBox& box, const ScaleSpaceParameters& parameters)
{
  VoxelBox cut;
  const int f = FieldCutFactor(box, piece.Whole, parameters.Sigma, cut);
  if (f > 1)
  {
    // Every process holds the whole cut's coarse grid, and the block means' sums in double
    // (PieceBlockMeans).
    return FieldGridVoxels(cut, f) * (FieldBytesPerVoxel(false) + sizeof(double));
  }
  std::string ignored;
  const VoxelBox region = FineRegion(piece, cut, parameters.Sigma, ignored);
  const bool bricked = FieldInBricks(box, piece.Whole, parameters);
  const double bytes = static_cast<double>(region.NumberOfVoxels()) * FieldBytesPerVoxel(bricked);
  if (!bricked || !PieceFieldInSlabs(piece, region))
  {
    return bytes;
  }
  // In slabs: the tiles at most the region's voxels (counted above as its G_sigma * f: a bound,
  // since the tiles near the surface are fewer), the slabs while they are smoothed, and the
  // pieces' states at the region's ends.
  return bytes + SmoothInSlabsBytes(BoxGeometry(piece.Whole, region), parameters.Sigma, 0) +
    PieceSmoothingBytes(region);
}

std::string PieceProblem(const ImagePiece& piece)
{
  if (piece.Owned.NumberOfVoxels() <= 0)
  {
    return "its piece of the image is empty";
  }
  const ImageGeometry held = piece.HeldGeometry();
  if (!piece.Image.Data || !piece.Held.Contains(piece.Owned) ||
    !std::equal(held.Dimensions, held.Dimensions + 3, piece.Image.Geometry.Dimensions) ||
    !VoxelBox::Whole(piece.Whole).Contains(piece.Held))
  {
    return "its piece of the image is invalid (no values, or not the voxels it should hold)";
  }
  return std::string();
}

std::string CheckPieces(const ImagePiece& piece, const PieceReductions& reduce)
{
  const std::string mine = PieceProblem(piece);
  const double failed = reduce.Max(mine.empty() ? 0.0 : 1.0);
  if (failed == 0.0)
  {
    return std::string();
  }
  return mine.empty() ? std::string("another process's piece of the image is empty or invalid")
                      : mine;
}

long long CountPieceVoxelsInRange(
  const ImagePiece& piece, double lo, double hi, const PieceReductions& reduce)
{
  std::vector<double> count{ 0.0 };
  ForEachHeldVoxel(piece, piece.CountedVoxels(),
    [&](int, int, int, float v) { count[0] += v >= lo && v <= hi ? 1.0 : 0.0; });
  reduce.Sum(count);
  return static_cast<long long>(count[0]);
}

ForceExchange OwnerForceExchange(const ImagePiece& piece, const PieceReductions& reduce)
{
  return [piece, reduce](VertexForce* forces, int count)
  {
    // Per vertex: the force and 1 when this process sampled it, else zeros.
    std::vector<double> v(4 * static_cast<std::size_t>(count), 0.0);
    for (int i = 0; i < count; ++i)
    {
      if (piece.OwnsCell(forces[i].Position.data()))
      {
        for (int a = 0; a < 3; ++a)
        {
          v[4 * i + a] = forces[i].Force[a];
        }
        v[4 * i + 3] = forces[i].Outside ? 0.0 : 1.0;
      }
    }
    reduce.Sum(v);
    for (int i = 0; i < count; ++i)
    {
      forces[i].Force = { v[4 * i], v[4 * i + 1], v[4 * i + 2] };
      forces[i].Outside = v[4 * i + 3] > 0.0 ? 0 : 1;
    }
  };
}
} // namespace dsurf
