// SPDX-License-Identifier: BSD-3-Clause
// Trilinear interpolation in a regular grid: the one home of the cell lookup and corner
// weights that the force field (dsScaleSpace.h: SampleForce, SampleVolume) and the seed's
// intensity rule (vtkDelaunaySeedSurface) use. Header-only so that the solver's per-vertex
// samples stay inlined.
#ifndef dsTrilinear_h
#define dsTrilinear_h

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace dsurf
{
/// The cell holding a continuous index: the linear id of its lower corner, the id step per
/// axis (0 along an axis with one sample) and the fractions along each axis.
struct TrilinearCell
{
  long long Base = 0;
  long long Step[3] = { 0, 0, 0 };
  double T[3] = { 0, 0, 0 };

  /// Linear id of corner `corner` (bit a set = the upper sample along axis a).
  long long Corner(int corner) const
  {
    return this->Base + (corner & 1) * this->Step[0] + ((corner >> 1) & 1) * this->Step[1] +
      ((corner >> 2) & 1) * this->Step[2];
  }
  /// Trilinear weight of that corner.
  double Weight(int corner) const
  {
    return ((corner & 1) ? this->T[0] : 1.0 - this->T[0]) *
      (((corner >> 1) & 1) ? this->T[1] : 1.0 - this->T[1]) *
      (((corner >> 2) & 1) ? this->T[2] : 1.0 - this->T[2]);
  }
};

/// Adds the trilinear sample in `cell` of a field of three values per sample (x, y, z) to f.
inline void AddTrilinearVector(const float* values, const TrilinearCell& cell, double f[3])
{
  for (int corner = 0; corner < 8; ++corner)
  {
    const double w = cell.Weight(corner);
    const float* v = values + 3 * cell.Corner(corner);
    f[0] += w * v[0];
    f[1] += w * v[1];
    f[2] += w * v[2];
  }
}

/// floor(v) for a finite v within the range of long long, without the libm call that std::floor
/// is on the baseline x86-64 (no SSE4.1 round instruction): truncation, one less below zero.
inline long long Floor(double v)
{
  const long long t = static_cast<long long>(v);
  return t - (static_cast<double>(t) > v ? 1 : 0);
}

/// The cell of continuous index ijk in a grid whose samples are lo[a] .. hi[a] along axis a
/// (x fastest; linear ids count from lo). An index up to `tolerance` beyond the first or last
/// sample is clamped onto it (the border value); further out, or an empty axis: false.
/// increments: the id step per axis when the samples are not contiguous (a box of a larger
/// array); nullptr: contiguous from lo to hi.
inline bool LocateTrilinearCell(const double ijk[3], const int lo[3], const int hi[3],
  double tolerance, TrilinearCell& cell, const std::ptrdiff_t* increments = nullptr)
{
  long long stride = 1;
  cell.Base = 0;
  for (int a = 0; a < 3; ++a)
  {
    if (hi[a] < lo[a] || !(ijk[a] >= lo[a] - tolerance && ijk[a] <= hi[a] + tolerance))
    {
      return false;
    }
    long long i0 = lo[a];
    double t = 0.0;
    if (hi[a] > lo[a])
    {
      const double v =
        std::min(std::max(ijk[a], static_cast<double>(lo[a])), static_cast<double>(hi[a]));
      i0 = std::min(Floor(v), static_cast<long long>(hi[a] - 1));
      t = v - static_cast<double>(i0);
    }
    const long long step = increments ? static_cast<long long>(increments[a]) : stride;
    cell.Base += (i0 - lo[a]) * step;
    cell.Step[a] = hi[a] > lo[a] ? step : 0;
    cell.T[a] = t;
    stride *= hi[a] - lo[a] + 1;
  }
  return true;
}
} // namespace dsurf

#endif
