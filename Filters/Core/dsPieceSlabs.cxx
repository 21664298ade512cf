// SPDX-License-Identifier: BSD-3-Clause
#include "dsPieceSlabs.h"

#include "dsGaussianSmoother.h"
#include "dsPieceGaussian.h"
#include "dsThreads.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <memory>
#include <vector>

namespace dsurf
{
namespace
{
constexpr int K = RecursiveAxisPass::States;

/// The states from `offset` on, or null (the serial start) when there are none.
const double* StatesAt(const std::vector<double>& states, std::size_t offset)
{
  return states.empty() ? nullptr : states.data() + offset;
}

/// A volume's lines along axis a (0 or 1) in each of its slices: the lines of slices from z0 on
/// start at line z0 times this (RecursiveAxisPass's order: the lower other axis fastest).
std::size_t LinesPerSlice(const int dims[3], int a)
{
  return static_cast<std::size_t>(a == 0 ? dims[1] : dims[0]);
}

/// The pass along axis a (0 or 1) of the region's slices from z0 on, held in `slab`, as
/// SmoothPieceGaussian makes it: the serial pass, or from the ends' states on an axis with rounds.
void SmoothSlabAxis(float* slab, const int dims[3], int a, int z0, const PieceSmoothing& smoothing)
{
  if (!smoothing.Rounds[a])
  {
    SmoothGaussianAxis(slab, dims, a, smoothing.SigmaVoxels[a]);
    return;
  }
  const std::size_t offset = K * LinesPerSlice(dims, a) * z0;
  RecursiveAxisPass pass(slab, dims, a, smoothing.SigmaVoxels[a]);
  std::vector<std::vector<double>> none;
  pass.Forward(StatesAt(smoothing.Ends[a].Start, offset), {}, none);
  pass.Backward(StatesAt(smoothing.Ends[a].Ahead, offset), {}, none);
}

/// The region's slabs (coreSlices each, 0: DefaultSlabCore) smoothed along z and then along
/// the first `axesXY` of x and y (0, 1 or 2), as SmoothPieceGaussian makes them: visit(slab).
void EachSmoothedSlab(const ImageView& regionImage, const PieceSmoothing& smoothing, int axesXY,
  int coreSlices, const std::function<void(const SmoothSlab&)>& visit)
{
  const int* dims = regionImage.Geometry.Dimensions;
  SmoothSlabsOf(
    dims, smoothing.SigmaVoxels, coreSlices,
    [&](int z0, int z1, float* out) { SlicesAsFloat(regionImage, z0, z1, out); },
    smoothing.Rounds[2] ? smoothing.Ends[2] : AxisEnds(),
    [&](float* values, int first, int count)
    {
      const int slabDims[3] = { dims[0], dims[1], count };
      for (int a = 0; a < axesXY; ++a)
      {
        SmoothSlabAxis(values, slabDims, a, first, smoothing);
      }
    },
    visit);
}

/// The positions of `record` shifted to start at `first` (those outside a slab from there are
/// out of its range, which RecursiveAxisPass ignores), and `extra` (when not negative) unless
/// one of them is it: *extraSlot says where it is (RecursiveAxisPass records a position once;
/// meaningless when `extra` is negative).
std::vector<int> LocalRecord(const std::vector<int>& record, int first, int extra, int* extraSlot)
{
  std::vector<int> local;
  for (const int p : record)
  {
    local.push_back(p - first);
  }
  const auto at = std::find(local.begin(), local.end(), extra);
  *extraSlot = static_cast<int>(at - local.begin());
  if (extra >= 0 && at == local.end())
  {
    local.push_back(extra);
  }
  return local;
}

/// A run of the rounds (dsPieceGaussian.h) along axis a that streams the region slab by slab and
/// keeps no values: it records the states asked for, and keeps the states it starts from in the
/// smoothing's ends along a.
class StreamedRun : public PieceAxisRun
{
public:
  StreamedRun(const ImageView& regionImage, PieceSmoothing& smoothing, int a, int core)
    : RegionImage(regionImage)
    , Smoothing(smoothing)
    , Axis(a)
    , Core(core)
    , Cores(SlabCores(regionImage.Geometry.Dimensions[2], core))
  {
    const int* dims = regionImage.Geometry.Dimensions;
    this->Lines = a == 0 ? static_cast<std::size_t>(dims[1]) * dims[2]
                         : static_cast<std::size_t>(dims[0]) * dims[a == 1 ? 2 : 1];
  }

  void Forward(const double* start, const std::vector<int>& record,
    std::vector<std::vector<double>>& recorded) override
  {
    Keep(start, this->Smoothing.Ends[this->Axis].Start);
    recorded.assign(record.size(), std::vector<double>(K * this->Lines));
    if (record.empty()) // no piece goes on from here: nothing to run
    {
      return;
    }
    if (this->Axis == 2)
    {
      this->ForwardZ(record, recorded, nullptr);
      return;
    }
    this->EachSlab(
      [&](RecursiveAxisPass& pass, std::size_t offset, std::vector<std::vector<double>>& states)
      { pass.Forward(StatesAt(this->Smoothing.Ends[this->Axis].Start, offset), record, states); },
      recorded);
  }

  void Backward(const double* ahead, const std::vector<int>& record,
    std::vector<std::vector<double>>& recorded) override
  {
    Keep(ahead, this->Smoothing.Ends[this->Axis].Ahead);
    recorded.assign(record.size(), std::vector<double>(K * this->Lines));
    if (record.empty())
    {
      return;
    }
    if (this->Axis == 2)
    {
      this->BackwardZ(record, recorded);
      return;
    }
    const AxisEnds& ends = this->Smoothing.Ends[this->Axis];
    this->EachSlab(
      [&](RecursiveAxisPass& pass, std::size_t offset, std::vector<std::vector<double>>& states)
      {
        pass.Forward(StatesAt(ends.Start, offset), {}, states);
        pass.Backward(StatesAt(ends.Ahead, offset), record, states);
      },
      recorded);
  }

private:
  /// The states a run starts from (K per line of the region), kept for SmoothPieceInSlabs.
  void Keep(const double* states, std::vector<double>& kept) const
  {
    if (states)
    {
      kept.assign(states, states + K * this->Lines);
    }
    else
    {
      kept.clear();
    }
  }

  const int* Dims() const { return this->RegionImage.Geometry.Dimensions; }

  int Slabs() const { return static_cast<int>(this->Cores.size()) - 1; }

  /// Along x or y: each slab's own slices smoothed along z and the axes before a (the rounds
  /// along z ran first: the smoothing's ends along z are known), then run(pass over them, the
  /// offset of their lines' states, the states recorded), the records copied into place.
  template <typename Run>
  void EachSlab(Run&& run, std::vector<std::vector<double>>& recorded)
  {
    std::vector<float> buffer;
    std::vector<std::vector<double>> states;
    const std::ptrdiff_t slice = static_cast<std::ptrdiff_t>(this->Dims()[0]) * this->Dims()[1];
    EachSmoothedSlab(this->RegionImage, this->Smoothing, this->Axis, this->Core,
      [&](const SmoothSlab& slab)
      {
        const int dims[3] = { this->Dims()[0], this->Dims()[1], slab.Core1 - slab.Core0 };
        const float* own = slab.Values + (slab.Core0 - slab.First) * slice;
        buffer.assign(own, own + dims[2] * slice);
        RecursiveAxisPass pass(
          buffer.data(), dims, this->Axis, this->Smoothing.SigmaVoxels[this->Axis]);
        const std::size_t offset = K * LinesPerSlice(dims, this->Axis) * slab.Core0;
        run(pass, offset, states);
        for (std::size_t r = 0; r < recorded.size(); ++r)
        {
          std::copy(states[r].begin(), states[r].end(), recorded[r].begin() + offset);
        }
      });
  }

  /// Slab s's slices into `buffer`, and a pass along z over them (the first axis smoothed).
  std::unique_ptr<RecursiveAxisPass> SlabZ(int s, std::vector<float>& buffer) const
  {
    const int z0 = this->Cores[s], z1 = this->Cores[s + 1];
    const int dims[3] = { this->Dims()[0], this->Dims()[1], z1 - z0 };
    buffer.resize(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]);
    SlicesAsFloat(this->RegionImage, z0, z1, buffer.data());
    return std::unique_ptr<RecursiveAxisPass>(
      new RecursiveAxisPass(buffer.data(), dims, 2, this->Smoothing.SigmaVoxels[2]));
  }

  /// The forward recursion along z up the slabs, from the region's start, recording as asked;
  /// with `starts`, each slab's forward start kept there too (the first's is the region's).
  void ForwardZ(const std::vector<int>& record, std::vector<std::vector<double>>& recorded,
    std::vector<std::vector<double>>* starts)
  {
    std::vector<float> buffer;
    std::vector<std::vector<double>> states;
    std::vector<double> carry; // the forward state after the previous slab's last slice
    // Only for the slabs' starts (nothing recorded), the last slab need not run.
    const int slabs = starts && record.empty() ? this->Slabs() - 1 : this->Slabs();
    for (int s = 0; s < slabs; ++s)
    {
      const int n = this->Cores[s + 1] - this->Cores[s];
      std::unique_ptr<RecursiveAxisPass> pass = this->SlabZ(s, buffer);
      int last = 0;
      pass->Forward(s > 0 ? carry.data() : StatesAt(this->Smoothing.Ends[2].Start, 0),
        LocalRecord(record, this->Cores[s], n - 1, &last), states);
      carry = states[last];
      this->Collect(s, record, states, recorded);
      if (starts && s + 1 < this->Slabs())
      {
        starts->push_back(carry);
      }
    }
  }

  /// The backward recursion along z down the slabs, each slab's forward one first from the start
  /// a pass up recorded, recording as asked.
  void BackwardZ(const std::vector<int>& record, std::vector<std::vector<double>>& recorded)
  {
    std::vector<std::vector<double>> starts(1), none;
    this->ForwardZ({}, none, &starts); // starts[s] for s > 0
    std::vector<float> buffer;
    std::vector<std::vector<double>> states;
    std::vector<double> ahead = this->Smoothing.Ends[2].Ahead;
    for (int s = this->Slabs() - 1; s >= 0; --s)
    {
      std::unique_ptr<RecursiveAxisPass> pass = this->SlabZ(s, buffer);
      pass->Forward(
        s > 0 ? starts[s].data() : StatesAt(this->Smoothing.Ends[2].Start, 0), {}, states);
      std::vector<double>().swap(starts[s]);
      // The slab below goes on from the state after this slab's first slice.
      int first = 0;
      pass->Backward(
        StatesAt(ahead, 0), LocalRecord(record, this->Cores[s], s > 0 ? 0 : -1, &first), states);
      if (s > 0)
      {
        ahead = states[first];
      }
      this->Collect(s, record, states, recorded);
    }
  }

  /// The states of slab s recorded at positions of `record` within its core, moved into place.
  void Collect(int s, const std::vector<int>& record, std::vector<std::vector<double>>& states,
    std::vector<std::vector<double>>& recorded) const
  {
    for (std::size_t r = 0; r < record.size(); ++r)
    {
      if (record[r] >= this->Cores[s] && record[r] < this->Cores[s + 1])
      {
        recorded[r] = std::move(states[r]);
      }
    }
  }

  const ImageView& RegionImage;
  PieceSmoothing& Smoothing;
  int Axis;
  int Core;               // the slices of a slab's own part
  std::vector<int> Cores; // the slabs along z of a run along z
  std::size_t Lines = 0;
};
} // namespace

double PieceSmoothingBytes(const VoxelBox& region)
{
  double lines = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    lines +=
      static_cast<double>(region.NumberOfVoxels()) / std::max(1, region.End[a] - region.Begin[a]);
  }
  return 2.0 * K * sizeof(double) * lines;
}

PieceSmoothing GatherPieceSmoothing(const ImagePiece& piece, const VoxelBox& cut,
  const VoxelBox& region, const ImageView* regionImage, const double sigmaVoxels[3], int coreSlices,
  int numberOfThreads, const PieceReductions& reduce)
{
  PieceSmoothing smoothing;
  std::copy(sigmaVoxels, sigmaVoxels + 3, smoothing.SigmaVoxels);
  int core = 0;
  if (regionImage)
  {
    core = std::max(2,
      coreSlices > 0 ? coreSlices
                     : DefaultSlabCore(regionImage->Geometry.Dimensions, sigmaVoxels[2]));
  }
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ ResolveThreads(numberOfThreads), "STDThread", false },
    [&]()
    {
      PieceGaussianRounds(
        piece, cut, region, regionImage != nullptr, sigmaVoxels,
        [&](int a) -> std::unique_ptr<PieceAxisRun>
        {
          smoothing.Rounds[a] = true;
          return std::unique_ptr<PieceAxisRun>(new StreamedRun(*regionImage, smoothing, a, core));
        },
        [](int) {}, reduce);
    });
  return smoothing;
}

void SmoothPieceInSlabs(const ImageView& regionImage, const PieceSmoothing& smoothing,
  int coreSlices, const std::function<void(const SmoothSlab&)>& visit)
{
  EachSmoothedSlab(regionImage, smoothing, 2, coreSlices, visit);
}
} // namespace dsurf
