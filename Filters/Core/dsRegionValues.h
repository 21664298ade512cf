// SPDX-License-Identifier: BSD-3-Clause
// The values the intensity range's estimates share (docs/METHOD.md §9.3): the voxel rows a piece
// counts, read in the input's own type, and the quantiles of values sampled by all processes,
// which every process gets exactly as a sort of all of them would give (docs/METHOD.md §9.8).
// Both the range of a start against the background just outside it (dsRegion.cxx) and a click's
// competition among the classes around it (dsClickCompetition.cxx) read the image through them.
// Plain C++, used by those two files only.
#ifndef dsRegionValues_h
#define dsRegionValues_h

#include "dsFieldGrid.h"
#include "dsImageView.h"
#include "dsPieceField.h"

#include <vector>

namespace dsurf
{
/// Calls row(j, k, values) for every row (j, k) of `box` (whole-image indices, held by the
/// piece), values pointing at voxel (box.Begin[0], j, k) in the input's own type.
template <typename Row>
void ForEachCountedRow(const ImagePiece& piece, const VoxelBox& box, Row&& row)
{
  const int* h = piece.Held.Begin;
  VisitValues(piece.Image,
    [&](const auto* values)
    {
      for (int k = box.Begin[2]; k < box.End[2]; ++k)
      {
        for (int j = box.Begin[1]; j < box.End[1]; ++j)
        {
          row(j, k, values + piece.Image.RowOffset(j - h[1], k - h[2]) + (box.Begin[0] - h[0]));
        }
      }
    });
}

/// This process's share of values sampled by all processes, and the count of all of them.
struct SharedValues
{
  const std::vector<float>& Values;
  long long Count;
};

/// The count of `values` summed over all processes.
long long CountOfAll(const std::vector<float>& values, const PieceReductions& reduce);

/// The value at fraction q in [0, 1] of all processes' values (Count > 0): the k-th smallest,
/// k = q (n - 1) rounded, found digit by digit of OrderKey (11, 11 and 10 bits) from the
/// summed histograms of each share: every process gets the value a sort of all of them gives.
double Quantile(const SharedValues& all, double q, const PieceReductions& reduce);
} // namespace dsurf

#endif
