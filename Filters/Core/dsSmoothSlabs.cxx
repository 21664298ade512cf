// SPDX-License-Identifier: BSD-3-Clause
#include "dsSmoothSlabs.h"

#include "dsGaussianSmoother.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace dsurf
{
namespace
{
constexpr int StateDoubles = RecursiveAxisPass::States;

/// The states a pass starts from, or null (the lines' own end) when there are none.
const double* StatesOrNull(const std::vector<double>& states)
{
  return states.empty() ? nullptr : states.data();
}

/// The most slices a core has.
int LongestCore(const std::vector<int>& cores)
{
  int longest = 0;
  for (std::size_t s = 0; s + 1 < cores.size(); ++s)
  {
    longest = std::max(longest, cores[s + 1] - cores[s]);
  }
  return longest;
}

/// The sampled Gaussian (or none) along z. Each slice is read once, into a window of the slices
/// the slab's z pass reads (its radius on either side of the slab; the window's later slices
/// move to its front for the next slab); the z pass computes the slab's slices alone, and the
/// x and y passes smooth those.
void SampledSlabs(const int dims[3], const double sv[3], int core, const SlabSlices& slices,
  const SlabPassesXY& passesXY, const std::function<void(const SmoothSlab&)>& visit)
{
  const int nz = dims[2];
  const int radius = std::max(0, GaussianAxisReach(sv[2]));
  const std::ptrdiff_t slice = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  const std::vector<int> cores = SlabCores(nz, core);
  const int longest = LongestCore(cores);
  std::vector<float> window(
    static_cast<std::size_t>(std::min(nz, longest + 2 + 2 * radius) * slice));
  std::vector<float> out(static_cast<std::size_t>(std::min(nz, longest + 2) * slice));
  int w0 = 0, w1 = 0; // the window holds slices [w0, w1)
  for (std::size_t s = 0; s + 1 < cores.size(); ++s)
  {
    const int f0 = std::max(0, cores[s] - 1), f1 = std::min(nz, cores[s + 1] + 1);
    const int i0 = std::max(0, f0 - radius), i1 = std::min(nz, f1 + radius);
    // The window's slices from i0 on move to its front (i0 only grows); the rest are read.
    const int kept = std::max(0, w1 - i0);
    if (kept > 0 && i0 > w0)
    {
      std::copy_n(window.data() + (i0 - w0) * slice, kept * slice, window.data());
    }
    slices(i0 + kept, i1, window.data() + kept * slice);
    w0 = i0;
    w1 = i1;
    const int wdims[3] = { dims[0], dims[1], w1 - w0 };
    SampledAxisZ(window.data(), out.data(), wdims, sv[2], f0 - w0, f1 - w0);
    passesXY(out.data(), f0, f1 - f0);
    visit(SmoothSlab{ out.data(), f0, f1 - f0, cores[s], cores[s + 1] });
  }
}

/// The recursive filter along z, in two passes (the header's comment): slab s covers its core
/// and one slice on either side within the volume, and is visited on the pass down, after its
/// x and y passes.
void RecursiveSlabs(const int dims[3], const double sv[3], int core, const SlabSlices& slices,
  const SlabPassesXY& passesXY, const AxisEnds& z,
  const std::function<void(const SmoothSlab&)>& visit)
{
  const std::vector<int> cores = SlabCores(dims[2], core);
  RecursiveSlabsZ slabs(dims, sv[2], cores, 1, slices, z);
  slabs.Prepare(
    [&](int s, std::vector<float>& values)
    {
      const int first = slabs.Begin(s), count = slabs.End(s) - slabs.Begin(s);
      passesXY(values.data(), first, count);
      visit(SmoothSlab{ values.data(), first, count, cores[s], cores[s + 1] });
    });
}
} // namespace

std::vector<int> SlabCores(int nz, int core)
{
  // Several cores have two slices or more (RecursiveSlabs records the state after a core's
  // last but one).
  const int slabs = std::max(1, std::min((nz + core - 1) / core, nz / 2));
  std::vector<int> first(slabs + 1);
  for (int s = 0; s <= slabs; ++s)
  {
    first[s] = static_cast<int>(static_cast<long long>(nz) * s / slabs);
  }
  return first;
}

void SlicesAsFloat(const ImageView& image, int z0, int z1, float* out)
{
  VoxelBox slab = VoxelBox::Whole(image.Geometry);
  slab.Begin[2] = z0;
  slab.End[2] = z1;
  CopyToFloat(image.Box(slab), out);
}

void SmoothSlabXY(float* values, int nx, int ny, int count, const double sigmaVoxels[3])
{
  const int dims[3] = { nx, ny, count };
  const double sv[3] = { sigmaVoxels[0], sigmaVoxels[1], 0.0 };
  SmoothGaussianSeparable(values, values, dims, sv);
}

RecursiveSlabsZ::RecursiveSlabsZ(const int dims[3], double sigmaVoxelsZ, std::vector<int> cores,
  int margin, Input input, AxisEnds ends)
  : Sigma(sigmaVoxelsZ)
  , Cores(std::move(cores))
  , Margin(margin)
  , Produce(std::move(input))
{
  std::copy(dims, dims + 3, this->Dims);
  // A margin of one slice at most, and cores that cover the volume (SlabCores): the recorded
  // positions lie inside the slabs only then (RecursiveAxisPass ignores one outside).
  assert(margin >= 0 && margin <= 1);
  assert(this->Cores.size() >= 2 && this->Cores.front() == 0 && this->Cores.back() == dims[2]);
  this->Starts.resize(this->Slabs());
  this->Aheads.resize(this->Slabs());
  // The first slab starts, and the last ends, where the volume does: from the states given there.
  this->Starts.front() = std::move(ends.Start);
  this->Aheads.back() = std::move(ends.Ahead);
}

int RecursiveSlabsZ::Begin(int s) const
{
  return std::max(0, this->Cores[s] - this->Margin);
}

int RecursiveSlabsZ::End(int s) const
{
  return std::min(this->Dims[2], this->Cores[s + 1] + this->Margin);
}

void RecursiveSlabsZ::Prepare(const Visit& visit)
{
  const std::ptrdiff_t slice = static_cast<std::ptrdiff_t>(this->Dims[0]) * this->Dims[1];
  std::vector<float> buffer;
  std::vector<std::vector<double>> recorded;
  std::vector<double> carry; // the forward state after the previous core's last slice
  for (int s = 0; s + 1 < this->Slabs(); ++s)
  {
    const int n = this->Cores[s + 1] - this->Cores[s];
    buffer.resize(static_cast<std::size_t>(n * slice));
    this->Produce(this->Cores[s], this->Cores[s + 1], buffer.data());
    const int dims[3] = { this->Dims[0], this->Dims[1], n };
    RecursiveAxisPass pass(buffer.data(), dims, 2, this->Sigma);
    // After the core's last slice and, with a margin, after the slice before the next slab's
    // first (cores have two slices or more when there are several).
    std::vector<int> record{ n - 1 };
    if (this->Margin > 0)
    {
      record.push_back(this->Begin(s + 1) - 1 - this->Cores[s]);
    }
    assert(this->Cores[s + 1] - this->Cores[s] >= 2);
    pass.Forward(s > 0 ? carry.data() : StatesOrNull(this->Starts[0]), record, recorded);
    carry = std::move(recorded[0]);
    this->Starts[s + 1] = this->Margin > 0 ? std::move(recorded[1]) : carry;
  }
  // With a visitor the pass down is the last: each slab's states are freed once it ran, so
  // that the pass holds one backward state at a time (Slab may not follow).
  this->Prepared = !visit;
  std::vector<double>().swap(carry);
  for (int s = this->Slabs() - 1; s >= (visit ? 0 : 1); --s)
  {
    this->Run(s, buffer, true);
    if (visit)
    {
      std::vector<double>().swap(this->Starts[s]);
      std::vector<double>().swap(this->Aheads[s]);
      visit(s, buffer);
    }
  }
}

void RecursiveSlabsZ::Run(int s, std::vector<float>& values, bool recordBelow)
{
  const int f0 = this->Begin(s), f1 = this->End(s);
  values.resize(static_cast<std::size_t>(f1 - f0) * this->Dims[0] * this->Dims[1]);
  this->Produce(f0, f1, values.data());
  const int dims[3] = { this->Dims[0], this->Dims[1], f1 - f0 };
  RecursiveAxisPass pass(values.data(), dims, 2, this->Sigma);
  std::vector<std::vector<double>> recorded;
  // A slab's start is recorded unless it starts the volume's lines (as is its ahead state, below).
  assert(s == 0 || !this->Starts[s].empty());
  assert(s + 1 == this->Slabs() || !this->Aheads[s].empty());
  pass.Forward(StatesOrNull(this->Starts[s]), {}, recorded);
  // The slab below ends at End(s - 1) (exclusive): its backward recursion starts from the state
  // after that slice, unless it reaches the volume's end.
  std::vector<int> record;
  if (recordBelow && s > 0 && this->End(s - 1) < this->Dims[2])
  {
    record.push_back(this->End(s - 1) - f0);
  }
  pass.Backward(StatesOrNull(this->Aheads[s]), record, recorded);
  if (!record.empty())
  {
    this->Aheads[s - 1] = std::move(recorded[0]);
  }
}

void RecursiveSlabsZ::Slab(int s, std::vector<float>& values)
{
  assert(this->Prepared);
  this->Run(s, values, false);
}

int DefaultSlabCore(const int dims[3], double sigmaVoxelsZ)
{
  const int reach = GaussianAxisReach(sigmaVoxelsZ);
  if (reach < 0)
  {
    return std::max(4, static_cast<int>(std::lround(std::sqrt(10.0 * dims[2]))));
  }
  return std::max(32, 4 * reach);
}

void SmoothSlabsOf(const int dims[3], const double sigmaVoxels[3], int coreSlices,
  const SlabSlices& slices, const AxisEnds& z, const SlabPassesXY& passesXY,
  const std::function<void(const SmoothSlab&)>& visit)
{
  const int core = std::max(2, coreSlices > 0 ? coreSlices : DefaultSlabCore(dims, sigmaVoxels[2]));
  if (GaussianAxisReach(sigmaVoxels[2]) < 0)
  {
    RecursiveSlabs(dims, sigmaVoxels, core, slices, passesXY, z, visit);
  }
  else
  {
    SampledSlabs(dims, sigmaVoxels, core, slices, passesXY, visit);
  }
}

void SmoothInSlabs(const ImageView& image, const double sigmaVoxels[3], int coreSlices,
  const std::function<void(const SmoothSlab&)>& visit)
{
  const int* dims = image.Geometry.Dimensions;
  SmoothSlabsOf(
    dims, sigmaVoxels, coreSlices,
    [&](int z0, int z1, float* out) { SlicesAsFloat(image, z0, z1, out); }, AxisEnds(),
    [&](float* values, int, int count)
    { SmoothSlabXY(values, dims[0], dims[1], count, sigmaVoxels); },
    visit);
}

double SmoothInSlabsBytes(const ImageGeometry& geometry, double sigma, int coreSlices)
{
  const int* dims = geometry.Dimensions;
  const double sigmaVoxels[3] = { sigma / geometry.Spacing[0], sigma / geometry.Spacing[1],
    sigma / geometry.Spacing[2] };
  const int core = std::max(2, coreSlices > 0 ? coreSlices : DefaultSlabCore(dims, sigmaVoxels[2]));
  const int longest = LongestCore(SlabCores(dims[2], core));
  const double slice = static_cast<double>(dims[0]) * dims[1];
  const int reach = GaussianAxisReach(sigmaVoxels[2]);
  if (reach >= 0)
  {
    // The window of slices the z pass reads, and the slab's output.
    return sizeof(float) * slice *
      (std::min(dims[2], longest + 2 + 2 * reach) + std::min(dims[2], longest + 2));
  }
  // A slab's floats, the recorded starts of the slabs, and a pass's own states (its saved end
  // state and last input, two recorded states and the state carried between slabs).
  const double slabs = static_cast<double>(SlabCores(dims[2], core).size() - 1);
  return sizeof(float) * slice * std::min(dims[2], longest + 2) +
    sizeof(double) * slice * (StateDoubles * (slabs - 1) + (StateDoubles + 1) + 3 * StateDoubles);
}
} // namespace dsurf
