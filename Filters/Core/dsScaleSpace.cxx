// SPDX-License-Identifier: BSD-3-Clause
#include "dsScaleSpace.h"

#include "dsFieldBricks.h"

#include "dsGaussianSmoother.h"
#include "dsSmoothSlabs.h"
#include "dsThreads.h"
#include "dsTrilinear.h"
#include "dsVoxelSet.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <limits>

namespace dsurf
{
bool ForceField::SampleForce(const double x[3], double f[3]) const
{
  f[0] = f[1] = f[2] = 0.0;
  TrilinearCell c;
  if (this->Bricks)
  {
    if (this->Bricks->SampleForce(x, f))
    {
      return true;
    }
    // Beyond the bricks' box but inside the image: a vertex the box should have held.
    const bool inImage = this->Image.Dimensions[0] > 0 && LocateImageCell(this->Image, x, c);
    if (inImage)
    {
      this->Bricks->CountMiss();
    }
    return inImage;
  }
  else if (!this->Force.empty() && LocateImageCell(this->Geometry, x, c))
  {
    AddTrilinearVector(this->Force.data(), c, f);
    return true;
  }
  // Beyond the field's grid: outside the image only when beyond the image itself (a surface
  // leaving a level's box has not left the image).
  return !this->Force.empty() || this->Bricks
    ? this->Image.Dimensions[0] > 0 && LocateImageCell(this->Image, x, c)
    : false;
}

double SampleVolume(
  const float* values, const ImageGeometry& geometry, const double x[3], bool* inside)
{
  return SampleVolume(ImageView::Of(values, geometry), x, inside);
}

double ForceField::SamplePotential(const double x[3]) const
{
  if (this->Bricks)
  {
    return this->Bricks->SamplePotential(x);
  }
  return this->Potential.empty() ? 0.0
                                 : SampleVolume(this->Potential.data(), this->Geometry, x, nullptr);
}

namespace
{
// Runs body with vtkSMPTools on the STDThread backend (the machine default is
// Sequential), limited to n threads.
template <typename F>
void WithThreads(int n, F&& body)
{
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ ResolveThreads(n), "STDThread", false }, body);
}

bool Validate(const ImageGeometry& g, double sigma, std::string* error)
{
  auto fail = [&](const std::string& m)
  {
    if (error)
    {
      *error = m;
    }
    return false;
  };
  if (g.Dimensions[0] <= 0 || g.Dimensions[1] <= 0 || g.Dimensions[2] <= 0)
  {
    return fail("the image is empty");
  }
  if (g.Dimensions[0] < 2 || g.Dimensions[1] < 2 || g.Dimensions[2] < 2)
  {
    return fail("a 3-D image is needed (at least 2 voxels along every axis), got " +
      std::to_string(g.Dimensions[0]) + "x" + std::to_string(g.Dimensions[1]) + "x" +
      std::to_string(g.Dimensions[2]));
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!(g.Spacing[a] > 0.0) || !std::isfinite(g.Spacing[a]))
    {
      return fail("the spacing must be positive and finite");
    }
    if (!std::isfinite(g.Origin[a]))
    {
      return fail("the image origin must be finite");
    }
  }
  if (!std::isfinite(sigma) || sigma < 0.0)
  {
    return fail("sigma must be finite and >= 0");
  }
  // The recursive Gaussian's border start is built over ~40 sigma samples and its sections
  // lose precision as their poles near 1 (dsGaussianSmoother.cxx): far beyond any image.
  for (int a = 0; a < 3; ++a)
  {
    if (sigma / g.Spacing[a] > 1e5)
    {
      char text[160];
      std::snprintf(text, sizeof text,
        "sigma (%g) is too large: %g voxels along %c, at most 100000", sigma, sigma / g.Spacing[a],
        "xyz"[a]);
      return fail(text);
    }
  }
  // World <-> index uses the transpose as the inverse of the direction matrix, and the
  // gradient is turned by it: a shear or a scale would silently give wrong forces.
  const double* D = g.Direction;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double dot = D[r] * D[c] + D[3 + r] * D[3 + c] + D[6 + r] * D[6 + c];
      if (!(std::fabs(dot - (r == c ? 1.0 : 0.0)) <= 1e-6))
      {
        return fail("the image's direction matrix must be a rotation (orthonormal); put scale "
                    "into the spacing and resample sheared images first");
      }
    }
  }
  return true;
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

// Index-space second derivative along one axis at position p of n: [1, -2, 1], the border
// value replicated past the grid's ends (as the Gaussian replicates it).
inline double SecondDiff(const float* v, int p, int n, std::ptrdiff_t step)
{
  const double below = p == 0 ? v[0] : v[-step];
  const double above = p == n - 1 ? v[0] : v[step];
  return above - 2.0 * v[0] + below;
}

// Index-space mixed derivative along axes a != b at grid position p: Diff along b of Diff
// along a (the two commute).
inline double MixedDiff(
  const float* v, const int p[3], const int n[3], const std::ptrdiff_t step[3], int a, int b)
{
  const auto along = [&](std::ptrdiff_t o) { return Diff(v + o, p[a], n[a], step[a]); };
  if (p[b] == 0)
  {
    return along(step[b]) - along(0);
  }
  if (p[b] == n[b] - 1)
  {
    return along(0) - along(-step[b]);
  }
  return 0.5 * (along(step[b]) - along(-step[b]));
}

template <typename Body>
void ForEachVoxelSlice(const int dims[3], Body&& body)
{
  vtkSMPTools::For(0, dims[2],
    [&](int kb, int ke)
    {
      for (int k = kb; k < ke; ++k)
      {
        body(k);
      }
    });
}
} // namespace

namespace
{
// g <- g / (G_2sigma * g + floor) in place (EdgeNormalization::Local); `scratch` holds one
// volume. Returns the new maximum (on a piece of a distributed image, that of every piece:
// ScaleSpaceParameters::GradientMaximum with the largest ratio over the piece's own voxels). A
// Gaussian-weighted local mean, not a local maximum: it is smooth, so dividing by it adds no
// steps (spurious forces) to the potential. For an isolated edge of any contrast the ratio
// peaks at ~sqrt(5) (a Gaussian ridge of width sigma over its own blur at 2 sigma), so every
// isolated boundary ends up equally strong.
double NormalizeEdgesLocally(float* g, float* scratch, const int dims[3],
  const double sigmaVoxels[3], double floor, const ScaleSpaceParameters& parameters)
{
  const double wide[3] = { 2 * sigmaVoxels[0], 2 * sigmaVoxels[1], 2 * sigmaVoxels[2] };
  SmoothGaussianSeparable(g, scratch, dims, wide);
  const std::ptrdiff_t nx = dims[0], sz = nx * dims[1];
  const int* b = parameters.MaximumBegin;
  const int* e = parameters.MaximumEnd;
  std::vector<double> maxima(dims[2], 0.0), boxMaxima(dims[2], 0.0);
  ForEachVoxelSlice(dims,
    [&](int k)
    {
      double m = 0.0, mb = 0.0;
      for (int j = 0; j < dims[1]; ++j)
      {
        const bool rowInBox = k >= b[2] && k < e[2] && j >= b[1] && j < e[1];
        for (std::ptrdiff_t i = 0, v = k * sz + j * nx; i < nx; ++i, ++v)
        {
          const double r = g[v] / (std::max(0.0, static_cast<double>(scratch[v])) + floor);
          g[v] = static_cast<float>(r);
          m = std::max(m, r);
          mb = rowInBox && i >= b[0] && i < e[0] ? std::max(mb, r) : mb;
        }
      }
      maxima[k] = m;
      boxMaxima[k] = mb;
    });
  return parameters.GradientMaximum
    ? parameters.GradientMaximum(*std::max_element(boxMaxima.begin(), boxMaxima.end()))
    : *std::max_element(maxima.begin(), maxima.end());
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

/// Calls visit(p, step, v, o) for every voxel p (grid position) of `part`, a box within `box`
/// and within `valuesBox`: v its place among values known over `valuesBox` (x fastest; step[a]
/// between neighbours along axis a), o its place in `box`.
template <typename Visit>
void ForEachVoxelOfPart(
  const VoxelBox& valuesBox, const VoxelBox& box, const VoxelBox& part, Visit&& visit)
{
  const std::ptrdiff_t sx = valuesBox.End[0] - valuesBox.Begin[0];
  const std::ptrdiff_t step[3] = { 1, sx, sx * (valuesBox.End[1] - valuesBox.Begin[1]) };
  const std::ptrdiff_t bx = box.End[0] - box.Begin[0], by = box.End[1] - box.Begin[1];
  for (int k = part.Begin[2]; k < part.End[2]; ++k)
    for (int j = part.Begin[1]; j < part.End[1]; ++j)
      for (int i = part.Begin[0]; i < part.End[0]; ++i)
      {
        const int p[3] = { i, j, k };
        visit(p, step,
          (i - valuesBox.Begin[0]) + (j - valuesBox.Begin[1]) * step[1] +
            (k - valuesBox.Begin[2]) * step[2],
          (i - box.Begin[0]) + (j - box.Begin[1]) * bx + (k - box.Begin[2]) * bx * by);
      }
}

/// Calls visit(v, gw) for every voxel v of slice k with gw the world gradient of `values`
/// there (WorldGradientAt).
template <typename Visit>
void ForEachWorldGradientOfSlice(
  const float* values, const int dims[3], const GradientToWorld& toWorld, int k, Visit&& visit)
{
  const int nx = dims[0], ny = dims[1];
  const std::ptrdiff_t step[3] = { 1, nx, static_cast<std::ptrdiff_t>(nx) * ny };
  for (int j = 0; j < ny; ++j)
  {
    const std::ptrdiff_t row = k * step[2] + j * step[1];
    for (int i = 0; i < nx; ++i)
    {
      const int p[3] = { i, j, k };
      double gw[3];
      WorldGradientAt(values + row + i, p, dims, step, toWorld, gw);
      visit(row + i, gw);
    }
  }
}

/// Values of the image that are not finite as floats (a double beyond the float range
/// included); an integer image has none.
long long CountNonFinite(const ImageView& image)
{
  long long bad = 0;
  if (image.Type == ScalarType::Float32 || image.Type == ScalarType::Float64)
  {
    const int nx = image.Geometry.Dimensions[0];
    ForEachRow(image,
      [&](int, int, const auto* row)
      {
        for (int i = 0; i < nx; ++i)
        {
          bad += std::isfinite(AsFloat(row[i])) ? 0 : 1;
        }
      });
  }
  return bad;
}

/// Why ComputeScaleSpaceForceInto cannot run on these inputs; empty when it can.
std::string CheckForceInputs(const ImageView& image, const ScaleSpaceParameters& parameters,
  const float* potential, const float* force)
{
  std::string error;
  if (!image.Data || !potential || !force)
  {
    return "no data";
  }
  if (!Validate(image.Geometry, parameters.Sigma, &error))
  {
    return error.empty() ? std::string("invalid image geometry") : error;
  }
  if (!std::isfinite(parameters.EdgeWeight) || !std::isfinite(parameters.ImageWeight))
  {
    return "the weights must be finite";
  }
  // One NaN or Inf would spread along every line of the recursive filter and turn the
  // whole field into NaN.
  const long long bad = CountNonFinite(image);
  if (bad > 0)
  {
    return "the image has " + std::to_string(bad) +
      " non-finite values (NaN or Inf); replace them first (e.g. with a Calculator or Threshold)";
  }
  return std::string();
}

/// Range of the smoothed image and maximum of its gradient magnitude.
struct EdgeStatistics
{
  double GradientMax = 0, SmoothMin = 0, SmoothMax = 0;
};

/// g^2 (double) of the voxels 1 .. nx - 2 of a row whose voxels all have both neighbours along
/// y and z: WorldGradientAt's arithmetic (central differences, then to world), written so that
/// the loop vectorises.
void InnerRowSquares(const float* __restrict row, std::ptrdiff_t sy, std::ptrdiff_t sz, int nx,
  const GradientToWorld& toWorld, double* __restrict squares)
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
template <typename Visit>
void ForEachRowSquaresOfSlice(
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
void ForEachRowSquares(
  const float* values, const int dims[3], const GradientToWorld& toWorld, int k, Visit&& visit)
{
  ForEachRowSquaresOfSlice(values + k * (static_cast<std::ptrdiff_t>(dims[0]) * dims[1]), dims,
    toWorld, k, std::forward<Visit>(visit));
}

/// The largest of a row's g^2 (`squares`, the row j of a grid nx wide) over the rows and
/// columns [MaximumBegin, MaximumEnd) of `parameters` (a piece's own voxels), 0 outside them.
double RowBoxSquareMaximum(std::ptrdiff_t j, const double* squares, std::ptrdiff_t nx,
  const ScaleSpaceParameters& parameters)
{
  const int* b = parameters.MaximumBegin;
  const int* e = parameters.MaximumEnd;
  double gm2 = 0.0;
  for (std::ptrdiff_t i = std::max(0, b[0]);
       j >= b[1] && j < e[1] && i < std::min(nx, std::ptrdiff_t(e[0])); ++i)
  {
    gm2 = std::max(gm2, squares[i]);
  }
  return gm2;
}

/// Per slice of a grid, the largest g and the range of the smoothed values: EdgeMagnitude's
/// reduction, slice by slice (a volume's, or the slabs' of SmoothForPotentialInSlabs); with a
/// `box` (a piece's parameters), also the largest g^2 over its voxels [MaximumBegin,
/// MaximumEnd), from the same squares (BoxGradientMaximum's, slice by slice).
struct SliceStatistics
{
  std::vector<double> GradientMax, SmoothMin, SmoothMax, BoxSquareMax;
  const ScaleSpaceParameters* Box = nullptr;
  explicit SliceStatistics(int slices, const ScaleSpaceParameters* box = nullptr)
    : GradientMax(slices, 0.0)
    , SmoothMin(slices, std::numeric_limits<double>::max())
    , SmoothMax(slices, std::numeric_limits<double>::lowest())
    , BoxSquareMax(box ? slices : 0, 0.0)
    , Box(box)
  {
  }
  /// Slice k, whose values start at `slice` (its neighbours a slice away); g into `edges` (the
  /// whole grid's, unless nullptr).
  void Add(
    const float* slice, const int dims[3], const GradientToWorld& toWorld, int k, float* edges)
  {
    // The largest g^2, rooted once: the root is correctly rounded and monotonic, so the root
    // of the largest square is the largest root bit for bit.
    const std::ptrdiff_t nx = dims[0], first = k * (nx * dims[1]);
    const bool inBox = this->Box && k >= this->Box->MaximumBegin[2] && k < this->Box->MaximumEnd[2];
    double gm2 = 0.0, box2 = 0.0, lo = this->SmoothMin[k], hi = this->SmoothMax[k];
    ForEachRowSquaresOfSlice(slice, dims, toWorld, k,
      [&](std::ptrdiff_t row, const double* squares)
      {
        const float* values = slice + (row - first);
        for (int i = 0; i < dims[0]; ++i)
        {
          const double g2 = squares[i];
          if (edges)
          {
            edges[row + i] = static_cast<float>(std::sqrt(g2));
          }
          gm2 = std::max(gm2, g2);
          lo = std::min(lo, static_cast<double>(values[i]));
          hi = std::max(hi, static_cast<double>(values[i]));
        }
        if (inBox)
        {
          box2 = std::max(box2, RowBoxSquareMaximum((row - first) / nx, squares, nx, *this->Box));
        }
      });
    this->GradientMax[k] = std::sqrt(gm2);
    this->SmoothMin[k] = lo;
    this->SmoothMax[k] = hi;
    if (this->Box)
    {
      this->BoxSquareMax[k] = box2;
    }
  }
  /// Over every slice.
  EdgeStatistics Total() const
  {
    EdgeStatistics s;
    s.GradientMax = *std::max_element(this->GradientMax.begin(), this->GradientMax.end());
    s.SmoothMin = *std::min_element(this->SmoothMin.begin(), this->SmoothMin.end());
    s.SmoothMax = *std::max_element(this->SmoothMax.begin(), this->SmoothMax.end());
    return s;
  }
};

/// g = |grad smooth| into `edges` (unless nullptr), with the extrema the normalisation needs.
EdgeStatistics EdgeMagnitude(
  const float* smooth, const int dims[3], const GradientToWorld& toWorld, float* edges)
{
  SliceStatistics slices(dims[2]);
  const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  ForEachVoxelSlice(dims, [&](int k) { slices.Add(smooth + k * sz, dims, toWorld, k, edges); });
  return slices.Total();
}

/// The largest g over the voxels [MaximumBegin, MaximumEnd) of `parameters` (a piece's own,
/// ScaleSpaceParameters::GradientMaximum), in double as EdgeMagnitude computes it.
double BoxGradientMaximum(const float* smooth, const int dims[3], const GradientToWorld& toWorld,
  const ScaleSpaceParameters& parameters)
{
  const std::ptrdiff_t nx = dims[0], sz = nx * dims[1];
  double gm2 = 0.0; // the largest g^2, rooted once (as in EdgeMagnitude)
  for (int k = std::max(0, parameters.MaximumBegin[2]);
       k < std::min(dims[2], parameters.MaximumEnd[2]); ++k)
  {
    ForEachRowSquares(smooth, dims, toWorld, k,
      [&](std::ptrdiff_t row, const double* squares)
      { gm2 = std::max(gm2, RowBoxSquareMaximum((row - k * sz) / nx, squares, nx, parameters)); });
  }
  return std::sqrt(gm2);
}

/// The edge statistics of G_sigma*f (EdgeMagnitude, g into `g` when given) with, on a piece of a
/// distributed image, the normalising maximum of g over every piece
/// (ScaleSpaceParameters::GradientMaximum). In the caller's SMP scope.
EdgeStatistics EdgeStatisticsOf(const float* smooth, const int dims[3],
  const GradientToWorld& toWorld, float* g, const ScaleSpaceParameters& parameters)
{
  EdgeStatistics stats = EdgeMagnitude(smooth, dims, toWorld, g);
  if (parameters.GradientMaximum)
  {
    stats.GradientMax =
      parameters.GradientMaximum(BoxGradientMaximum(smooth, dims, toWorld, parameters));
  }
  return stats;
}

/// The gains of P = -(Edge g + Image s + Offset) (docs/METHOD.md §2, with the optional
/// normalisation of both terms), g divided by gNorm when normalised.
PotentialGains GainsOf(
  const EdgeStatistics& stats, double gNorm, const ScaleSpaceParameters& parameters)
{
  PotentialGains gains;
  gains.Edge = parameters.EdgeWeight;
  gains.Image = parameters.ImageWeight;
  if (parameters.NormalizePotential)
  {
    gains.Edge = gNorm > 0.0 ? parameters.EdgeWeight / gNorm : 0.0;
    gains.Image = stats.SmoothMax > stats.SmoothMin
      ? parameters.ImageWeight / (stats.SmoothMax - stats.SmoothMin)
      : 0.0;
    gains.Offset = -gains.Image * stats.SmoothMin;
  }
  return gains;
}

/// P of one voxel from its edge strength g (as stored, a float) and smoothed value s.
inline float PotentialOf(float g, float s, const PotentialGains& gains)
{
  return static_cast<float>(-(gains.Edge * g + gains.Image * s + gains.Offset));
}

/// The index-space gradient gi (Diff) and Hessian H (row-major: SecondDiff on the diagonal,
/// MixedDiff off it) of `v` at grid position p. Inside the grid the same arithmetic without
/// the border's branches.
inline void IndexDerivatives(const float* v, const int p[3], const int n[3],
  const std::ptrdiff_t step[3], double gi[3], double H[9])
{
  if (p[0] > 0 && p[0] < n[0] - 1 && p[1] > 0 && p[1] < n[1] - 1 && p[2] > 0 && p[2] < n[2] - 1)
  {
    for (int a = 0; a < 3; ++a)
    {
      const std::ptrdiff_t s = step[a];
      gi[a] = 0.5 * (static_cast<double>(v[s]) - v[-s]);
      H[4 * a] = static_cast<double>(v[s]) - 2.0 * v[0] + static_cast<double>(v[-s]);
      for (int b = a + 1; b < 3; ++b)
      {
        const std::ptrdiff_t t = step[b];
        const double up = 0.5 * (static_cast<double>(v[t + s]) - v[t - s]);
        const double down = 0.5 * (static_cast<double>(v[-t + s]) - v[-t - s]);
        H[3 * a + b] = H[3 * b + a] = 0.5 * (up - down);
      }
    }
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    gi[a] = Diff(v, p[a], n[a], step[a]);
    H[4 * a] = SecondDiff(v, p[a], n[a], step[a]);
    for (int b = a + 1; b < 3; ++b)
    {
      H[3 * a + b] = H[3 * b + a] = MixedDiff(v, p, n, step, a, b);
    }
  }
}

/// P and -grad P at the voxel v points at (grid position p of a grid of n voxels, neighbours
/// step[a] values apart) of s = G_sigma*f, with the global normalisation (or none):
/// P = PotentialOf(g, s) with g = |grad s|, and -grad P = Edge grad g + Image grad s, where
/// grad g = H grad s / g by the chain rule, H the Hessian of s (IndexDerivatives). Central
/// differences of P instead would widen the edge by a voxel again and move the force's zero
/// 1.5 voxels into a cube's corner at sigma = 0.5 voxel (0.7 with the chain rule, the
/// continuous Gaussian's 0.66; docs/METHOD.md §6 item 1).
inline void PotentialAndForceAt(const float* v, const int p[3], const int n[3],
  const std::ptrdiff_t step[3], const GradientToWorld& toWorld, const PotentialGains& gains,
  float& potential, float force[3])
{
  double gi[3], H[9], gw[3];
  IndexDerivatives(v, p, n, step, gi, H);
  toWorld.Apply(gi, gw);
  const double g = std::sqrt(gw[0] * gw[0] + gw[1] * gw[1] + gw[2] * gw[2]);
  potential = PotentialOf(static_cast<float>(g), v[0], gains);
  double edge[3] = { 0.0, 0.0, 0.0 };
  if (g > 0.0)
  {
    // grad g in index space is H J^T gw / g (g = |J gi|), then to world like any gradient.
    double w[3], u[3];
    toWorld.ApplyTransposed(gw, w);
    for (int a = 0; a < 3; ++a)
    {
      u[a] = (H[3 * a] * w[0] + H[3 * a + 1] * w[1] + H[3 * a + 2] * w[2]) / g;
    }
    toWorld.Apply(u, edge);
  }
  for (int a = 0; a < 3; ++a)
  {
    force[a] = static_cast<float>(gains.Edge * edge[a] + gains.Image * gw[a]);
  }
}

/// P and -grad P (PotentialAndForceAt) of the whole grid, s = G_sigma*f in `potential` on entry
/// and P there on return. Slice by slice, each slice's rows in parallel: a slice's P goes back
/// only once the next slice, whose differences read it, is done (two slices of scratch).
void PotentialAndForceInPlace(float* potential, float* force, const int dims[3],
  const GradientToWorld& toWorld, const PotentialGains& gains)
{
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(nx) * ny;
  const std::ptrdiff_t step[3] = { 1, nx, sz };
  std::vector<float> done[2] = { std::vector<float>(sz), std::vector<float>(sz) };
  for (int k = 0; k < nz; ++k)
  {
    float* slice = done[k % 2].data();
    vtkSMPTools::For(0, ny,
      [&](int jb, int je)
      {
        for (int j = jb; j < je; ++j)
        {
          for (int i = 0; i < nx; ++i)
          {
            const int p[3] = { i, j, k };
            const std::ptrdiff_t v = k * sz + j * step[1] + i;
            PotentialAndForceAt(
              potential + v, p, dims, step, toWorld, gains, slice[j * step[1] + i], force + 3 * v);
          }
        }
      });
    if (k > 0)
    {
      std::copy(done[(k - 1) % 2].begin(), done[(k - 1) % 2].end(), potential + (k - 1) * sz);
    }
  }
  std::copy(done[(nz - 1) % 2].begin(), done[(nz - 1) % 2].end(), potential + (nz - 1) * sz);
}

/// P in place of g in `potential`; `scratch` holds one volume for the local normalisation.
void CombinePotential(float* potential, const float* smooth, float* scratch, const int dims[3],
  const double sigmaVoxels[3], const EdgeStatistics& stats, const ScaleSpaceParameters& parameters)
{
  double gNorm = stats.GradientMax;
  if (parameters.NormalizePotential && parameters.EdgeNormalization == EdgeNormalization::Local &&
    stats.GradientMax > 0.0)
  {
    gNorm = NormalizeEdgesLocally(potential, scratch, dims, sigmaVoxels,
      parameters.LocalEdgeFloor * stats.GradientMax, parameters);
  }
  const PotentialGains gains = GainsOf(stats, gNorm, parameters);
  const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  ForEachVoxelSlice(dims,
    [&](int k)
    {
      const std::ptrdiff_t b = k * sz, e = b + sz;
      for (std::ptrdiff_t v = b; v < e; ++v)
      {
        potential[v] = PotentialOf(potential[v], smooth[v], gains);
      }
    });
}

/// G_sigma * f of `image` into `smooth`: an image of another type (or a box of a larger one)
/// is converted there first and smoothed in place, with the same result; on a piece of a
/// distributed image by `pieceSmooth` (ScaleSpaceParameters::Smooth). In the caller's SMP scope.
void SmoothImage(const ImageView& image, const double sigmaVoxels[3], float* smooth,
  const std::function<void(float*, const double*)>& pieceSmooth = nullptr)
{
  const int* dims = image.Geometry.Dimensions;
  if (pieceSmooth)
  {
    CopyToFloat(image, smooth);
    pieceSmooth(smooth, sigmaVoxels);
  }
  else if (image.IsContiguousFloat())
  {
    SmoothGaussianSeparable(static_cast<const float*>(image.Data), smooth, dims, sigmaVoxels);
  }
  else
  {
    CopyToFloat(image, smooth);
    SmoothGaussianSeparable(smooth, smooth, dims, sigmaVoxels);
  }
}

/// sigma in voxels along each axis.
void SigmaVoxels(double sigma, const ImageGeometry& geometry, double sv[3])
{
  for (int a = 0; a < 3; ++a)
  {
    sv[a] = sigma / geometry.Spacing[a];
  }
}

/// The local edge normalisation asked for P alone (ScaleSpaceParameters::ComputeForce).
bool PotentialOnly(const ScaleSpaceParameters& parameters)
{
  return !parameters.ComputeForce && parameters.NormalizePotential &&
    parameters.EdgeNormalization == EdgeNormalization::Local;
}

/// P and -grad P with the local edge normalisation (EdgeNormalization::Local), in the caller's
/// SMP scope: P = -(Edge g / (G_2sigma * g + floor) + ...) and -grad P by central differences
/// of P (the chain rule of PotentialAndForceAt would need the local mean's gradient too).
void LocallyNormalisedField(const ImageView& image, const ScaleSpaceParameters& parameters,
  const double sigmaVoxels[3], const GradientToWorld& toWorld, float* potential, float* force)
{
  const int* dims = image.Geometry.Dimensions;
  // The first third of the force buffer holds G_sigma*f until P is known; the rest is
  // scratch for the local edge normalisation.
  float* smooth = force;
  SmoothImage(image, sigmaVoxels, smooth);
  const EdgeStatistics stats = EdgeStatisticsOf(smooth, dims, toWorld, potential, parameters);
  float* scratch = force + dims[0] * static_cast<std::ptrdiff_t>(dims[1]) * dims[2];
  CombinePotential(potential, smooth, scratch, dims, sigmaVoxels, stats, parameters);
  if (!parameters.ComputeForce)
  {
    return;
  }

  // Force = -grad P; the smoothed image is no longer needed, so the buffer is free.
  ForEachVoxelSlice(dims,
    [&](int k)
    {
      ForEachWorldGradientOfSlice(potential, dims, toWorld, k,
        [&](std::ptrdiff_t v, const double gw[3])
        {
          float* f = force + 3 * v;
          f[0] = static_cast<float>(-gw[0]);
          f[1] = static_cast<float>(-gw[1]);
          f[2] = static_cast<float>(-gw[2]);
        });
    });
}
} // namespace

namespace
{
/// The sampled Gaussian's radius at sigmaVoxels (dsGaussianSmoother.h).
int SampledRadius(double sigmaVoxels)
{
  return std::max(1, static_cast<int>(std::ceil(4.0 * sigmaVoxels)));
}

/// Voxels along an axis of sigmaVoxels that the locally normalised P at a voxel reads: the
/// first Gaussian's radius, one for the differences, the second Gaussian's radius; -1 when
/// either Gaussian is recursive (it reads the whole axis).
int LocalFieldReach(double sigmaVoxels)
{
  if (!(2.0 * sigmaVoxels < GaussianRecursiveFromSigmaVoxels))
  {
    return -1;
  }
  return SampledRadius(sigmaVoxels) + 1 + SampledRadius(2.0 * sigmaVoxels);
}

/// Bins of G_2sigma * g by the leading bits of its float (monotonic for values >= 0): a voxel
/// whose g no voxel of a lower bin reaches may hold the largest ratio (LocalPotentialAt).
constexpr int RatioBinShift = 19;
constexpr int RatioBins = 1 << (32 - RatioBinShift);

inline float Denominator(float wide)
{
  return std::max(0.0f, wide);
}

inline int RatioBin(float wide)
{
  std::uint32_t bits;
  const float d = Denominator(wide);
  std::memcpy(&bits, &d, sizeof bits);
  return static_cast<int>(bits >> RatioBinShift);
}

/// Keeps of `candidates` (g, G_2sigma * g) only those no other beats on both terms (a larger
/// or equal g with a smaller or equal G_2sigma * g): they alone may hold the largest ratio, and
/// with bins of 1/16 of an octave a slab leaves ~10^5 of its voxels, this ~10^2.
void KeepUnbeaten(std::vector<std::pair<float, float>>& candidates)
{
  std::sort(candidates.begin(), candidates.end(),
    [](const std::pair<float, float>& a, const std::pair<float, float>& b)
    {
      const float da = Denominator(a.second), db = Denominator(b.second);
      return da < db || (da == db && a.first > b.first);
    });
  std::size_t kept = 0;
  float best = -1.0f;
  for (const auto& c : candidates)
  {
    if (c.first > best)
    {
      candidates[kept++] = c;
      best = c.first;
    }
  }
  candidates.resize(kept);
}

/// What LocalPotentialAt keeps of the slabs.
struct LocalEdgeScan
{
  double GradientSquareMax = 0.0; ///< over the maximum box, as BoxGradientMaximum
  double SmoothMin = std::numeric_limits<double>::max();
  double SmoothMax = std::numeric_limits<double>::lowest();
  bool Finite = true; ///< every g and s of the cores (else the whole field's P is not finite)
  std::vector<float> BinMax = std::vector<float>(RatioBins, -1.0f); ///< largest g per bin so far
  std::vector<std::pair<float, float>>
    Candidates; ///< (g, G_2sigma * g) that may hold the ratio's maximum
  /// At the wanted voxels, by rank; Smooth only when the image term reads it (ImageWeight not 0:
  /// else its gain is 0, and 0 * s adds nothing to the edge term's non-negative value).
  std::vector<float> G, Wide, Smooth;
};

/// A slab's core (slices [Core0, Core1)) and the maximum box, in the slab's indices.
struct SlabBox
{
  int Core0, Core1;
  int Box0[3], Box1[3];
  bool InBox(int i, int j, int k) const
  {
    return k >= std::max(this->Core0, this->Box0[2]) && k < std::min(this->Core1, this->Box1[2]) &&
      j >= this->Box0[1] && j < this->Box1[1] && i >= this->Box0[0] && i < this->Box1[0];
  }
};

/// g = |grad s| on the slab's slices [k0, k1) (as EdgeMagnitude) and, in the same pass, the
/// largest g^2 over the box (rooted once, as BoxGradientMaximum), the range of s over the core
/// and whether the core's s and g are finite, folded into `scan`.
void SlabEdges(const float* s, const int dims[3], const GradientToWorld& toWorld,
  const SlabBox& slab, int k0, int k1, float* g, LocalEdgeScan& scan)
{
  const int nx = dims[0], ny = dims[1];
  const std::ptrdiff_t step[3] = { 1, nx, static_cast<std::ptrdiff_t>(nx) * ny };
  std::vector<double> gm2(dims[2], 0.0), lo(dims[2], scan.SmoothMin), hi(dims[2], scan.SmoothMax);
  std::vector<char> finite(dims[2], 1);
  vtkSMPTools::For(k0, k1,
    [&](int kb, int ke)
    {
      for (int k = kb; k < ke; ++k)
      {
        const bool core = k >= slab.Core0 && k < slab.Core1;
        double m = 0.0, l = lo[k], h = hi[k];
        bool f = true;
        ForEachRowSquares(s, dims, toWorld, k,
          [&](std::ptrdiff_t row, const double* squares)
          {
            const int j = static_cast<int>((row - k * step[2]) / nx);
            const bool rowInBox = slab.InBox(slab.Box0[0], j, k);
            for (int i = 0; i < nx; ++i)
            {
              g[row + i] = static_cast<float>(std::sqrt(squares[i]));
            }
            for (int i = rowInBox ? slab.Box0[0] : 0; rowInBox && i < slab.Box1[0]; ++i)
            {
              m = std::max(m, squares[i]);
            }
            for (std::ptrdiff_t v = row; core && v < row + nx; ++v)
            {
              f = f && std::isfinite(g[v]) && std::isfinite(s[v]);
              l = std::min(l, static_cast<double>(s[v]));
              h = std::max(h, static_cast<double>(s[v]));
            }
          });
        gm2[k] = m;
        finite[k] = f;
        lo[k] = l;
        hi[k] = h;
      }
    });
  for (int k = slab.Core0; k < slab.Core1; ++k)
  {
    scan.GradientSquareMax = std::max(scan.GradientSquareMax, gm2[k]);
    scan.SmoothMin = std::min(scan.SmoothMin, lo[k]);
    scan.SmoothMax = std::max(scan.SmoothMax, hi[k]);
    scan.Finite = scan.Finite && finite[k];
  }
}

/// Keeps the box's voxels of the slab's core that may hold the largest ratio g / (G_2sigma * g +
/// floor), whatever the floor (LocalPotentialAt), in `scan`.
void SlabRatioCandidates(
  const float* g, const float* wide, const int dims[3], const SlabBox& slab, LocalEdgeScan& scan)
{
  const int nx = dims[0];
  const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(nx) * dims[1];
  const int k0 = std::max(slab.Core0, slab.Box0[2]), k1 = std::min(slab.Core1, slab.Box1[2]);
  const auto forBoxRows = [&](int k, auto&& row)
  {
    for (int j = slab.Box0[1]; j < slab.Box1[1]; ++j)
    {
      row(k * sz + j * nx + slab.Box0[0], k * sz + j * nx + slab.Box1[0]);
    }
  };
  // Each bin's largest g, slice by slice.
  std::vector<std::vector<float>> binMax(std::max(0, k1 - k0));
  vtkSMPTools::For(k0, std::max(k0, k1),
    [&](int kb, int ke)
    {
      for (int k = kb; k < ke; ++k)
      {
        std::vector<float>& bins = binMax[k - k0];
        bins.assign(RatioBins, -1.0f);
        forBoxRows(k,
          [&](std::ptrdiff_t b, std::ptrdiff_t e)
          {
            for (std::ptrdiff_t v = b; v < e; ++v)
            {
              float& m = bins[RatioBin(wide[v])];
              m = std::max(m, g[v]);
            }
          });
      }
    });
  // below[b]: the largest g of a voxel in a lower bin, this slab's or an earlier one's. A voxel
  // whose g does not exceed it cannot hold a larger ratio than that voxel (whatever the floor:
  // the ratio grows with g and falls with the denominator), so it is not kept.
  std::vector<float> below(RatioBins);
  float run = -1.0f;
  for (int b = 0; b < RatioBins; ++b)
  {
    below[b] = run;
    float m = scan.BinMax[b];
    for (const std::vector<float>& bins : binMax)
    {
      m = std::max(m, bins[b]);
    }
    scan.BinMax[b] = m;
    run = std::max(run, m);
  }
  for (int k = k0; k < k1; ++k)
  {
    forBoxRows(k,
      [&](std::ptrdiff_t b, std::ptrdiff_t e)
      {
        for (std::ptrdiff_t v = b; v < e; ++v)
        {
          // g = 0 gives the ratio 0, the maximum's start.
          if (g[v] > std::max(0.0f, below[RatioBin(wide[v])]))
          {
            scan.Candidates.emplace_back(g[v], wide[v]);
          }
        }
      });
  }
}
} // namespace

namespace
{
/// Slices of a slab's core when both Gaussians along z are sampled (reach >= 0): coreSlices, by
/// default four times the reach.
int SlabCore(int reach, int coreSlices)
{
  return std::max(1, coreSlices > 0 ? coreSlices : 4 * reach);
}
} // namespace

double LocalPotentialBytes(const ImageGeometry& geometry, const ScaleSpaceParameters& parameters,
  const VoxelSet& wanted, int coreSlices)
{
  return LocalPotentialBytes(geometry, parameters, static_cast<double>(wanted.Size()), coreSlices);
}

double LocalPotentialBytes(const ImageGeometry& geometry, const ScaleSpaceParameters& parameters,
  double wantedVoxels, int coreSlices)
{
  const int nz = geometry.Dimensions[2];
  const double sigmaZ = parameters.Sigma / geometry.Spacing[2];
  const int reach = LocalFieldReach(sigmaZ);
  const double slice = static_cast<double>(geometry.Dimensions[0]) * geometry.Dimensions[1];
  // The set of wanted voxels: a bit and a count every 64 voxels (VoxelSet::Bytes).
  const double set = std::ceil(static_cast<double>(geometry.NumberOfVoxels()) / 64.0) *
    (sizeof(std::uint64_t) + sizeof(long long));
  const double kept = (parameters.ImageWeight != 0.0 ? 3 : 2) * sizeof(float) * wantedVoxels + set;
  if (reach >= 0)
  {
    // G_sigma * f, g and G_2sigma * g of a slab, and its candidates for the largest ratio (two
    // floats each, at most its voxels).
    const int slab = std::min(nz, SlabCore(reach, coreSlices) + 2 * reach);
    return 5 * sizeof(float) * slab * slice + kept;
  }
  // ScanRecursiveSlabs: G_2sigma * g of a core, G_sigma * f and g of its slab (two slices more),
  // the slices smoothed along x and y that either Gaussian's pass along z reads (a sampled one's
  // reach on either side), the core's candidates; the recorded states of both passes along z
  // and what a pass along z holds besides while it runs: the state carried between slabs, the
  // states it records and a RecursiveAxisPass's own (21 doubles a line, as SmoothInSlabsBytes).
  const int core = coreSlices > 0 ? coreSlices : DefaultSlabCore(geometry.Dimensions, 2 * sigmaZ);
  const std::vector<int> cores = SlabCores(nz, core);
  int longest = 0;
  for (std::size_t c = 0; c + 1 < cores.size(); ++c)
  {
    longest = std::max(longest, cores[c + 1] - cores[c]);
  }
  const int smoothReach = GaussianAxisReach(sigmaZ);
  const double floats = 6.0 * longest + 6 + 2 * std::max(0, smoothReach);
  const double boundaries = static_cast<double>(cores.size()) - 2;
  const double states = 2.0 * RecursiveAxisPass::States * (smoothReach < 0 ? 2 : 1) * boundaries;
  return sizeof(float) * floats * slice + sizeof(double) * (states + 21) * slice + kept;
}

namespace
{
/// The maximum box of `parameters` in the indices of slices [first, ...) of the image, with the
/// slices [core0, core1) (image indices) as the core.
SlabBox SlabBoxOf(const ScaleSpaceParameters& parameters, int first, int core0, int core1)
{
  SlabBox where{ core0 - first, core1 - first, {}, {} };
  for (int a = 0; a < 3; ++a)
  {
    where.Box0[a] = parameters.MaximumBegin[a] - (a == 2 ? first : 0);
    where.Box1[a] = parameters.MaximumEnd[a] - (a == 2 ? first : 0);
  }
  return where;
}

/// The wanted voxels' g, G_2sigma * g and s of the core [core0, core1) into `scan`: g and wide
/// hold the core's slices, s the slices from `first` on.
void KeepWanted(const VoxelSet& wanted, std::ptrdiff_t sliceVoxels, int first, int core0, int core1,
  const float* g, const float* wide, const float* s, LocalEdgeScan& scan)
{
  const std::ptrdiff_t coreFirst = core0 * sliceVoxels, sFirst = first * sliceVoxels;
  // Slice by slice in parallel: each voxel has its own rank.
  vtkSMPTools::For(core0, core1,
    [&](int kb, int ke)
    {
      wanted.ForEachIn(kb * sliceVoxels, ke * sliceVoxels,
        [&](long long v, long long rank)
        {
          scan.G[rank] = g[v - coreFirst];
          scan.Wide[rank] = wide[v - coreFirst];
          if (!scan.Smooth.empty())
          {
            scan.Smooth[rank] = s[v - sFirst];
          }
        });
    });
}

/// LocalPotentialAt's pass when both Gaussians along z are sampled: slabs of `core` slices with
/// the pipeline's `reach` (LocalFieldReach) on either side, each computed whole.
void ScanSampledSlabs(const ImageView& image, const ScaleSpaceParameters& parameters,
  const VoxelSet& wanted, int core, int reach, LocalEdgeScan& scan)
{
  const ImageGeometry& geometry = image.Geometry;
  const int nx = geometry.Dimensions[0], ny = geometry.Dimensions[1], nz = geometry.Dimensions[2];
  double sv[3];
  SigmaVoxels(parameters.Sigma, geometry, sv);
  const double wide[3] = { 2 * sv[0], 2 * sv[1], 2 * sv[2] };
  const GradientToWorld toWorld(geometry);
  const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(nx) * ny;
  std::vector<float> s, g, w;
  for (int z0 = 0; z0 < nz; z0 += core)
  {
    const int z1 = std::min(nz, z0 + core);
    VoxelBox slab = VoxelBox::Whole(geometry);
    slab.Begin[2] = std::max(0, z0 - reach);
    slab.End[2] = std::min(nz, z1 + reach);
    const ImageView part = image.Box(slab);
    const int* dims = part.Geometry.Dimensions;
    const std::size_t n = static_cast<std::size_t>(part.Geometry.NumberOfVoxels());
    s.resize(n);
    g.resize(n);
    w.resize(n);
    SmoothImage(part, sv, s.data());
    const SlabBox where = SlabBoxOf(parameters, slab.Begin[2], z0, z1);
    // g where G_2sigma * g on the core reads it, and that Gaussian on those slices alone (its
    // values beyond the core are not used).
    const int k0 = std::max(0, where.Core0 - SampledRadius(wide[2]));
    const int k1 = std::min(dims[2], where.Core1 + SampledRadius(wide[2]));
    SlabEdges(s.data(), dims, toWorld, where, k0, k1, g.data(), scan);
    const int used[3] = { dims[0], dims[1], k1 - k0 };
    SmoothGaussianSeparable(g.data() + k0 * sz, w.data() + k0 * sz, used, wide);
    SlabRatioCandidates(g.data(), w.data(), dims, where, scan);
    KeepUnbeaten(scan.Candidates);
    const std::ptrdiff_t core0 = where.Core0 * sz;
    KeepWanted(
      wanted, sz, slab.Begin[2], z0, z1, g.data() + core0, w.data() + core0, s.data(), scan);
  }
}

/// G_sigma * f of slab s of `cores` (its core and a slice on either side, which g's differences
/// read), in any order: sampled along z from the slab's reach of slices smoothed along x and y,
/// or, recursive along z, from a RecursiveSlabsZ prepared by a pass up and down the slabs.
class SmoothedSlabs
{
public:
  SmoothedSlabs(const ImageView& image, const double sigmaVoxels[3], const std::vector<int>& cores)
    : Image(image)
    , Cores(cores)
  {
    std::copy(sigmaVoxels, sigmaVoxels + 3, this->Sigma);
    if (GaussianAxisReach(this->Sigma[2]) < 0)
    {
      this->Recursive.reset(new RecursiveSlabsZ(image.Geometry.Dimensions, this->Sigma[2], cores, 1,
        [this](int z0, int z1, float* out)
        { SmoothSlicesXY(this->Image, z0, z1, this->Sigma, out); }));
      this->Recursive->Prepare();
    }
  }
  void Slab(int s, std::vector<float>& out)
  {
    if (this->Recursive)
    {
      this->Recursive->Slab(s, out);
      return;
    }
    const int* dims = this->Image.Geometry.Dimensions;
    const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
    const int f0 = std::max(0, this->Cores[s] - 1), f1 = std::min(dims[2], this->Cores[s + 1] + 1);
    const int r = std::max(0, GaussianAxisReach(this->Sigma[2]));
    const int w0 = std::max(0, f0 - r), w1 = std::min(dims[2], f1 + r);
    this->Window.resize(static_cast<std::size_t>((w1 - w0) * sz));
    SmoothSlicesXY(this->Image, w0, w1, this->Sigma, this->Window.data());
    out.resize(static_cast<std::size_t>((f1 - f0) * sz));
    const int wdims[3] = { dims[0], dims[1], w1 - w0 };
    SampledAxisZ(this->Window.data(), out.data(), wdims, this->Sigma[2], f0 - w0, f1 - w0);
  }

private:
  ImageView Image;
  std::vector<int> Cores;
  double Sigma[3];
  std::unique_ptr<RecursiveSlabsZ> Recursive;
  std::vector<float> Window; ///< the slices a sampled slab's pass along z reads
};

/// g of the slices [z0, z1) (a slab's core) into `out`, from G_sigma * f of those slices and one
/// on either side within the image (`smooth`, from slice max(0, z0 - 1) on): EdgeMagnitude's
/// values.
void CoreEdges(const float* smooth, const int dims[3], const GradientToWorld& toWorld, int z0,
  int z1, float* out)
{
  const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  const int f0 = std::max(0, z0 - 1);
  const int slabDims[3] = { dims[0], dims[1], std::min(dims[2], z1 + 1) - f0 };
  vtkSMPTools::For(z0 - f0, z1 - f0,
    [&](int kb, int ke)
    {
      for (int k = kb; k < ke; ++k)
      {
        ForEachRowSquares(smooth, slabDims, toWorld, k,
          [&](std::ptrdiff_t row, const double* squares)
          {
            float* to = out + (row - (z0 - f0) * sz);
            for (int i = 0; i < dims[0]; ++i)
            {
              to[i] = static_cast<float>(std::sqrt(squares[i]));
            }
          });
      }
    });
}

/// LocalPotentialAt's pass when G_2sigma * g is recursive along z (2 sigma of 3 voxels or more,
/// so it reads whole lines of g): slabs of `core` slices (SmoothedSlabs gives G_sigma * f of
/// each); g of each core, smoothed along x and y at 2 sigma, is the input of the second
/// Gaussian's RecursiveSlabsZ, which runs up the slabs and then down them, where each slab's
/// values are final and scanned.
void ScanRecursiveSlabs(const ImageView& image, const ScaleSpaceParameters& parameters,
  const VoxelSet& wanted, int core, LocalEdgeScan& scan)
{
  const int* dims = image.Geometry.Dimensions;
  double sv[3];
  SigmaVoxels(parameters.Sigma, image.Geometry, sv);
  const double wideXY[3] = { 2 * sv[0], 2 * sv[1], 0.0 };
  const GradientToWorld toWorld(image.Geometry);
  const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  const std::vector<int> cores = SlabCores(dims[2], core);
  SmoothedSlabs smoothed(image, sv, cores);
  std::vector<float> smooth, g; // G_sigma * f of slab `made` (the last asked for), its g
  int made = -1;
  const auto wideInput = [&](int z0, int z1, float* out)
  {
    // wideZ's slabs are the cores themselves (margin 0): z0 starts one.
    made = static_cast<int>(std::lower_bound(cores.begin(), cores.end(), z0) - cores.begin());
    assert(cores[made] == z0 && cores[made + 1] == z1);
    smoothed.Slab(made, smooth);
    CoreEdges(smooth.data(), dims, toWorld, z0, z1, out);
    const int coreDims[3] = { dims[0], dims[1], z1 - z0 };
    SmoothGaussianSeparable(out, out, coreDims, wideXY);
  };
  RecursiveSlabsZ wideZ(dims, 2 * sv[2], cores, 0, wideInput);
  wideZ.Prepare(
    [&](int s, const std::vector<float>& wide)
    {
      assert(made == s); // the pass made this slab's G_2sigma * g just now, from `smooth`
      const int z0 = cores[s], z1 = cores[s + 1], f0 = std::max(0, z0 - 1);
      const int slabDims[3] = { dims[0], dims[1], std::min(dims[2], z1 + 1) - f0 };
      g.resize(smooth.size());
      const SlabBox where = SlabBoxOf(parameters, f0, z0, z1);
      SlabEdges(smooth.data(), slabDims, toWorld, where, where.Core0, where.Core1, g.data(), scan);
      const int coreDims[3] = { dims[0], dims[1], z1 - z0 };
      const float* coreG = g.data() + where.Core0 * sz;
      SlabRatioCandidates(coreG, wide.data(), coreDims, SlabBoxOf(parameters, z0, z0, z1), scan);
      KeepUnbeaten(scan.Candidates);
      KeepWanted(wanted, sz, f0, z0, z1, coreG, wide.data(), smooth.data(), scan);
    });
}
} // namespace

bool LocalPotentialAt(const ImageView& image, const ScaleSpaceParameters& parameters,
  const VoxelSet& wanted, std::vector<float>& potential, std::string* error, int coreSlices)
{
  float probe = 0.0f;
  std::string problem = CheckForceInputs(image, parameters, &probe, &probe);
  if (problem.empty() && (!PotentialOnly(parameters) || parameters.Smooth))
  {
    problem = "only the locally normalised potential, smoothed here, is computed at chosen voxels";
  }
  if (!problem.empty())
  {
    if (error)
    {
      *error = problem;
    }
    return false;
  }
  const ImageGeometry& geometry = image.Geometry;
  const int nz = geometry.Dimensions[2];
  const double sigmaZ = parameters.Sigma / geometry.Spacing[2];
  const int reach = LocalFieldReach(sigmaZ);
  LocalEdgeScan scan;
  scan.G.resize(wanted.Size());
  scan.Wide.resize(wanted.Size());
  scan.Smooth.resize(parameters.ImageWeight != 0.0 ? wanted.Size() : 0);
  WithThreads(parameters.NumberOfThreads,
    [&]()
    {
      if (reach < 0)
      {
        ScanRecursiveSlabs(image, parameters, wanted,
          coreSlices > 0 ? coreSlices : DefaultSlabCore(geometry.Dimensions, 2 * sigmaZ), scan);
      }
      else
      {
        ScanSampledSlabs(image, parameters, wanted, SlabCore(reach, coreSlices), reach, scan);
      }
    });

  // The two maxima as NormalizeEdgesLocally and EdgeStatisticsOf take them over the box.
  EdgeStatistics stats;
  stats.SmoothMin = scan.SmoothMin;
  stats.SmoothMax = scan.SmoothMax;
  const double gMax = std::sqrt(scan.GradientSquareMax);
  stats.GradientMax = parameters.GradientMaximum ? parameters.GradientMaximum(gMax) : gMax;
  const double floor = parameters.LocalEdgeFloor * stats.GradientMax;
  const auto ratio = [floor](float gv, float wv)
  { return gv / (std::max(0.0, static_cast<double>(wv)) + floor); };
  double gNorm = stats.GradientMax;
  if (stats.GradientMax > 0.0)
  {
    double m = 0.0;
    for (const auto& c : scan.Candidates)
    {
      m = std::max(m, ratio(c.first, c.second));
    }
    gNorm = parameters.GradientMaximum ? parameters.GradientMaximum(m) : m;
  }
  const PotentialGains gains = GainsOf(stats, gNorm, parameters);
  // P in place of g (a wanted voxel's value is read once), then handed out.
  for (std::size_t r = 0; r < scan.G.size(); ++r)
  {
    const float e =
      stats.GradientMax > 0.0 ? static_cast<float>(ratio(scan.G[r], scan.Wide[r])) : scan.G[r];
    scan.G[r] = PotentialOf(e, scan.Smooth.empty() ? 0.0f : scan.Smooth[r], gains);
  }
  std::vector<float>().swap(scan.Wide);
  potential = std::move(scan.G);
  if (!scan.Finite ||
    !std::all_of(potential.begin(), potential.end(), [](float v) { return std::isfinite(v); }))
  {
    if (error)
    {
      *error = "the locally normalised potential is not finite: sigma (" +
        std::to_string(parameters.Sigma) + ") or the weights are too large";
    }
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool SmoothGaussian(float* volume, const ImageGeometry& geometry, double sigma, int numberOfThreads,
  std::string* error)
{
  if (!volume || !Validate(geometry, sigma, error))
  {
    if (!volume && error)
    {
      *error = "no data";
    }
    return false;
  }
  const double sv[3] = { sigma / geometry.Spacing[0], sigma / geometry.Spacing[1],
    sigma / geometry.Spacing[2] };
  WithThreads(
    numberOfThreads, [&]() { SmoothGaussianSeparable(volume, volume, geometry.Dimensions, sv); });
  return true;
}

bool ComputeScaleSpaceForceInto(const ImageView& image, const ScaleSpaceParameters& parameters,
  float* potential, float* force, std::string* error)
{
  const std::string problem = CheckForceInputs(image, parameters, potential, force);
  if (!problem.empty())
  {
    if (error)
    {
      *error = problem;
    }
    return false;
  }
  const ImageGeometry& geometry = image.Geometry;
  const int* dims = geometry.Dimensions;
  double sv[3];
  SigmaVoxels(parameters.Sigma, geometry, sv);
  const GradientToWorld toWorld(geometry);

  const bool local =
    parameters.NormalizePotential && parameters.EdgeNormalization == EdgeNormalization::Local;
  WithThreads(parameters.NumberOfThreads,
    [&]()
    {
      if (local)
      {
        LocallyNormalisedField(image, parameters, sv, toWorld, potential, force);
        return;
      }
      // G_sigma*f, replaced by P as the force is computed
      SmoothImage(image, sv, potential, parameters.Smooth);
      const EdgeStatistics stats = EdgeStatisticsOf(potential, dims, toWorld, nullptr, parameters);
      PotentialAndForceInPlace(
        potential, force, dims, toWorld, GainsOf(stats, stats.GradientMax, parameters));
    });
  // Finite inputs can still overflow single precision: a weight near VTK_DOUBLE_MAX, or a
  // sigma so large that the recursive filter's coefficients are not finite.
  const std::size_t n = static_cast<std::size_t>(geometry.NumberOfVoxels());
  const std::size_t forceValues = PotentialOnly(parameters) ? 0 : 3 * n;
  if (!std::all_of(potential, potential + n, [](float v) { return std::isfinite(v); }) ||
    !std::all_of(force, force + forceValues, [](float v) { return std::isfinite(v); }))
  {
    if (error)
    {
      char text[160];
      std::snprintf(text, sizeof text,
        "the force field is not finite: sigma (%g) or the weights (%g, %g) are too large",
        parameters.Sigma, parameters.EdgeWeight, parameters.ImageWeight);
      *error = text;
    }
    return false;
  }
  return true;
}

namespace
{
/// Whether `problem` is empty; else it goes to *error (when given).
bool Unproblematic(const std::string& problem, std::string* error)
{
  if (!problem.empty() && error)
  {
    *error = problem;
  }
  return problem.empty();
}

/// Whether the potential's gains are finite (huge weights overflow them); else a message.
bool GainsFinite(const PotentialGains& gains, std::string* error)
{
  return Unproblematic(
    std::isfinite(gains.Edge) && std::isfinite(gains.Image) && std::isfinite(gains.Offset)
      ? std::string()
      : "the potential's normalisation is not finite: the weights are too large",
    error);
}
} // namespace

bool SmoothForPotential(const ImageView& image, const ScaleSpaceParameters& parameters,
  float* smooth, PotentialGains& gains, std::string* error)
{
  std::string problem = CheckForceInputs(image, parameters, smooth, smooth);
  if (problem.empty() && parameters.NormalizePotential &&
    parameters.EdgeNormalization == EdgeNormalization::Local)
  {
    problem = "the local edge normalisation is not computed in pieces";
  }
  if (!Unproblematic(problem, error))
  {
    return false;
  }
  double sv[3];
  SigmaVoxels(parameters.Sigma, image.Geometry, sv);
  const GradientToWorld toWorld(image.Geometry);
  WithThreads(parameters.NumberOfThreads,
    [&]()
    {
      SmoothImage(image, sv, smooth, parameters.Smooth);
      const EdgeStatistics stats =
        EdgeStatisticsOf(smooth, image.Geometry.Dimensions, toWorld, nullptr, parameters);
      gains = GainsOf(stats, stats.GradientMax, parameters);
    });
  return GainsFinite(gains, error);
}

bool SmoothForPotentialInSlabs(const ImageView& image, const ScaleSpaceParameters& parameters,
  int coreSlices, const std::function<void(const SmoothSlab&)>& keep, PotentialGains& gains,
  std::string* error, const SlabSource& source, bool findGains)
{
  float probe = 0.0f;
  std::string problem = CheckForceInputs(image, parameters, &probe, &probe);
  if (problem.empty() &&
    ((parameters.NormalizePotential && parameters.EdgeNormalization == EdgeNormalization::Local) ||
      parameters.Smooth))
  {
    problem = "only the globally normalised field is smoothed in slabs";
  }
  if (!Unproblematic(problem, error))
  {
    return false;
  }
  double sv[3];
  SigmaVoxels(parameters.Sigma, image.Geometry, sv);
  const GradientToWorld toWorld(image.Geometry);
  const int* dims = image.Geometry.Dimensions;
  const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  // As EdgeMagnitude takes them; a piece's own voxels' largest g too (BoxGradientMaximum's).
  SliceStatistics slices(dims[2], parameters.GradientMaximum ? &parameters : nullptr);
  const auto visit = [&](const SmoothSlab& slab)
  {
    if (!findGains)
    {
      keep(slab);
      return;
    }
    vtkSMPTools::For(slab.Core0, slab.Core1,
      [&](int kb, int ke)
      {
        for (int k = kb; k < ke; ++k)
        {
          slices.Add(slab.Values + (k - slab.First) * sz, dims, toWorld, k, nullptr);
        }
      });
    keep(slab);
  };
  WithThreads(parameters.NumberOfThreads,
    [&]()
    {
      if (source)
      {
        source(coreSlices, visit);
      }
      else
      {
        SmoothInSlabs(image, sv, coreSlices, visit);
      }
    });
  if (!findGains)
  {
    return true;
  }
  EdgeStatistics stats = slices.Total();
  if (parameters.GradientMaximum)
  {
    stats.GradientMax = parameters.GradientMaximum(
      std::sqrt(*std::max_element(slices.BoxSquareMax.begin(), slices.BoxSquareMax.end())));
  }
  gains = GainsOf(stats, stats.GradientMax, parameters);
  return GainsFinite(gains, error);
}

void PotentialAndForceInBox(const float* smooth, const VoxelBox& smoothBox,
  const ImageGeometry& geometry, const VoxelBox& box, const VoxelBox& part,
  const PotentialGains& gains, float* potential, float* force)
{
  // Each value as ComputeScaleSpaceForceInto computes it (PotentialAndForceAt on the image's
  // grid: its border where the grid's is), so the box's values equal the whole field's bit for
  // bit.
  const GradientToWorld toWorld(geometry);
  ForEachVoxelOfPart(smoothBox, box, part,
    [&](const int p[3], const std::ptrdiff_t step[3], std::ptrdiff_t v, std::ptrdiff_t o)
    {
      PotentialAndForceAt(
        smooth + v, p, geometry.Dimensions, step, toWorld, gains, potential[o], force + 3 * o);
    });
}

void PotentialAndForceInBox(const float* smooth, const ImageGeometry& geometry, const VoxelBox& box,
  const VoxelBox& part, const PotentialGains& gains, float* potential, float* force)
{
  PotentialAndForceInBox(
    smooth, VoxelBox::Whole(geometry), geometry, box, part, gains, potential, force);
}

void ForceOfPotentialInBox(const float* potentialValues, const VoxelBox& potentialBox,
  const ImageGeometry& geometry, const VoxelBox& box, const VoxelBox& part, float* potential,
  float* force)
{
  // As LocallyNormalisedField differentiates P over the image's grid (WorldGradientAt: its
  // border where the grid's is).
  const GradientToWorld toWorld(geometry);
  ForEachVoxelOfPart(potentialBox, box, part,
    [&](const int p[3], const std::ptrdiff_t step[3], std::ptrdiff_t v, std::ptrdiff_t o)
    {
      double gw[3];
      WorldGradientAt(potentialValues + v, p, geometry.Dimensions, step, toWorld, gw);
      potential[o] = potentialValues[v];
      float* f = force + 3 * o;
      f[0] = static_cast<float>(-gw[0]);
      f[1] = static_cast<float>(-gw[1]);
      f[2] = static_cast<float>(-gw[2]);
    });
}

std::string ScaleSpaceProblem(const ImageGeometry& geometry, double sigma)
{
  std::string error;
  if (!Validate(geometry, sigma, &error) && error.empty())
  {
    error = "invalid image geometry";
  }
  return error;
}

bool ComputeScaleSpaceForce(const ImageView& image, const ScaleSpaceParameters& parameters,
  ForceField& out, std::string* error)
{
  out.Potential.clear();
  out.Force.clear();
  out.Geometry = image.Geometry;
  out.Sigma = parameters.Sigma;
  if (!image.Data || !Validate(image.Geometry, parameters.Sigma, error))
  {
    if (!image.Data && error)
    {
      *error = "no data";
    }
    return false;
  }
  const std::size_t n = static_cast<std::size_t>(image.Geometry.NumberOfVoxels());
  out.Potential.resize(n);
  // P alone: the force buffer is the local normalisation's scratch (G_sigma * f and G_2sigma * g).
  const bool potentialOnly = PotentialOnly(parameters);
  out.Force.resize((potentialOnly ? 2 : 3) * n);
  if (!ComputeScaleSpaceForceInto(image, parameters, out.Potential.data(), out.Force.data(), error))
  {
    out.Potential.clear();
    out.Force.clear();
    return false;
  }
  if (potentialOnly)
  {
    out.Force.clear();
    out.Force.shrink_to_fit();
  }
  return true;
}

bool ComputeScaleSpaceForce(const float* scalars, const ImageGeometry& geometry,
  const ScaleSpaceParameters& parameters, ForceField& out, std::string* error)
{
  return ComputeScaleSpaceForce(ImageView::Of(scalars, geometry), parameters, out, error);
}
} // namespace dsurf
