// SPDX-License-Identifier: BSD-3-Clause
#include "dsScaleSpace.h"
#include "dsScaleSpaceKernels.h"

#include "dsFieldBricks.h"

#include "dsGaussianSmoother.h"
#include "dsSmoothSlabs.h"
#include "dsThreads.h"
#include "dsTrilinear.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>

namespace dsurf
{
// The helpers dsLocalPotential.cxx shares are declared in dsScaleSpaceKernels.h, namespace
// scalespace; the others are this file's own.
using namespace scalespace;

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

} // namespace

// Shared with dsLocalPotential.cxx (dsScaleSpaceKernels.h).
namespace scalespace
{
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
} // namespace scalespace

namespace
{

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

} // namespace

// Shared with dsLocalPotential.cxx (dsScaleSpaceKernels.h).
namespace scalespace
{
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
} // namespace scalespace

namespace
{

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

} // namespace

// Shared with dsLocalPotential.cxx (dsScaleSpaceKernels.h).
namespace scalespace
{
void SmoothImage(const ImageView& image, const double sigmaVoxels[3], float* smooth,
  const std::function<void(float*, const double*)>& pieceSmooth)
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

void SigmaVoxels(double sigma, const ImageGeometry& geometry, double sv[3])
{
  for (int a = 0; a < 3; ++a)
  {
    sv[a] = sigma / geometry.Spacing[a];
  }
}

bool PotentialOnly(const ScaleSpaceParameters& parameters)
{
  return !parameters.ComputeForce && parameters.NormalizePotential &&
    parameters.EdgeNormalization == EdgeNormalization::Local;
}
} // namespace scalespace

namespace
{

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
