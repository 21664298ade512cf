// SPDX-License-Identifier: BSD-3-Clause
// The pieces of the emulated processes' tests (EmulatedRanks.h): slabs along z as VTK splits an
// image (neighbouring pieces share their border voxels), each holding a copy of its voxels and
// ghost layers in the image's own type (what a parallel reader gives a rank), and the ranks'
// reductions as PieceReductions.
#ifndef PieceSlabs_h
#define PieceSlabs_h

#include "EmulatedRanks.h"

#include "dsPieceField.h"

#include <algorithm>
#include <functional>
#include <vector>

namespace dstest
{
/// An image of nx x ny x nz voxels with spacing (1, 1.1, 0.9) and origin (-3, 2, 5): world and
/// index coordinates differ by more than a shift, as a scanner's do.
inline dsurf::ImageGeometry AnisotropicGeometry(int nx, int ny, int nz)
{
  dsurf::ImageGeometry g;
  g.Dimensions[0] = nx;
  g.Dimensions[1] = ny;
  g.Dimensions[2] = nz;
  g.Spacing[0] = 1.0;
  g.Spacing[1] = 1.1;
  g.Spacing[2] = 0.9;
  g.Origin[0] = -3;
  g.Origin[1] = 2;
  g.Origin[2] = 5;
  return g;
}

/// The piece owning `owned` (whole-image indices) with ghost(a) ghost layers along axis a,
/// clipped to the image; its Image is left unset. An empty piece (nothing owned or held) when
/// `empty`.
inline dsurf::ImagePiece PieceBoxes(const dsurf::ImageGeometry& g, const dsurf::VoxelBox& owned,
  const std::function<int(int)>& ghost, bool empty = false)
{
  dsurf::ImagePiece piece;
  piece.Whole = g;
  piece.Owned = owned;
  if (empty)
  {
    piece.Owned.End[2] = piece.Owned.Begin[2];
  }
  piece.Held = piece.Owned;
  for (int a = 0; a < 3 && !empty; ++a)
  {
    piece.Held.Begin[a] = std::max(0, piece.Held.Begin[a] - ghost(a));
    piece.Held.End[a] = std::min(g.Dimensions[a], piece.Held.End[a] + ghost(a));
  }
  return piece;
}

/// The piece owning `owned` (whole-image indices) with ghost(a) ghost layers along axis a,
/// holding a copy of its voxels; an empty piece (nothing owned or held) when `empty`.
template <typename T>
dsurf::ImagePiece PieceOf(const dsurf::ImageGeometry& g, const std::vector<T>& image,
  const dsurf::VoxelBox& owned, const std::function<int(int)>& ghost, std::vector<T>& held,
  bool empty = false)
{
  dsurf::ImagePiece piece = PieceBoxes(g, owned, ghost, empty);
  held.clear();
  const int nx = g.Dimensions[0], ny = g.Dimensions[1];
  for (int k = piece.Held.Begin[2]; k < piece.Held.End[2]; ++k)
    for (int j = piece.Held.Begin[1]; j < piece.Held.End[1]; ++j)
      for (int i = piece.Held.Begin[0]; i < piece.Held.End[0]; ++i)
      {
        held.push_back(image[i + nx * (j + static_cast<std::size_t>(ny) * k)]);
      }
  piece.Image = dsurf::ImageView::Of(held.empty() ? nullptr : held.data(), piece.HeldGeometry());
  return piece;
}

/// Part r of `parts` of the cells of [begin, end) along axis a, as VTK splits an extent: the
/// voxels of those cells (neighbouring parts share their border voxel).
inline void SplitAxis(dsurf::VoxelBox& box, int a, int r, int parts)
{
  const int begin = box.Begin[a], cells = box.End[a] - 1 - begin;
  box.Begin[a] = begin + cells * r / parts;
  box.End[a] = begin + cells * (r + 1) / parts + 1;
}

/// Rank r's slab of `ranks` along z with ghost(a) ghost layers along axis a; an empty piece
/// (nothing owned or held) when `empty`.
template <typename T>
dsurf::ImagePiece Slab(const dsurf::ImageGeometry& g, const std::vector<T>& image, int r, int ranks,
  const std::function<int(int)>& ghost, std::vector<T>& held, bool empty = false)
{
  dsurf::VoxelBox owned = dsurf::VoxelBox::Whole(g);
  SplitAxis(owned, 2, r, ranks);
  return PieceOf(g, image, owned, ghost, held, empty);
}

/// Rank r's slab of `ranks` along z with ghost(a) ghost layers along axis a, a view of the
/// whole image's `values` (x fastest; no copy): a slab's held voxels are one run of them.
template <typename T>
dsurf::ImagePiece SlabView(const dsurf::ImageGeometry& g, const T* values, int r, int ranks,
  const std::function<int(int)>& ghost)
{
  dsurf::VoxelBox owned = dsurf::VoxelBox::Whole(g);
  SplitAxis(owned, 2, r, ranks);
  dsurf::ImagePiece piece = PieceBoxes(g, owned, ghost);
  piece.Image = dsurf::ImageView::Of(
    values + static_cast<std::size_t>(g.Dimensions[0]) * g.Dimensions[1] * piece.Held.Begin[2],
    piece.HeldGeometry());
  return piece;
}

/// Rank r's reductions among `ranks`.
inline dsurf::PieceReductions ReductionsOf(EmulatedRanks& ranks, int r)
{
  dsurf::PieceReductions reduce;
  reduce.Sum = [&ranks, r](std::vector<double>& v) { ranks.Sum(r, v); };
  reduce.Max = [&ranks, r](double v) { return ranks.Max(r, v); };
  return reduce;
}
} // namespace dstest

#endif
