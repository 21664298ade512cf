#include "dsScaleSpace.h"

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
//------------------------------------------------------------------------------
// One axis of the separable Gaussian. Recursive (Young & van Vliet 1995, 3rd order):
//   forward  w[n] = B x[n] + a1 w[n-1] + a2 w[n-2] + a3 w[n-3]
//   backward y[n] = B w[n] + a1 y[n+1] + a2 y[n+2] + a3 y[n+3]
// The coefficients are double on purpose: B ~ 1e-5 at sigma 43, and float
// coefficients would miss the unit DC gain by percents.
struct AxisSmoother
{
  enum Kind
  {
    Identity,
    FIR,
    IIR
  } Type = Identity;
  std::vector<double> Taps; // FIR: 2R+1 taps, centre at R
  int Radius = 0;
  double B = 1, A1 = 0, A2 = 0, A3 = 0;
  double M[9] = { 0 }; // Triggs-Sdika right-border start, row-major
};

void YvVCoefficients(double q, double& B, double& a1, double& a2, double& a3)
{
  const double q2 = q * q, q3 = q2 * q;
  const double b0 = 1.57825 + 2.44413 * q + 1.4281 * q2 + 0.422205 * q3;
  const double b1 = 2.44413 * q + 2.85619 * q2 + 1.26661 * q3;
  const double b2 = -(1.4281 * q2 + 1.26661 * q3);
  const double b3 = 0.422205 * q3;
  a1 = b1 / b0;
  a2 = b2 / b0;
  a3 = b3 / b0;
  B = 1.0 - (a1 + a2 + a3);
}

// Variance of the forward+backward impulse response: twice that of the causal part,
// from the generating function G(t) = B / (1 - a1 t - a2 t^2 - a3 t^3) at t = 1.
double IIRVariance(double q)
{
  double B, a1, a2, a3;
  YvVCoefficients(q, B, a1, a2, a3);
  const double d1 = -(a1 + 2 * a2 + 3 * a3); // D'(1)
  const double d2 = -(2 * a2 + 6 * a3);      // D''(1)
  const double g1 = -d1 / B;
  const double g2 = 2 * d1 * d1 / (B * B) - d2 / B;
  return 2.0 * (g2 + g1 - g1 * g1);
}

// Right-border start (Triggs & Sdika 2006) for an input held constant at u past the
// end: (y[N-1], y[N], y[N+1]) - u = M (w[N-1], w[N-2], w[N-3]) - u. M is obtained by
// running the two recursions on the basis states until they have died out, which
// avoids transcribing the closed form and is exact to rounding.
void TriggsMatrix(AxisSmoother& s, double sigmaVoxels)
{
  const int L = static_cast<int>(std::min(40.0 * sigmaVoxels + 100.0, 4.0e6));
  std::vector<double> d(L + 6), e(L + 6);
  for (int c = 0; c < 3; ++c)
  {
    std::fill(d.begin(), d.end(), 0.0);
    std::fill(e.begin(), e.end(), 0.0);
    // index t: 0 <-> N-3, 1 <-> N-2, 2 <-> N-1
    d[2 - c] = 1.0;
    for (int t = 3; t < L + 3; ++t)
    {
      d[t] = s.A1 * d[t - 1] + s.A2 * d[t - 2] + s.A3 * d[t - 3];
    }
    for (int t = L + 2; t >= 2; --t)
    {
      e[t] = s.B * d[t] + s.A1 * e[t + 1] + s.A2 * e[t + 2] + s.A3 * e[t + 3];
    }
    s.M[0 * 3 + c] = e[2];
    s.M[1 * 3 + c] = e[3];
    s.M[2 * 3 + c] = e[4];
  }
}

AxisSmoother MakeSmoother(double sigmaVoxels)
{
  AxisSmoother s;
  if (!(sigmaVoxels > 1e-3))
  {
    return s;
  }
  if (sigmaVoxels < 1.0)
  {
    // The 3-pole recursion cannot be this narrow; a sampled Gaussian is cheap here.
    s.Type = AxisSmoother::FIR;
    s.Radius = std::max(1, static_cast<int>(std::ceil(4.0 * sigmaVoxels)));
    s.Taps.resize(2 * s.Radius + 1);
    auto build = [&s](double width)
    {
      double sum = 0.0, var = 0.0;
      for (int k = -s.Radius; k <= s.Radius; ++k)
      {
        const double w = std::exp(-0.5 * k * k / (width * width));
        s.Taps[k + s.Radius] = w;
        sum += w;
        var += w * k * k;
      }
      for (double& w : s.Taps)
      {
        w /= sum;
      }
      return var / sum;
    };
    // Sampling a narrow Gaussian loses variance; widen it so the taps have sigma^2.
    double lo = 0.5 * sigmaVoxels, hi = 2.0 * sigmaVoxels;
    if (build(hi) > sigmaVoxels * sigmaVoxels)
    {
      for (int it = 0; it < 100; ++it)
      {
        const double mid = 0.5 * (lo + hi);
        (build(mid) < sigmaVoxels * sigmaVoxels ? lo : hi) = mid;
      }
      build(0.5 * (lo + hi));
    }
    else
    {
      build(sigmaVoxels);
    }
    return s;
  }
  s.Type = AxisSmoother::IIR;
  // Young-van Vliet's q(sigma) fit misses the variance by a few percent; solve for
  // the q that gives exactly sigma^2 so gradient magnitudes are at the stated scale.
  const double target = sigmaVoxels * sigmaVoxels;
  double lo = 0.05, hi = 2.0 * sigmaVoxels + 10.0;
  for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it)
  {
    const double mid = 0.5 * (lo + hi);
    (IIRVariance(mid) < target ? lo : hi) = mid;
  }
  YvVCoefficients(0.5 * (lo + hi), s.B, s.A1, s.A2, s.A3);
  TriggsMatrix(s, sigmaVoxels);
  return s;
}

//------------------------------------------------------------------------------
// One contiguous line, in place (in may equal out). w: n doubles of scratch.
void IIRLine(const float* in, float* out, int n, const AxisSmoother& s, double* w)
{
  const double x0 = in[0];
  const double u = in[n - 1];
  double w1 = x0, w2 = x0, w3 = x0;
  for (int i = 0; i < n; ++i)
  {
    const double v = s.B * in[i] + s.A1 * w1 + s.A2 * w2 + s.A3 * w3;
    w[i] = v;
    w3 = w2;
    w2 = w1;
    w1 = v;
  }
  const double d0 = w1 - u, d1 = w2 - u, d2 = w3 - u; // w[N-1], w[N-2], w[N-3]
  double y1 = u + s.M[0] * d0 + s.M[1] * d1 + s.M[2] * d2;
  double y2 = u + s.M[3] * d0 + s.M[4] * d1 + s.M[5] * d2;
  double y3 = u + s.M[6] * d0 + s.M[7] * d1 + s.M[8] * d2;
  out[n - 1] = static_cast<float>(y1);
  for (int i = n - 2; i >= 0; --i)
  {
    const double v = s.B * w[i] + s.A1 * y1 + s.A2 * y2 + s.A3 * y3;
    out[i] = static_cast<float>(v);
    y3 = y2;
    y2 = y1;
    y1 = v;
  }
}

void FIRLine(const float* in, float* out, int n, const AxisSmoother& s, double* pad)
{
  const int R = s.Radius;
  for (int i = -R; i < n + R; ++i)
  {
    pad[i + R] = in[std::min(std::max(i, 0), n - 1)];
  }
  for (int i = 0; i < n; ++i)
  {
    double v = 0.0;
    for (int k = 0; k <= 2 * R; ++k)
    {
      v += s.Taps[k] * pad[i + k];
    }
    out[i] = static_cast<float>(v);
  }
}

// N rows of nx contiguous floats, row r at base + r*stride, filtered along r in place.
// The recursion runs over whole rows so memory access stays sequential and the
// inner loops vectorise. scratch: 4*nx doubles (IIR) or N*nx floats (FIR).
void IIRRows(
  float* base, int N, std::ptrdiff_t stride, int nx, const AxisSmoother& s, double* scratch)
{
  double* s1 = scratch;
  double* s2 = scratch + nx;
  double* s3 = scratch + 2 * nx;
  double* last = scratch + 3 * nx;
  const double B = s.B, a1 = s.A1, a2 = s.A2, a3 = s.A3;
  {
    const float* r0 = base;
    const float* rl = base + (N - 1) * stride;
    for (int i = 0; i < nx; ++i)
    {
      s1[i] = s2[i] = s3[i] = r0[i];
      last[i] = rl[i];
    }
  }
  for (int r = 0; r < N; ++r)
  {
    float* row = base + r * stride;
    for (int i = 0; i < nx; ++i)
    {
      const double v = B * row[i] + a1 * s1[i] + a2 * s2[i] + a3 * s3[i];
      row[i] = static_cast<float>(v);
      s3[i] = v;
    }
    std::swap(s2, s3); // (s1,s2,s3) <- (s3,s1,s2)
    std::swap(s1, s2);
  }
  {
    const double* M = s.M;
    float* row = base + (N - 1) * stride;
    for (int i = 0; i < nx; ++i)
    {
      const double u = last[i];
      const double d0 = s1[i] - u, d1 = s2[i] - u, d2 = s3[i] - u;
      const double y1 = u + M[0] * d0 + M[1] * d1 + M[2] * d2;
      const double y2 = u + M[3] * d0 + M[4] * d1 + M[5] * d2;
      const double y3 = u + M[6] * d0 + M[7] * d1 + M[8] * d2;
      s1[i] = y1;
      s2[i] = y2;
      s3[i] = y3;
      row[i] = static_cast<float>(y1);
    }
  }
  for (int r = N - 2; r >= 0; --r)
  {
    float* row = base + r * stride;
    for (int i = 0; i < nx; ++i)
    {
      const double v = B * row[i] + a1 * s1[i] + a2 * s2[i] + a3 * s3[i];
      row[i] = static_cast<float>(v);
      s3[i] = v;
    }
    std::swap(s2, s3);
    std::swap(s1, s2);
  }
}

void FIRRows(float* base, int N, std::ptrdiff_t stride, int nx, const AxisSmoother& s, float* copy)
{
  for (int r = 0; r < N; ++r)
  {
    std::copy(
      base + r * stride, base + r * stride + nx, copy + static_cast<std::ptrdiff_t>(r) * nx);
  }
  const int R = s.Radius;
  for (int r = 0; r < N; ++r)
  {
    float* row = base + r * stride;
    for (int i = 0; i < nx; ++i)
    {
      row[i] = 0.0f;
    }
    for (int k = -R; k <= R; ++k)
    {
      const float* src =
        copy + static_cast<std::ptrdiff_t>(std::min(std::max(r + k, 0), N - 1)) * nx;
      const float w = static_cast<float>(s.Taps[k + R]);
      for (int i = 0; i < nx; ++i)
      {
        row[i] += w * src[i];
      }
    }
  }
}

// Runs body with vtkSMPTools on the STDThread backend (the machine default is
// Sequential), limited to n threads.
template <typename F>
void WithThreads(int n, F&& body)
{
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ ResolveThreads(n), "STDThread", false }, body);
}

// Separable smoothing of src into dst (dst may equal src). Called inside WithThreads.
void Smooth(const float* src, float* dst, const int dims[3], const double sigmaVoxels[3])
{
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  const std::ptrdiff_t slice = static_cast<std::ptrdiff_t>(nx) * ny;
  const AxisSmoother sx = MakeSmoother(sigmaVoxels[0]);
  const AxisSmoother sy = MakeSmoother(sigmaVoxels[1]);
  const AxisSmoother sz = MakeSmoother(sigmaVoxels[2]);

  // x: one line per (j,k).
  const long long nLines = static_cast<long long>(ny) * nz;
  vtkSMPTools::For(0, nLines,
    [&](long long begin, long long end)
    {
      std::vector<double> scratch(nx + 2 * (sx.Radius + 1));
      for (long long l = begin; l < end; ++l)
      {
        const float* in = src + l * nx;
        float* out = dst + l * nx;
        switch (sx.Type)
        {
          case AxisSmoother::IIR:
            IIRLine(in, out, nx, sx, scratch.data());
            break;
          case AxisSmoother::FIR:
            FIRLine(in, out, nx, sx, scratch.data());
            break;
          default:
            if (in != out)
            {
              std::copy(in, in + nx, out);
            }
        }
      }
    });

  auto rows =
    [&](const AxisSmoother& s, long long count, int N, std::ptrdiff_t outer, std::ptrdiff_t stride)
  {
    if (s.Type == AxisSmoother::Identity)
    {
      return;
    }
    vtkSMPTools::For(0, count,
      [&](long long begin, long long end)
      {
        std::vector<double> dscratch;
        std::vector<float> fscratch;
        if (s.Type == AxisSmoother::IIR)
        {
          dscratch.resize(4 * static_cast<std::size_t>(nx));
        }
        else
        {
          fscratch.resize(static_cast<std::size_t>(N) * nx);
        }
        for (long long c = begin; c < end; ++c)
        {
          float* base = dst + c * outer;
          if (s.Type == AxisSmoother::IIR)
          {
            IIRRows(base, N, stride, nx, s, dscratch.data());
          }
          else
          {
            FIRRows(base, N, stride, nx, s, fscratch.data());
          }
        }
      });
  };
  rows(sy, nz, ny, slice, nx); // y: for each k, rows j
  rows(sz, ny, nz, nx, slice); // z: for each j, rows k
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
  Smooth(g, scratch, dims, wide);
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
double SmootherVariance(double sigmaVoxels)
{
  const AxisSmoother s = MakeSmoother(sigmaVoxels);
  switch (s.Type)
  {
    case AxisSmoother::IIR:
    {
      // From the coefficients actually in use, not from the target.
      const double d1 = -(s.A1 + 2 * s.A2 + 3 * s.A3);
      const double d2 = -(2 * s.A2 + 6 * s.A3);
      const double g1 = -d1 / s.B;
      const double g2 = 2 * d1 * d1 / (s.B * s.B) - d2 / s.B;
      return 2.0 * (g2 + g1 - g1 * g1);
    }
    case AxisSmoother::FIR:
    {
      double v = 0.0;
      for (int k = -s.Radius; k <= s.Radius; ++k)
      {
        v += s.Taps[k + s.Radius] * k * k;
      }
      return v;
    }
    default:
      return 0.0;
  }
}

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
  WithThreads(numberOfThreads, [&]() { Smooth(volume, volume, geometry.Dimensions, sv); });
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
      Smooth(scalars, smooth, dims, sv);
      const EdgeStatistics stats = EdgeMagnitude(smooth, dims, toWorld, potential);
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
