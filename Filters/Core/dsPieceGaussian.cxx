// SPDX-License-Identifier: BSD-3-Clause
#include "dsPieceGaussian.h"

#include "dsGaussianSmoother.h"

#include <algorithm>
#include <memory>
#include <vector>

namespace dsurf
{
namespace
{
constexpr int K = RecursiveAxisPass::States;

bool IsRecursive(double sigmaVoxels)
{
  return sigmaVoxels >= GaussianRecursiveFromSigmaVoxels;
}

/// The other two axes of a, lower first (the order of RecursiveAxisPass's lines).
void CrossAxes(int a, int& b0, int& b1)
{
  b0 = a == 0 ? 1 : 0;
  b1 = a == 2 ? 1 : 2;
}

/// Every process's first and last voxel of its region along each axis: Firsts ascending, Lasts
/// descending, distinct (whole-image indices). One sum.
struct RegionEnds
{
  std::vector<int> Firsts[3], Lasts[3];
};

RegionEnds GatherEnds(
  const VoxelBox& cut, const VoxelBox& region, bool hasRegion, const PieceReductions& reduce)
{
  std::vector<double> flags;
  std::size_t offset[3];
  for (int a = 0; a < 3; ++a)
  {
    offset[a] = flags.size();
    const int n = cut.End[a] - cut.Begin[a];
    flags.resize(flags.size() + 2 * static_cast<std::size_t>(n), 0.0);
    if (hasRegion)
    {
      flags[offset[a] + region.Begin[a] - cut.Begin[a]] = 1.0;
      flags[offset[a] + n + region.End[a] - 1 - cut.Begin[a]] = 1.0;
    }
  }
  reduce.Sum(flags);
  RegionEnds ends;
  for (int a = 0; a < 3; ++a)
  {
    const int n = cut.End[a] - cut.Begin[a];
    for (int p = 0; p < n; ++p)
    {
      if (flags[offset[a] + p] > 0.0)
      {
        ends.Firsts[a].push_back(cut.Begin[a] + p);
      }
      if (flags[offset[a] + n + (n - 1 - p)] > 0.0)
      {
        ends.Lasts[a].push_back(cut.Begin[a] + n - 1 - p);
      }
    }
  }
  return ends;
}

/// One round along axis a: the states of the plane p (a position along a, whole-image
/// indices) summed over the processes, each giving `states` (recorded at p, per line of its
/// region; null when it has none) for the voxels it counts; returned per line of the region.
std::vector<double> ExchangePlane(const ImagePiece& piece, const VoxelBox& cut,
  const VoxelBox& region, int a, int p, const std::vector<double>* states,
  const PieceReductions& reduce)
{
  int b0, b1;
  CrossAxes(a, b0, b1);
  const long long cu = cut.End[b0] - cut.Begin[b0], cv = cut.End[b1] - cut.Begin[b1];
  const long long ru = region.End[b0] - region.Begin[b0];
  const auto cutIndex = [&](int u, int v)
  { return (u - cut.Begin[b0]) + cu * (v - cut.Begin[b1]); };
  const auto lineIndex = [&](int u, int v)
  { return (u - region.Begin[b0]) + ru * (v - region.Begin[b1]); };
  std::vector<double> plane(static_cast<std::size_t>(K * cu * cv), -0.0);
  VoxelBox counted = piece.CountedVoxels();
  for (int c = 0; c < 3; ++c)
  {
    counted.Begin[c] = std::max(counted.Begin[c], cut.Begin[c]);
    counted.End[c] = std::min(counted.End[c], cut.End[c]);
  }
  if (states && p >= counted.Begin[a] && p < counted.End[a])
  {
    for (int v = counted.Begin[b1]; v < counted.End[b1]; ++v)
      for (int u = counted.Begin[b0]; u < counted.End[b0]; ++u)
      {
        std::copy_n(states->data() + K * lineIndex(u, v), K, plane.data() + K * cutIndex(u, v));
      }
  }
  reduce.Sum(plane);
  std::vector<double> lines(K * ru * (region.End[b1] - region.Begin[b1]));
  for (int v = region.Begin[b1]; v < region.End[b1]; ++v)
    for (int u = region.Begin[b0]; u < region.End[b0]; ++u)
    {
      std::copy_n(plane.data() + K * cutIndex(u, v), K, lines.data() + K * lineIndex(u, v));
    }
  return lines;
}

/// The positions along a (whole-image indices) whose states other pieces start from, and the
/// slots RecursiveAxisPass records them in on this region (-1: not in the region).
struct Records
{
  std::vector<int> Local;                  // positions in the region, for the pass
  std::vector<std::vector<double>> States; // filled by the pass
  int SlotOf(int localPosition) const
  {
    const auto it = std::find(this->Local.begin(), this->Local.end(), localPosition);
    return it == this->Local.end() ? -1 : static_cast<int>(it - this->Local.begin());
  }
};

/// The recursive filter along axis a in rounds: forward from the cut's first voxel on, then
/// backward from its last (see the header). `axisRun` is null on a process with no region.
void RecursiveRounds(const ImagePiece& piece, const VoxelBox& cut, const VoxelBox& region, int a,
  const RegionEnds& ends, PieceAxisRun* axisRun, const PieceReductions& reduce)
{
  for (const bool forward : { true, false })
  {
    // Forward: the pieces starting at Firsts[t] take the state after Firsts[t] - 1; backward:
    // those ending at Lasts[t] take the state after Lasts[t] + 1 (backward).
    const std::vector<int>& starts = forward ? ends.Firsts[a] : ends.Lasts[a];
    const int mine = forward ? region.Begin[a] : region.End[a] - 1;
    const int cutEnd = forward ? cut.Begin[a] : cut.End[a] - 1;
    Records records;
    for (std::size_t t = 1; t < starts.size() && axisRun; ++t)
    {
      const int p = starts[t] + (forward ? -1 : 1);
      if (p >= region.Begin[a] && p < region.End[a])
      {
        records.Local.push_back(p - region.Begin[a]);
      }
    }
    const auto run = [&](const double* from)
    {
      if (forward)
      {
        axisRun->Forward(from, records.Local, records.States);
      }
      else
      {
        axisRun->Backward(from, records.Local, records.States);
      }
    };
    bool ran = false;
    if (axisRun && mine == cutEnd)
    {
      run(nullptr);
      ran = true;
    }
    for (std::size_t t = 1; t < starts.size(); ++t)
    {
      const int p = starts[t] + (forward ? -1 : 1);
      const int slot = ran ? records.SlotOf(p - region.Begin[a]) : -1;
      const std::vector<double> lines = ExchangePlane(
        piece, cut, region, a, p, slot >= 0 ? &records.States[slot] : nullptr, reduce);
      if (axisRun && mine == starts[t] && mine != cutEnd)
      {
        run(lines.data());
        ran = true;
      }
    }
  }
}

/// RecursiveAxisPass over the region held whole.
class WholeRegionRun : public PieceAxisRun
{
public:
  WholeRegionRun(float* volume, const int dims[3], int a, double sigmaVoxels)
    : Pass(volume, dims, a, sigmaVoxels)
  {
  }
  void Forward(const double* start, const std::vector<int>& record,
    std::vector<std::vector<double>>& recorded) override
  {
    this->Pass.Forward(start, record, recorded);
  }
  void Backward(const double* ahead, const std::vector<int>& record,
    std::vector<std::vector<double>>& recorded) override
  {
    this->Pass.Backward(ahead, record, recorded);
  }

private:
  RecursiveAxisPass Pass;
};
} // namespace

void PieceGaussianRounds(const ImagePiece& piece, const VoxelBox& cut, const VoxelBox& region,
  bool hasRegion, const double sigmaVoxels[3],
  const std::function<std::unique_ptr<PieceAxisRun>(int axis)>& runOf,
  const std::function<void(int axis)>& uncut, const PieceReductions& reduce)
{
  const bool recursive = std::any_of(sigmaVoxels, sigmaVoxels + 3, IsRecursive);
  const RegionEnds ends = recursive ? GatherEnds(cut, region, hasRegion, reduce) : RegionEnds();
  // The axes in the serial order (z, x, y: SmoothGaussianSeparable), each pass reading the
  // previous one's floats.
  for (const int a : { 2, 0, 1 })
  {
    // A sampled axis, or a recursive one no piece is cut along: the serial pass itself.
    if (!IsRecursive(sigmaVoxels[a]) || (ends.Firsts[a].size() <= 1 && ends.Lasts[a].size() <= 1))
    {
      uncut(a);
      continue;
    }
    std::unique_ptr<PieceAxisRun> run = hasRegion ? runOf(a) : nullptr;
    RecursiveRounds(piece, cut, region, a, ends, run.get(), reduce);
  }
}

void SmoothPieceGaussian(const ImagePiece& piece, const VoxelBox& cut, const VoxelBox& region,
  float* volume, const double sigmaVoxels[3], const PieceReductions& reduce)
{
  int dims[3];
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = region.End[a] - region.Begin[a];
  }
  PieceGaussianRounds(
    piece, cut, region, volume != nullptr, sigmaVoxels,
    [&](int a) -> std::unique_ptr<PieceAxisRun>
    { return std::unique_ptr<PieceAxisRun>(new WholeRegionRun(volume, dims, a, sigmaVoxels[a])); },
    [&](int a)
    {
      if (volume)
      {
        SmoothGaussianAxis(volume, dims, a, sigmaVoxels[a]);
      }
    },
    reduce);
}
} // namespace dsurf
