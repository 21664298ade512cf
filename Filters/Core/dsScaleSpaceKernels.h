// SPDX-License-Identifier: BSD-3-Clause
// The kernels of the scale-space field that dsScaleSpace.cxx (the field over a box, the staged
// and slab-wise G_sigma * f) and dsLocalPotential.cxx (the locally normalised potential at
// chosen voxels) share: the world gradient of a smoothed volume row by row, the edge statistics
// and the potential's gains. Internal to the module. Plain C++.
#ifndef dsScaleSpaceKernels_h
#define dsScaleSpaceKernels_h

#include "dsImageView.h"
#include "dsScaleSpace.h"
#include "dsThreads.h"

#include "vtkSMPTools.h"

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace dsurf
{
namespace scalespace
{
/// Range of the smoothed image and maximum of its gradient magnitude.
struct EdgeStatistics
{
  double GradientMax = 0, SmoothMin = 0, SmoothMax = 0;
};

// Runs body with vtkSMPTools on the STDThread backend (the machine default is
// Sequential), limited to n threads.
template <typename F>
inline void WithThreads(int n, F&& body)
{
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ ResolveThreads(n), "STDThread", false }, body);
}

// World gradient of a scalar field from index-space central differences.
struct GradientToWorld
{
  double J[9]; // Direction * diag(1/spacing)
  explicit GradientToWorld(const ImageGeometry& g)
  {
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        this->J[3 * r + c] = g.Direction[3 * r + c] / g.Spacing[c];
      }
    }
  }
  void Apply(const double gi[3], double gw[3]) const
  {
    gw[0] = this->J[0] * gi[0] + this->J[1] * gi[1] + this->J[2] * gi[2];
    gw[1] = this->J[3] * gi[0] + this->J[4] * gi[1] + this->J[5] * gi[2];
    gw[2] = this->J[6] * gi[0] + this->J[7] * gi[1] + this->J[8] * gi[2];
  }
  /// J^T w: a world covector (the gradient of a function of the world gradient) to index space.
  void ApplyTransposed(const double w[3], double wi[3]) const
  {
    wi[0] = this->J[0] * w[0] + this->J[3] * w[1] + this->J[6] * w[2];
    wi[1] = this->J[1] * w[0] + this->J[4] * w[1] + this->J[7] * w[2];
    wi[2] = this->J[2] * w[0] + this->J[5] * w[1] + this->J[8] * w[2];
  }
};

// Index-space derivative along one axis at position p of n: central inside,
// one-sided at the border (n >= 2 is guaranteed by Validate).
inline double Diff(const float* v, int p, int n, std::ptrdiff_t step)
{
  if (p == 0)
  {
    return static_cast<double>(v[step]) - v[0];
  }
  if (p == n - 1)
  {
    return static_cast<double>(v[0]) - v[-step];
  }
  return 0.5 * (static_cast<double>(v[step]) - v[-step]);
}

/// The world gradient of `values` at the voxel v points at, grid position p of a grid of n
/// voxels whose neighbours lie step[a] values away along axis a: central differences in index
/// space, one-sided at the grid's border, turned to world.
inline void WorldGradientAt(const float* v, const int p[3], const int n[3],
  const std::ptrdiff_t step[3], const GradientToWorld& toWorld, double gw[3])
{
  const double gi[3] = { Diff(v, p[0], n[0], step[0]), Diff(v, p[1], n[1], step[1]),
    Diff(v, p[2], n[2], step[2]) };
  toWorld.Apply(gi, gw);
}

/// g^2 (double) of the voxels 1 .. nx - 2 of a row whose voxels all have both neighbours along
/// y and z: WorldGradientAt's arithmetic (central differences, then to world), written so that
/// the loop vectorises.
inline void InnerRowSquares(const float* __restrict row, std::ptrdiff_t sy, std::ptrdiff_t sz,
  int nx, const GradientToWorld& toWorld, double* __restrict squares)
{
  const double* J = toWorld.J;
  const double j0 = J[0], j1 = J[1], j2 = J[2], j3 = J[3], j4 = J[4], j5 = J[5], j6 = J[6],
               j7 = J[7], j8 = J[8];
  for (int i = 1; i < nx - 1; ++i)
  {
    const double a = 0.5 * (static_cast<double>(row[i + 1]) - row[i - 1]);
    const double b = 0.5 * (static_cast<double>(row[i + sy]) - row[i - sy]);
    const double c = 0.5 * (static_cast<double>(row[i + sz]) - row[i - sz]);
    const double w0 = j0 * a + j1 * b + j2 * c;
    const double w1 = j3 * a + j4 * b + j5 * c;
    const double w2 = j6 * a + j7 * b + j8 * c;
    squares[i] = w0 * w0 + w1 * w1 + w2 * w2;
  }
}

/// Calls visit(row, squares) for every row of slice k of a grid of dims voxels, squares[i] the
/// squared world gradient at voxel i of the row (WorldGradientAt's arithmetic: InnerRowSquares
/// inside, WorldGradientAt at the border); `slice` points at the slice's first value, its
/// neighbour slices a slice away (they need not be more of a volume: a slab of one,
/// dsSmoothSlabs.h). row: the row's offset in the whole grid.
// Always inlined, with ForEachRowSquares: as one file's own helper the compiler inlined it into
// each caller's loop; shared, it did not into SlabEdges (dsLocalPotential.cxx), whose slabs then
// took twice as long (BenchScale's tight spheres at 512^3: 6-10 % longer in all).
template <typename Visit>
[[gnu::always_inline]] inline void ForEachRowSquaresOfSlice(
  const float* slice, const int dims[3], const GradientToWorld& toWorld, int k, Visit&& visit)
{
  const int nx = dims[0], ny = dims[1];
  const std::ptrdiff_t step[3] = { 1, nx, static_cast<std::ptrdiff_t>(nx) * ny };
  std::vector<double> squares(nx);
  for (int j = 0; j < ny; ++j)
  {
    const float* values = slice + j * step[1];
    const bool inner = nx > 2 && j > 0 && j < ny - 1 && k > 0 && k < dims[2] - 1;
    for (int i = 0; i < nx; i += inner && i == 0 ? nx - 1 : 1)
    {
      const int p[3] = { i, j, k };
      double gw[3];
      WorldGradientAt(values + i, p, dims, step, toWorld, gw);
      squares[i] = gw[0] * gw[0] + gw[1] * gw[1] + gw[2] * gw[2];
    }
    if (inner)
    {
      InnerRowSquares(values, step[1], step[2], nx, toWorld, squares.data());
    }
    visit(k * step[2] + j * step[1], squares.data());
  }
}

/// ForEachRowSquaresOfSlice of slice k of the volume `values`.
template <typename Visit>
[[gnu::always_inline]] inline void ForEachRowSquares(
  const float* values, const int dims[3], const GradientToWorld& toWorld, int k, Visit&& visit)
{
  ForEachRowSquaresOfSlice(values + k * (static_cast<std::ptrdiff_t>(dims[0]) * dims[1]), dims,
    toWorld, k, std::forward<Visit>(visit));
}

/// P of one voxel from its edge strength g (as stored, a float) and smoothed value s.
inline float PotentialOf(float g, float s, const PotentialGains& gains)
{
  return static_cast<float>(-(gains.Edge * g + gains.Image * s + gains.Offset));
}

/// G_sigma * f of `image` into `smooth`: an image of another type (or a box of a larger one)
/// is converted there first and smoothed in place, with the same result; on a piece of a
/// distributed image by `pieceSmooth` (ScaleSpaceParameters::Smooth). In the caller's SMP scope.
void SmoothImage(const ImageView& image, const double sigmaVoxels[3], float* smooth,
  const std::function<void(float*, const double*)>& pieceSmooth = nullptr);

/// sigma in voxels along each axis.
void SigmaVoxels(double sigma, const ImageGeometry& geometry, double sv[3]);

/// The local edge normalisation asked for P alone (ScaleSpaceParameters::ComputeForce).
bool PotentialOnly(const ScaleSpaceParameters& parameters);

/// Why ComputeScaleSpaceForceInto cannot run on these inputs; empty when it can.
std::string CheckForceInputs(const ImageView& image, const ScaleSpaceParameters& parameters,
  const float* potential, const float* force);

/// The gains of P = -(Edge g + Image s + Offset) (docs/METHOD.md §2, with the optional
/// normalisation of both terms), g divided by gNorm when normalised.
PotentialGains GainsOf(
  const EdgeStatistics& stats, double gNorm, const ScaleSpaceParameters& parameters);
} // namespace scalespace
} // namespace dsurf

#endif
