// SPDX-License-Identifier: BSD-3-Clause
#include "dsVoxelSet.h"

namespace dsurf
{
VoxelSet::VoxelSet(long long voxels)
  : Bits(static_cast<std::size_t>((voxels + 63) / 64), 0)
{
}

void VoxelSet::Finish()
{
  this->Before.resize(this->Bits.size());
  long long count = 0;
  for (std::size_t w = 0; w < this->Bits.size(); ++w)
  {
    this->Before[w] = count;
    count += __builtin_popcountll(this->Bits[w]);
  }
  this->Members = count;
}

long long VoxelSet::Rank(long long v) const
{
  const std::size_t w = static_cast<std::size_t>(v >> 6);
  const std::uint64_t below = this->Bits[w] & ((std::uint64_t(1) << (v & 63)) - 1);
  return this->Before[w] + __builtin_popcountll(below);
}

double VoxelSet::Bytes() const
{
  return static_cast<double>(this->Bits.size()) * (sizeof(std::uint64_t) + sizeof(long long));
}
} // namespace dsurf
