#include "dsScaleSpace.h"

#include "dsGaussianSmoother.h"
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
//------------------------------------------------------------------------------
double ImageGeometry::MeanExtent() const
{
  double sum = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    sum += this->Dimensions[a] * this->Spacing[a];
  }
  return sum / 3.0;
}

void ImageGeometry::WorldToIndex(const double x[3], double ijk[3]) const
{
  const double d[3] = { x[0] - this->Origin[0], x[1] - this->Origin[1], x[2] - this->Origin[2] };
  const double* D = this->Direction;
  // Orthonormal direction: its inverse is its transpose.
  ijk[0] = (D[0] * d[0] + D[3] * d[1] + D[6] * d[2]) / this->Spacing[0];
  ijk[1] = (D[1] * d[0] + D[4] * d[1] + D[7] * d[2]) / this->Spacing[1];
  ijk[2] = (D[2] * d[0] + D[5] * d[1] + D[8] * d[2]) / this->Spacing[2];
}

void ImageGeometry::IndexToWorld(const double ijk[3], double x[3]) const
{
  const double s[3] = { ijk[0] * this->Spacing[0], ijk[1] * this->Spacing[1],
    ijk[2] * this->Spacing[2] };
  const double* D = this->Direction;
  x[0] = this->Origin[0] + D[0] * s[0] + D[1] * s[1] + D[2] * s[2];
  x[1] = this->Origin[1] + D[3] * s[0] + D[4] * s[1] + D[5] * s[2];
  x[2] = this->Origin[2] + D[6] * s[0] + D[7] * s[1] + D[8] * s[2];
}

namespace
{
/// The trilinear cell of world point x. A voxel covers half a spacing around its centre, so
/// the volume reaches half a voxel beyond the outermost centres (the image bounds); there the
/// border value is used. A start box at the image bounds thus feels the force at every vertex.
bool LocateCell(const ImageGeometry& g, const double x[3], TrilinearCell& c)
{
  double ijk[3];
  g.WorldToIndex(x, ijk);
  const int lo[3] = { 0, 0, 0 };
  const int hi[3] = { g.Dimensions[0] - 1, g.Dimensions[1] - 1, g.Dimensions[2] - 1 };
  return LocateTrilinearCell(ijk, lo, hi, 0.5, c);
}
} // namespace

bool ForceField::SampleForce(const double x[3], double f[3]) const
{
  f[0] = f[1] = f[2] = 0.0;
  TrilinearCell c;
  if (this->Force.empty() || !LocateCell(this->Geometry, x, c))
  {
    return false;
  }
  const float* F = this->Force.data();
  for (int corner = 0; corner < 8; ++corner)
  {
    const double w = c.Weight(corner);
    const float* v = F + 3 * c.Corner(corner);
    f[0] += w * v[0];
    f[1] += w * v[1];
    f[2] += w * v[2];
  }
  return true;
}

double SampleVolume(
  const float* values, const ImageGeometry& geometry, const double x[3], bool* inside)
{
  TrilinearCell c;
  const bool in = values && LocateCell(geometry, x, c);
  if (inside)
  {
    *inside = in;
  }
  if (!in)
  {
    return 0.0;
  }
  double v = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    v += c.Weight(corner) * values[c.Corner(corner)];
  }
  return v;
}

double ForceField::SamplePotential(const double x[3]) const
{
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
// volume. Returns the new maximum. A Gaussian-weighted local mean, not a local maximum: it is
// smooth, so dividing by it adds no steps (spurious forces) to the potential. For an isolated
// edge of any contrast the ratio peaks at ~sqrt(5) (a Gaussian ridge of width sigma over its
// own blur at 2 sigma), so every isolated boundary ends up equally strong.
double NormalizeEdgesLocally(
  float* g, float* scratch, const int dims[3], const double sigmaVoxels[3], double floor)
{
  const double wide[3] = { 2 * sigmaVoxels[0], 2 * sigmaVoxels[1], 2 * sigmaVoxels[2] };
  SmoothGaussianSeparable(g, scratch, dims, wide);
  const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  std::vector<double> maxima(dims[2], 0.0);
  ForEachVoxelSlice(dims,
    [&](int k)
    {
      double m = 0.0;
      for (std::ptrdiff_t v = k * sz, e = v + sz; v < e; ++v)
      {
        const double r = g[v] / (std::max(0.0, static_cast<double>(scratch[v])) + floor);
        g[v] = static_cast<float>(r);
        m = std::max(m, r);
      }
      maxima[k] = m;
    });
  return *std::max_element(maxima.begin(), maxima.end());
}

/// Calls visit(v, gw) for every voxel v of slice k with gw the world gradient of `values`
/// there (central differences in index space, one-sided at the border, turned to world).
template <typename Visit>
void ForEachWorldGradientOfSlice(
  const float* values, const int dims[3], const GradientToWorld& toWorld, int k, Visit&& visit)
{
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  const std::ptrdiff_t sx = 1, sy = nx, sz = static_cast<std::ptrdiff_t>(nx) * ny;
  for (int j = 0; j < ny; ++j)
  {
    const std::ptrdiff_t row = k * sz + j * sy;
    for (int i = 0; i < nx; ++i)
    {
      const float* v = values + row + i;
      const double gi[3] = { Diff(v, i, nx, sx), Diff(v, j, ny, sy), Diff(v, k, nz, sz) };
      double gw[3];
      toWorld.Apply(gi, gw);
      visit(row + i, gw);
    }
  }
}

/// Why ComputeScaleSpaceForceInto cannot run on these inputs; empty when it can.
std::string CheckForceInputs(const float* scalars, const ImageGeometry& geometry,
  const ScaleSpaceParameters& parameters, const float* potential, const float* force)
{
  std::string error;
  if (!scalars || !potential || !force)
  {
    return "no data";
  }
  if (!Validate(geometry, parameters.Sigma, &error))
  {
    return error.empty() ? std::string("invalid image geometry") : error;
  }
  if (!std::isfinite(parameters.EdgeWeight) || !std::isfinite(parameters.ImageWeight))
  {
    return "the weights must be finite";
  }
  // One NaN or Inf would spread along every line of the recursive filter and turn the
  // whole field into NaN.
  const long long n = geometry.NumberOfVoxels();
  long long bad = 0;
  for (long long i = 0; i < n; ++i)
  {
    bad += std::isfinite(scalars[i]) ? 0 : 1;
  }
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

/// g = |grad smooth| into `edges`, with the extrema the normalisation needs.
EdgeStatistics EdgeMagnitude(
  const float* smooth, const int dims[3], const GradientToWorld& toWorld, float* edges)
{
  const int nz = dims[2];
  std::vector<double> gMax(nz, 0.0), sMin(nz, std::numeric_limits<double>::max()),
    sMax(nz, std::numeric_limits<double>::lowest());
  ForEachVoxelSlice(dims,
    [&](int k)
    {
      double gm = 0.0, lo = sMin[k], hi = sMax[k];
      ForEachWorldGradientOfSlice(smooth, dims, toWorld, k,
        [&](std::ptrdiff_t v, const double gw[3])
        {
          const double g = std::sqrt(gw[0] * gw[0] + gw[1] * gw[1] + gw[2] * gw[2]);
          edges[v] = static_cast<float>(g);
          gm = std::max(gm, g);
          lo = std::min(lo, static_cast<double>(smooth[v]));
          hi = std::max(hi, static_cast<double>(smooth[v]));
        });
      gMax[k] = gm;
      sMin[k] = lo;
      sMax[k] = hi;
    });
  EdgeStatistics s;
  s.GradientMax = *std::max_element(gMax.begin(), gMax.end());
  s.SmoothMin = *std::min_element(sMin.begin(), sMin.end());
  s.SmoothMax = *std::max_element(sMax.begin(), sMax.end());
  return s;
}

/// The largest g over the voxels [MaximumBegin, MaximumEnd) of `parameters` (a piece's own,
/// ScaleSpaceParameters::GradientMaximum), in double as EdgeMagnitude computes it.
double BoxGradientMaximum(const float* smooth, const int dims[3], const GradientToWorld& toWorld,
  const ScaleSpaceParameters& parameters)
{
  const int* b = parameters.MaximumBegin;
  const int* e = parameters.MaximumEnd;
  const std::ptrdiff_t nx = dims[0], sz = nx * dims[1];
  double gm = 0.0;
  for (int k = std::max(0, b[2]); k < std::min(dims[2], e[2]); ++k)
  {
    ForEachWorldGradientOfSlice(smooth, dims, toWorld, k,
      [&](std::ptrdiff_t v, const double gw[3])
      {
        const std::ptrdiff_t j = (v - k * sz) / nx, i = v - k * sz - j * nx;
        if (j >= b[1] && j < e[1] && i >= b[0] && i < e[0])
        {
          gm = std::max(gm, std::sqrt(gw[0] * gw[0] + gw[1] * gw[1] + gw[2] * gw[2]));
        }
      });
  }
  return gm;
}

/// P = -(ge g + gs s + offset) in place of g in `potential` (docs/METHOD.md §2, with the
/// optional normalisation of both terms); `scratch` holds one volume for the local one.
void CombinePotential(float* potential, const float* smooth, float* scratch, const int dims[3],
  const double sigmaVoxels[3], const EdgeStatistics& stats, const ScaleSpaceParameters& parameters)
{
  const double we = parameters.EdgeWeight, wi = parameters.ImageWeight;
  double ge = we, gs = wi, offset = 0.0;
  double gNorm = stats.GradientMax;
  if (parameters.NormalizePotential && parameters.EdgeNormalization == EdgeNormalization::Local &&
    stats.GradientMax > 0.0)
  {
    gNorm = NormalizeEdgesLocally(
      potential, scratch, dims, sigmaVoxels, parameters.LocalEdgeFloor * stats.GradientMax);
  }
  if (parameters.NormalizePotential)
  {
    ge = gNorm > 0.0 ? we / gNorm : 0.0;
    gs = stats.SmoothMax > stats.SmoothMin ? wi / (stats.SmoothMax - stats.SmoothMin) : 0.0;
    offset = -gs * stats.SmoothMin;
  }
  const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  ForEachVoxelSlice(dims,
    [&](int k)
    {
      const std::ptrdiff_t b = k * sz, e = b + sz;
      for (std::ptrdiff_t v = b; v < e; ++v)
      {
        potential[v] = static_cast<float>(-(ge * potential[v] + gs * smooth[v] + offset));
      }
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

bool ComputeScaleSpaceForceInto(const float* scalars, const ImageGeometry& geometry,
  const ScaleSpaceParameters& parameters, float* potential, float* force, std::string* error)
{
  const std::string problem = CheckForceInputs(scalars, geometry, parameters, potential, force);
  if (!problem.empty())
  {
    if (error)
    {
      *error = problem;
    }
    return false;
  }
  const int* dims = geometry.Dimensions;
  const double sv[3] = { parameters.Sigma / geometry.Spacing[0],
    parameters.Sigma / geometry.Spacing[1], parameters.Sigma / geometry.Spacing[2] };
  const GradientToWorld toWorld(geometry);

  WithThreads(parameters.NumberOfThreads,
    [&]()
    {
      // The first third of the force buffer holds G_sigma*f until P is known; the rest is
      // scratch for the local edge normalisation.
      float* smooth = force;
      SmoothGaussianSeparable(scalars, smooth, dims, sv);
      EdgeStatistics stats = EdgeMagnitude(smooth, dims, toWorld, potential);
      if (parameters.GradientMaximum)
      {
        stats.GradientMax =
          parameters.GradientMaximum(BoxGradientMaximum(smooth, dims, toWorld, parameters));
      }
      float* scratch = force + dims[0] * static_cast<std::ptrdiff_t>(dims[1]) * dims[2];
      CombinePotential(potential, smooth, scratch, dims, sv, stats, parameters);

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
    });
  // Finite inputs can still overflow single precision: a weight near VTK_DOUBLE_MAX, or a
  // sigma so large that the recursive filter's coefficients are not finite.
  const std::size_t n = static_cast<std::size_t>(geometry.NumberOfVoxels());
  if (!std::all_of(potential, potential + n, [](float v) { return std::isfinite(v); }) ||
    !std::all_of(force, force + 3 * n, [](float v) { return std::isfinite(v); }))
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

std::string ScaleSpaceProblem(const ImageGeometry& geometry, double sigma)
{
  std::string error;
  if (!Validate(geometry, sigma, &error) && error.empty())
  {
    error = "invalid image geometry";
  }
  return error;
}

bool ComputeScaleSpaceForce(const float* scalars, const ImageGeometry& geometry,
  const ScaleSpaceParameters& parameters, ForceField& out, std::string* error)
{
  out.Potential.clear();
  out.Force.clear();
  out.Geometry = geometry;
  out.Sigma = parameters.Sigma;
  if (!scalars || !Validate(geometry, parameters.Sigma, error))
  {
    if (!scalars && error)
    {
      *error = "no data";
    }
    return false;
  }
  const std::size_t n = static_cast<std::size_t>(geometry.NumberOfVoxels());
  out.Potential.resize(n);
  out.Force.resize(3 * n);
  if (!ComputeScaleSpaceForceInto(
        scalars, geometry, parameters, out.Potential.data(), out.Force.data(), error))
  {
    out.Potential.clear();
    out.Force.clear();
    return false;
  }
  return true;
}
} // namespace dsurf
