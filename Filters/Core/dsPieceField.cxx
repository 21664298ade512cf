#include "dsPieceField.h"

#include "dsGaussianSmoother.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dsurf
{
ImageGeometry ImagePiece::HeldGeometry() const
{
  ImageGeometry g = this->Whole;
  double first[3];
  for (int a = 0; a < 3; ++a)
  {
    g.Dimensions[a] = this->Held.End[a] - this->Held.Begin[a];
    first[a] = this->Held.Begin[a];
  }
  this->Whole.IndexToWorld(first, g.Origin);
  return g;
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
  // Two voxels for the central differences of g and of P, and the Gaussian's reach
  // (dsGaussianSmoother.h): the sampled kernel's radius exactly; for the recursive filter the
  // reach at which a cut changes the field by < 1e-6 of its maximum (measured by
  // TestPieceField: ghosts of 6, 8, 10, 12, 14 sigma left 4e-4, 8e-6, 3e-6, 1e-6, 4e-7).
  const double s = sigma / whole.Spacing[a];
  const double reach = s < GaussianRecursiveFromSigmaVoxels ? std::ceil(4.0 * s) : std::ceil(14.0 * s);
  return static_cast<int>(std::min(reach, 1e8)) + 2;
}

namespace
{
/// The block layout BlockMeans (dsFieldGrid.h) uses on an axis of n voxels: blocks of f
/// centred on voxels first + I f, the end blocks taking in the voxels left over.
struct AxisBlocks
{
  int Count = 0, First = 0;
  std::vector<int> OfVoxel; ///< the block of every voxel of the axis

  AxisBlocks(int n, int f)
  {
    const int h = f / 2;
    this->Count = (n - 1) / f + 1;
    this->First = (n - 1 - (this->Count - 1) * f) / 2;
    this->OfVoxel.resize(n);
    for (int I = 0; I < this->Count; ++I)
    {
      const int begin = I == 0 ? 0 : this->First + I * f - h;
      const int end = I == this->Count - 1 ? n : this->First + I * f + h + 1;
      std::fill(this->OfVoxel.begin() + begin, this->OfVoxel.begin() + end, I);
    }
  }
};

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

/// Calls visit(i, j, k, value) for the piece's voxels in `voxels` (whole-image indices).
template <typename Visit>
void ForEachHeldVoxel(const ImagePiece& piece, const VoxelBox& voxels, Visit&& visit)
{
  const std::ptrdiff_t nx = piece.Held.End[0] - piece.Held.Begin[0];
  const std::ptrdiff_t slice = nx * (piece.Held.End[1] - piece.Held.Begin[1]);
  for (int k = voxels.Begin[2]; k < voxels.End[2]; ++k)
  {
    for (int j = voxels.Begin[1]; j < voxels.End[1]; ++j)
    {
      const float* row = piece.Scalars + (k - piece.Held.Begin[2]) * slice +
        (j - piece.Held.Begin[1]) * nx - piece.Held.Begin[0];
      for (int i = voxels.Begin[0]; i < voxels.End[0]; ++i)
      {
        visit(i, j, k, row[i]);
      }
    }
  }
}

/// Coarse scales: the block sums of every piece, summed over the processes, give each the
/// block means of the cut, and from them the serial coarse field.
bool CoarsePieceForce(const ImagePiece& piece, const VoxelBox& cut, int f,
  const ScaleSpaceParameters& parameters, const PieceReductions& reduce, ForceField& out,
  std::string* error)
{
  ImageGeometry cutGeometry = piece.Whole;
  const AxisBlocks blocks[3] = { AxisBlocks(cut.End[0] - cut.Begin[0], f),
    AxisBlocks(cut.End[1] - cut.Begin[1], f), AxisBlocks(cut.End[2] - cut.Begin[2], f) };
  ImageGeometry coarseGeometry = piece.Whole;
  double first[3];
  for (int a = 0; a < 3; ++a)
  {
    coarseGeometry.Dimensions[a] = blocks[a].Count;
    coarseGeometry.Spacing[a] = f * piece.Whole.Spacing[a];
    first[a] = cut.Begin[a] + blocks[a].First;
    cutGeometry.Dimensions[a] = cut.End[a] - cut.Begin[a];
  }
  piece.Whole.IndexToWorld(first, coarseGeometry.Origin);
  const std::size_t m = static_cast<std::size_t>(coarseGeometry.NumberOfVoxels());
  std::vector<double> sums(2 * m, 0.0); // the sums, then the counts
  ForEachHeldVoxel(piece, Intersect(piece.CountedVoxels(), cut),
    [&](int i, int j, int k, float value)
    {
      const std::size_t b = blocks[0].OfVoxel[i - cut.Begin[0]] +
        blocks[0].Count *
          (blocks[1].OfVoxel[j - cut.Begin[1]] +
            static_cast<std::size_t>(blocks[1].Count) * blocks[2].OfVoxel[k - cut.Begin[2]]);
      sums[b] += value;
      sums[m + b] += 1.0;
    });
  reduce.Sum(sums);
  std::vector<float> coarse(m);
  for (std::size_t b = 0; b < m; ++b)
  {
    coarse[b] = static_cast<float>(sums[b] / sums[m + b]);
  }
  ScaleSpaceParameters remaining = parameters;
  remaining.Sigma = RemainingSigma(parameters.Sigma, cutGeometry, f);
  if (!ComputeScaleSpaceForce(coarse.data(), coarseGeometry, remaining, out, error))
  {
    return false;
  }
  out.Sigma = parameters.Sigma;
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

/// Fine scales: the unnormalised field on the owned voxels and their ghosts, normalised by the
/// largest edge strength of all pieces. A failed piece still takes part in the reduction (with
/// an infinite maximum, which tells the others).
bool FinePieceForce(const ImagePiece& piece, const VoxelBox& cut,
  const ScaleSpaceParameters& parameters, const PieceReductions& reduce, ForceField& out,
  std::string* error)
{
  std::string problem;
  if (Intersect(piece.Owned, cut).NumberOfVoxels() == 0)
  {
    // Nothing of the box here: no field (its vertices are other pieces'), and a maximum of 0.
    const double gMax = reduce.Max(0.0);
    *error = std::isfinite(gMax) ? std::string() : "another process's piece failed";
    return std::isfinite(gMax);
  }
  const VoxelBox region = FineRegion(piece, cut, parameters.Sigma, problem);
  ImageGeometry regionGeometry = piece.Whole;
  std::vector<float> values;
  values.reserve(static_cast<std::size_t>(region.NumberOfVoxels()));
  ForEachHeldVoxel(piece, region, [&](int, int, int, float v) { values.push_back(v); });
  double first[3];
  for (int a = 0; a < 3; ++a)
  {
    regionGeometry.Dimensions[a] = region.End[a] - region.Begin[a];
    first[a] = region.Begin[a];
  }
  piece.Whole.IndexToWorld(first, regionGeometry.Origin);
  ScaleSpaceParameters raw = parameters;
  raw.NormalizePotential = false; // P = -EdgeWeight g
  double localMax = std::numeric_limits<double>::infinity();
  if (problem.empty() && ComputeScaleSpaceForce(values.data(), regionGeometry, raw, out, &problem))
  {
    // g on the owned voxels (their edge strengths are the serial ones).
    localMax = 0.0;
    const VoxelBox owned = Intersect(piece.Owned, cut);
    const int* n = regionGeometry.Dimensions;
    for (int k = owned.Begin[2]; k < owned.End[2]; ++k)
      for (int j = owned.Begin[1]; j < owned.End[1]; ++j)
        for (int i = owned.Begin[0]; i < owned.End[0]; ++i)
        {
          const std::size_t v = (i - region.Begin[0]) +
            static_cast<std::size_t>(n[0]) *
              ((j - region.Begin[1]) + static_cast<std::size_t>(n[1]) * (k - region.Begin[2]));
          localMax = std::max(localMax, -out.Potential[v] / parameters.EdgeWeight);
        }
  }
  const double gMax = reduce.Max(localMax);
  if (!std::isfinite(gMax))
  {
    *error = problem.empty() ? "another process's piece failed" : problem;
    out = ForceField();
    return false;
  }
  // The serial normalisation, P = -(EdgeWeight / max g) g, and -grad P scaled alike.
  const double scale = gMax > 0.0 ? 1.0 / gMax : 0.0;
  for (float& p : out.Potential)
  {
    p = static_cast<float>(scale * p);
  }
  for (float& f : out.Force)
  {
    f = static_cast<float>(scale * f);
  }
  out.Sigma = parameters.Sigma;
  return true;
}
} // namespace

bool ComputePieceForce(const ImagePiece& piece, const VoxelBox& box,
  const ScaleSpaceParameters& parameters, const PieceReductions& reduce, ForceField& out,
  std::string* error)
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
  // The cut and the block size as ComputeForceAtScale chooses them.
  const VoxelBox cut = 2 * box.NumberOfVoxels() <= piece.Whole.NumberOfVoxels()
    ? box
    : VoxelBox::Whole(piece.Whole);
  ImageGeometry cutGeometry = piece.Whole;
  for (int a = 0; a < 3; ++a)
  {
    cutGeometry.Dimensions[a] = cut.End[a] - cut.Begin[a];
  }
  const int f = DecimationFactor(parameters.Sigma, cutGeometry);
  std::string message;
  const bool ok = f > 1
    ? CoarsePieceForce(piece, cut, f, parameters, reduce, out, &message)
    : FinePieceForce(piece, cut, parameters, reduce, out, &message);
  if (!ok && error)
  {
    *error = message;
  }
  return ok;
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
