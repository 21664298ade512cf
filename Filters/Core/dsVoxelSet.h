// SPDX-License-Identifier: BSD-3-Clause
// A set of voxels of a box, for values wanted at a few of its voxels only (the sigma_0 probe's
// rays, docs/METHOD.md §9.7): one bit a voxel and a count every 64 voxels, so that the members'
// values lie in one array in the order of their linear ids and a member's place is found in
// constant time. Plain C++.
#ifndef dsVoxelSet_h
#define dsVoxelSet_h

#include "DeformableSurfaceFiltersModule.h" // for export macro

#include <algorithm>
#include <cstdint>
#include <vector>

namespace dsurf
{
class DEFORMABLESURFACEFILTERS_EXPORT VoxelSet
{
public:
  /// An empty set of a box of `voxels` voxels (linear ids 0 .. voxels - 1).
  explicit VoxelSet(long long voxels = 0);
  /// Adds voxel v (an id of the box); then Finish before Rank.
  void Insert(long long v) { this->Bits[v >> 6] |= std::uint64_t(1) << (v & 63); }
  /// Counts the members: after it, Rank and Size (no Insert any more).
  void Finish();
  bool Contains(long long v) const { return (this->Bits[v >> 6] >> (v & 63)) & 1; }
  /// The number of members with a smaller id than v (v's place in their values).
  long long Rank(long long v) const;
  long long Size() const { return this->Members; }
  /// Calls visit(v, rank) for the members v in [begin, end), in increasing order.
  template <typename Visit>
  void ForEachIn(long long begin, long long end, Visit&& visit) const
  {
    const long long last = std::min(static_cast<long long>(this->Bits.size()), (end + 63) >> 6);
    for (long long w = begin >> 6; w < last; ++w)
    {
      std::uint64_t bits = this->Bits[w];
      while (bits)
      {
        const long long v = (w << 6) + __builtin_ctzll(bits);
        if (v >= end)
        {
          return;
        }
        if (v >= begin)
        {
          visit(v, this->Rank(v));
        }
        bits &= bits - 1;
      }
    }
  }
  /// Bytes it holds: a quarter of a byte per voxel of its box.
  double Bytes() const;

private:
  std::vector<std::uint64_t> Bits;
  std::vector<long long> Before; ///< members in the words before each
  long long Members = 0;
};
} // namespace dsurf

#endif
