// SPDX-License-Identifier: BSD-3-Clause
#include "dsGaussianSmoother.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <complex>
#include <cstddef>
#include <vector>

namespace dsurf
{
namespace
{
// Order of the recursive filter. The 3rd-order filter of the same paper departs from the
// Gaussian by ~1 % of the peak and its edge pull 2.5-3 sigma out is ~15 % too strong; the
// 5th order is within 0.11 % and 3.1 % from 3 voxels on (docs/METHOD.md §6c).
constexpr int K = 5;
static_assert(K == RecursiveAxisPass::States, "a line's state is the cascade's K values");

// One axis of the separable Gaussian. Recursive: the 5 poles as a cascade of one real and two
// complex-pair sections, each with unit DC gain, run forward and then backward:
//   f1[n] = BR x[n] + R f1[n-1]
//   f2[n] = BC[0] f1[n] + C1[0] f2[n-1] + C2[0] f2[n-2]
//   f3[n] = BC[1] f2[n] + C1[1] f3[n-1] + C2[1] f3[n-2]       (backward: n+1, n+2)
// Sections rather than one 5th-order recursion: with the poles crowding towards 1 at large
// sigma the expanded polynomial loses all precision (its border start was off by 14 % of the
// step at 100 voxels); the sections measure as accurate at 1000 voxels as at 5.
// The state of the cascade is (f1[n], f2[n], f2[n-1], f3[n], f3[n-1]).
struct AxisSmoother
{
  enum Kind
  {
    Identity,
    FIR,
    IIR
  } Type = Identity;
  std::vector<double> Taps; // FIR: Taps[k] for offsets +k and -k, k = 0..Radius
  int Radius = 0;
  double R = 0, BR = 1;
  double C1[2] = { 0, 0 }, C2[2] = { 0, 0 }, BC[2] = { 1, 1 };
  double M[K * K] = { 0 }; // Triggs-Sdika right-border start, row-major
};

// One step of the cascade on input x; st is updated and the output returned. The backward
// pass uses it too, with st holding the states one and two samples ahead.
inline double CascadeStep(const AxisSmoother& s, double x, double st[K])
{
  const double a = s.BR * x + s.R * st[0];
  const double b = s.BC[0] * a + s.C1[0] * st[1] + s.C2[0] * st[2];
  const double c = s.BC[1] * b + s.C1[1] * st[3] + s.C2[1] * st[4];
  st[0] = a;
  st[2] = st[1];
  st[1] = b;
  st[4] = st[3];
  st[3] = c;
  return c;
}

// The z-domain poles at scale q: 1 / d^(1/q) for the 5th-order smoothing poles d of van Vliet,
// Young & Verbeek (1998), Table 1 (designed for q = 1, i.e. sigma ~ 2 voxels): two complex
// pairs (given by one member each) and a real pole, last.
void ScaledPoles(double q, std::complex<double> p[3])
{
  static const std::complex<double> d[3] = { { 0.86430, 1.45389 }, { 1.61433, 0.83134 },
    { 1.87504, 0.0 } };
  for (int k = 0; k < 3; ++k)
  {
    p[k] = 1.0 / std::pow(d[k], 1.0 / q);
  }
}

// Variance of the forward + backward impulse response: each pole p of the causal part adds
// p / (1 - p)^2 (a pair twice the real part), and the backward pass doubles the sum.
double RecursiveVariance(double q)
{
  std::complex<double> p[3];
  ScaledPoles(q, p);
  const auto term = [](std::complex<double> z) { return z / ((1.0 - z) * (1.0 - z)); };
  return 2.0 * (2.0 * term(p[0]).real() + 2.0 * term(p[1]).real() + term(p[2]).real());
}

void RecursiveCoefficients(double q, AxisSmoother& s)
{
  std::complex<double> p[3];
  ScaledPoles(q, p);
  for (int k = 0; k < 2; ++k)
  {
    s.C1[k] = 2.0 * p[k].real();
    s.C2[k] = -std::norm(p[k]);
    s.BC[k] = 1.0 - s.C1[k] - s.C2[k];
  }
  s.R = p[2].real();
  s.BR = 1.0 - s.R;
}

// Right-border start (Triggs & Sdika 2006) for an input held constant at u past the end: the
// backward states ahead of N-1, minus u, are M times the forward state at N-1, minus u. M is
// obtained by running the two passes on the basis states until they have died out (~34 sigma
// for these poles), which avoids transcribing the closed form and is exact to rounding.
void TriggsMatrix(AxisSmoother& s, double sigmaVoxels)
{
  const int L = static_cast<int>(std::min(40.0 * sigmaVoxels + 100.0, 4.0e6));
  std::vector<double> w(L);
  for (int c = 0; c < K; ++c)
  {
    double st[K] = { 0, 0, 0, 0, 0 };
    st[c] = 1.0;
    for (int t = 0; t < L; ++t)
    {
      w[t] = CascadeStep(s, 0.0, st);
    }
    double ahead[K] = { 0, 0, 0, 0, 0 };
    for (int t = L - 1; t >= 0; --t)
    {
      CascadeStep(s, w[t], ahead);
    }
    for (int m = 0; m < K; ++m)
    {
      s.M[m * K + c] = ahead[m];
    }
  }
}

// The backward states ahead of the last sample from the forward state there (in place), for
// an input replicated past the end at u.
inline void StartBackward(const AxisSmoother& s, double u, double st[K])
{
  double d[K];
  for (int c = 0; c < K; ++c)
  {
    d[c] = st[c] - u;
  }
  for (int m = 0; m < K; ++m)
  {
    st[m] = u;
    for (int c = 0; c < K; ++c)
    {
      st[m] += s.M[m * K + c] * d[c];
    }
  }
}

// Sampled Gaussian, radius 4 sigma. Sampling a narrow Gaussian loses variance (below ~0.8
// voxel), so the width is raised until the taps have sigma^2; from 1 voxel on that changes
// nothing measurable and the taps are the sampled Gaussian itself.
void SampledGaussianTaps(AxisSmoother& s, double sigmaVoxels)
{
  s.Radius = std::max(1, static_cast<int>(std::ceil(4.0 * sigmaVoxels)));
  s.Taps.resize(s.Radius + 1);
  auto build = [&s](double width)
  {
    double sum = 0.0, var = 0.0;
    for (int k = 0; k <= s.Radius; ++k)
    {
      const double w = std::exp(-0.5 * k * k / (width * width));
      s.Taps[k] = w;
      sum += k == 0 ? w : 2.0 * w;
      var += 2.0 * w * k * k;
    }
    for (double& w : s.Taps)
    {
      w /= sum;
    }
    return var / sum;
  };
  const double target = sigmaVoxels * sigmaVoxels;
  double lo = 0.5 * sigmaVoxels, hi = 2.0 * sigmaVoxels;
  if (build(hi) > target)
  {
    for (int it = 0; it < 100; ++it)
    {
      const double mid = 0.5 * (lo + hi);
      (build(mid) < target ? lo : hi) = mid;
    }
    build(0.5 * (lo + hi));
  }
  else
  {
    build(sigmaVoxels);
  }
}

AxisSmoother MakeSmoother(double sigmaVoxels)
{
  AxisSmoother s;
  if (!(sigmaVoxels > 1e-3))
  {
    return s;
  }
  if (sigmaVoxels < GaussianRecursiveFromSigmaVoxels)
  {
    s.Type = AxisSmoother::FIR;
    SampledGaussianTaps(s, sigmaVoxels);
    return s;
  }
  s.Type = AxisSmoother::IIR;
  // The variance grows with q; q ~ sigma / 2 for these poles.
  const double target = sigmaVoxels * sigmaVoxels;
  double lo = 0.05, hi = sigmaVoxels + 10.0;
  for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it)
  {
    const double mid = 0.5 * (lo + hi);
    (RecursiveVariance(mid) < target ? lo : hi) = mid;
  }
  RecursiveCoefficients(0.5 * (lo + hi), s);
  TriggsMatrix(s, sigmaVoxels);
  return s;
}

//------------------------------------------------------------------------------
// One contiguous line, in place (in may equal out). w: n doubles of scratch.
void IIRLine(const float* in, float* out, int n, const AxisSmoother& s, double* w)
{
  // Replicated left border: the forward pass starts in its steady state for in[0].
  double st[K];
  std::fill(st, st + K, static_cast<double>(in[0]));
  for (int i = 0; i < n; ++i)
  {
    w[i] = CascadeStep(s, in[i], st);
  }
  StartBackward(s, in[n - 1], st);
  for (int i = n - 1; i >= 0; --i)
  {
    out[i] = static_cast<float>(CascadeStep(s, w[i], st));
  }
}

// pad: n + 2 (Radius + 1) doubles, then n more for the sums. Each output is the sum
// Taps[0] c[0] + Taps[1] (c[-1] + c[1]) + ... in that order, built tap by tap over the whole
// line so that the loops vectorise (the same arithmetic as one voxel at a time).
void FIRLine(const float* in, float* out, int n, const AxisSmoother& s, double* pad)
{
  const int R = s.Radius;
  for (int i = -R; i < n + R; ++i)
  {
    pad[i + R] = in[std::min(std::max(i, 0), n - 1)];
  }
  const double* __restrict c = pad + R;
  double* __restrict v = pad + n + 2 * (R + 1);
  const double t0 = s.Taps[0];
  for (int i = 0; i < n; ++i)
  {
    v[i] = t0 * c[i];
  }
  for (int k = 1; k <= R; ++k)
  {
    const double t = s.Taps[k];
    for (int i = 0; i < n; ++i)
    {
      v[i] += t * (c[i - k] + c[i + k]);
    }
  }
  for (int i = 0; i < n; ++i)
  {
    out[i] = static_cast<float>(v[i]);
  }
}

// One step of the cascade over a whole row, in place: f1 holds the real section's state, f2
// and f3 the pair sections' newest states, f2Old and f3Old their older ones, which receive the
// new values. Restrict parameters (and the coefficients in locals) let the loop vectorise.
void CascadeRow(float* __restrict row, int nx, const AxisSmoother& s, double* __restrict f1,
  const double* __restrict f2, double* __restrict f2Old, const double* __restrict f3,
  double* __restrict f3Old)
{
  const double br = s.BR, r = s.R, b2 = s.BC[0], c21 = s.C1[0], c22 = s.C2[0], b3 = s.BC[1],
               c31 = s.C1[1], c32 = s.C2[1];
  for (int i = 0; i < nx; ++i)
  {
    const double a = br * row[i] + r * f1[i];
    const double b = b2 * a + c21 * f2[i] + c22 * f2Old[i];
    const double c = b3 * b + c31 * f3[i] + c32 * f3Old[i];
    f1[i] = a;
    f2Old[i] = b;
    f3Old[i] = c;
    row[i] = static_cast<float>(c);
  }
}

// The cascade over a whole row with the states of column i in state[0..K-1][i]; the pair
// sections' two state arrays swap, so nothing is copied.
void CascadeRowStep(float* row, int nx, const AxisSmoother& s, double* state[K])
{
  CascadeRow(row, nx, s, state[0], state[1], state[2], state[3], state[4]);
  std::swap(state[1], state[2]);
  std::swap(state[3], state[4]);
}

// N rows of nx contiguous floats, row r at base + r*stride, filtered along r in place.
// The recursion runs over whole rows so memory access stays sequential and the
// inner loops vectorise. scratch: (K+1)*nx doubles.
void IIRRows(
  float* base, int N, std::ptrdiff_t stride, int nx, const AxisSmoother& s, double* scratch)
{
  double* state[K];
  for (int j = 0; j < K; ++j)
  {
    state[j] = scratch + static_cast<std::ptrdiff_t>(j) * nx;
  }
  double* last = scratch + static_cast<std::ptrdiff_t>(K) * nx;
  const float* r0 = base;
  const float* rl = base + (N - 1) * stride;
  for (int i = 0; i < nx; ++i)
  {
    for (int j = 0; j < K; ++j)
    {
      state[j][i] = r0[i];
    }
    last[i] = rl[i];
  }
  for (int r = 0; r < N; ++r)
  {
    CascadeRowStep(base + r * stride, nx, s, state);
  }
  for (int i = 0; i < nx; ++i)
  {
    double st[K];
    for (int j = 0; j < K; ++j)
    {
      st[j] = state[j][i];
    }
    StartBackward(s, last[i], st);
    for (int j = 0; j < K; ++j)
    {
      state[j][i] = st[j];
    }
  }
  for (int r = N - 1; r >= 0; --r)
  {
    CascadeRowStep(base + r * stride, nx, s, state);
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
  auto source = [&](int r)
  { return copy + static_cast<std::ptrdiff_t>(std::min(std::max(r, 0), N - 1)) * nx; };
  for (int r = 0; r < N; ++r)
  {
    float* row = base + r * stride;
    const float* centre = source(r);
    const float w0 = static_cast<float>(s.Taps[0]);
    for (int i = 0; i < nx; ++i)
    {
      row[i] = w0 * centre[i];
    }
    for (int k = 1; k <= R; ++k)
    {
      const float* below = source(r - k);
      const float* above = source(r + k);
      const float w = static_cast<float>(s.Taps[k]);
      for (int i = 0; i < nx; ++i)
      {
        row[i] += w * (below[i] + above[i]);
      }
    }
  }
}

void SmoothX(const float* src, float* dst, const int dims[3], const AxisSmoother& s)
{
  const int nx = dims[0];
  const long long nLines = static_cast<long long>(dims[1]) * dims[2];
  vtkSMPTools::For(0, nLines,
    [&](long long begin, long long end)
    {
      std::vector<double> scratch(2 * nx + 2 * (s.Radius + 1)); // FIRLine's
      for (long long l = begin; l < end; ++l)
      {
        const float* in = src + l * nx;
        float* out = dst + l * nx;
        switch (s.Type)
        {
          case AxisSmoother::IIR:
            IIRLine(in, out, nx, s, scratch.data());
            break;
          case AxisSmoother::FIR:
            FIRLine(in, out, nx, s, scratch.data());
            break;
          default:
            if (in != out)
            {
              std::copy(in, in + nx, out);
            }
        }
      }
    });
}

// count blocks of N rows (nx floats each, `stride` apart; block c at dst + c*outer),
// each filtered along its rows in place.
void SmoothRows(float* dst, const AxisSmoother& s, long long count, int N, std::ptrdiff_t outer,
  std::ptrdiff_t stride, int nx)
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
        dscratch.resize((K + 1) * static_cast<std::size_t>(nx));
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
}
} // namespace

int GaussianAxisReach(double sigmaVoxels)
{
  const AxisSmoother s = MakeSmoother(sigmaVoxels);
  return s.Type == AxisSmoother::IIR ? -1 : s.Type == AxisSmoother::FIR ? s.Radius : 0;
}

void SampledAxisZ(
  const float* src, float* dst, const int dims[3], double sigmaVoxels, int k0, int k1)
{
  const AxisSmoother s = MakeSmoother(sigmaVoxels);
  // The recursive filter reads whole lines, which a window of slices does not hold: its callers
  // (dsSmoothSlabs.cxx) run it in two passes over the whole axis instead.
  assert(s.Type != AxisSmoother::IIR && "SampledAxisZ is the sampled Gaussian's pass only");
  const std::ptrdiff_t slice = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  const int last = dims[2] - 1;
  const auto source = [&](int k) { return src + std::min(std::max(k, 0), last) * slice; };
  vtkSMPTools::For(k0, k1,
    [&](int begin, int end)
    {
      for (int k = begin; k < end; ++k)
      {
        // FIRRows's arithmetic for every line through this slice.
        float* out = dst + (k - k0) * slice;
        const float* centre = source(k);
        if (s.Type != AxisSmoother::FIR) // the axis left alone (sigma below 0.001 voxel)
        {
          std::copy(centre, centre + slice, out);
          continue;
        }
        const float w0 = static_cast<float>(s.Taps[0]);
        for (std::ptrdiff_t i = 0; i < slice; ++i)
        {
          out[i] = w0 * centre[i];
        }
        for (int t = 1; t <= s.Radius; ++t)
        {
          const float* below = source(k - t);
          const float* above = source(k + t);
          const float w = static_cast<float>(s.Taps[t]);
          for (std::ptrdiff_t i = 0; i < slice; ++i)
          {
            out[i] += w * (below[i] + above[i]);
          }
        }
      }
    });
}

void SmoothGaussianAxis(float* volume, const int dims[3], int a, double sigmaVoxels)
{
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  const std::ptrdiff_t slice = static_cast<std::ptrdiff_t>(nx) * ny;
  const AxisSmoother s = MakeSmoother(sigmaVoxels);
  if (a == 0)
  {
    SmoothX(volume, volume, dims, s);
  }
  else if (a == 1)
  {
    SmoothRows(volume, s, nz, ny, slice, nx, nx); // for each k, rows j
  }
  else
  {
    SmoothRows(volume, s, ny, nz, nx, slice, nx); // for each j, rows k
  }
}

//------------------------------------------------------------------------------
struct RecursiveAxisPass::Filter
{
  AxisSmoother S;
};

RecursiveAxisPass::RecursiveAxisPass(float* volume, const int dims[3], int axis, double sigmaVoxels)
  : Coefficients(new Filter{ MakeSmoother(sigmaVoxels) })
  , Volume(volume)
  , Axis(axis)
{
  std::copy(dims, dims + 3, this->Dims);
  this->NumberOfLines = static_cast<long long>(dims[0]) * dims[1] * dims[2] / dims[axis];
  // Axis 0: a start state per line; axes 1, 2: an end state and the last input per line.
  this->Saved.resize(static_cast<std::size_t>(this->NumberOfLines) * (axis == 0 ? K : K + 1));
}

RecursiveAxisPass::~RecursiveAxisPass() = default;

namespace
{
/// slot[p] = r for p = record[r], -1 elsewhere (positions 0..n-1).
std::vector<int> RecordSlots(const std::vector<int>& record, int n)
{
  std::vector<int> slot(n, -1);
  for (std::size_t r = 0; r < record.size(); ++r)
  {
    if (record[r] >= 0 && record[r] < n)
    {
      slot[record[r]] = static_cast<int>(r);
    }
  }
  return slot;
}

/// Line l's state into recorded[slot] (K per line), unless slot is -1.
inline void RecordLine(
  const double* st, int slot, long long l, std::vector<std::vector<double>>& recorded)
{
  if (slot >= 0)
  {
    std::copy(st, st + K, recorded[slot].data() + l * K);
  }
}

/// The geometry of the rows path (SmoothRows): `blocks` blocks of N rows of nx floats, line
/// i + nx * c being column i of block c.
struct RowBlocks
{
  long long Blocks;
  int N, Nx;
  std::ptrdiff_t Outer, Stride;
  RowBlocks(const int dims[3], int axis)
    : Blocks(axis == 1 ? dims[2] : dims[1])
    , N(dims[axis])
    , Nx(dims[0])
    , Outer(axis == 1 ? static_cast<std::ptrdiff_t>(dims[0]) * dims[1] : dims[0])
    , Stride(axis == 1 ? dims[0] : static_cast<std::ptrdiff_t>(dims[0]) * dims[1])
  {
  }
};

/// Copies the rows path's state of block c's columns into `to` (K per line).
void StoreRowStates(double* const state[K], int nx, long long c, double* to, int perLine)
{
  for (int i = 0; i < nx; ++i)
  {
    for (int j = 0; j < K; ++j)
    {
      to[(i + nx * c) * perLine + j] = state[j][i];
    }
  }
}
/// body(c, state) for every block c of the rows path, in parallel, state holding K rows of nx
/// doubles for its columns.
template <typename Body>
void ForEachRowBlock(const RowBlocks& g, Body&& body)
{
  vtkSMPTools::For(0, g.Blocks,
    [&](long long begin, long long end)
    {
      std::vector<double> scratch(K * static_cast<std::size_t>(g.Nx));
      double* state[K];
      for (long long c = begin; c < end; ++c)
      {
        for (int j = 0; j < K; ++j)
        {
          state[j] = scratch.data() + j * static_cast<std::ptrdiff_t>(g.Nx);
        }
        body(c, state);
      }
    });
}

/// body(l, scratch) for every line l of `lines` x lines of n voxels, in parallel, scratch
/// holding n doubles.
template <typename Body>
void ForEachXLine(long long lines, int n, Body&& body)
{
  vtkSMPTools::For(0LL, lines,
    [&](long long begin, long long end)
    {
      std::vector<double> scratch(n);
      for (long long l = begin; l < end; ++l)
      {
        body(l, scratch.data());
      }
    });
}
} // namespace

void RecursiveAxisPass::Forward(
  const double* start, const std::vector<int>& record, std::vector<std::vector<double>>& recorded)
{
  const AxisSmoother& s = this->Coefficients->S;
  const std::vector<int> slot = RecordSlots(record, this->Dims[this->Axis]);
  recorded.assign(record.size(), std::vector<double>(K * this->NumberOfLines));
  if (this->Axis == 0)
  {
    const int n = this->Dims[0];
    ForEachXLine(this->NumberOfLines, n,
      [&](long long l, double*)
      {
        const float* in = this->Volume + l * n;
        double* st = this->Saved.data() + l * K;
        for (int j = 0; j < K; ++j)
        {
          st[j] = start ? start[l * K + j] : static_cast<double>(in[0]);
        }
        double run[K];
        std::copy(st, st + K, run);
        for (int i = 0; i < n; ++i)
        {
          CascadeStep(s, in[i], run);
          RecordLine(run, slot[i], l, recorded);
        }
      });
    return;
  }
  const RowBlocks g(this->Dims, this->Axis);
  ForEachRowBlock(g,
    [&](long long c, double* state[K])
    {
      float* base = this->Volume + c * g.Outer;
      for (int i = 0; i < g.Nx; ++i)
      {
        const long long l = i + g.Nx * c;
        for (int j = 0; j < K; ++j)
        {
          state[j][i] = start ? start[l * K + j] : static_cast<double>(base[i]);
        }
        this->Saved[l * (K + 1) + K] = base[(g.N - 1) * g.Stride + i];
      }
      for (int r = 0; r < g.N; ++r)
      {
        CascadeRowStep(base + r * g.Stride, g.Nx, s, state);
        if (slot[r] >= 0)
        {
          StoreRowStates(state, g.Nx, c, recorded[slot[r]].data(), K);
        }
      }
      StoreRowStates(state, g.Nx, c, this->Saved.data(), K + 1);
    });
}

void RecursiveAxisPass::Backward(
  const double* ahead, const std::vector<int>& record, std::vector<std::vector<double>>& recorded)
{
  const AxisSmoother& s = this->Coefficients->S;
  const std::vector<int> slot = RecordSlots(record, this->Dims[this->Axis]);
  recorded.assign(record.size(), std::vector<double>(K * this->NumberOfLines));
  if (this->Axis == 0)
  {
    const int n = this->Dims[0];
    ForEachXLine(this->NumberOfLines, n,
      [&](long long l, double* w)
      {
        // The forward outputs again, as doubles as IIRLine keeps them.
        float* line = this->Volume + l * n;
        double st[K];
        std::copy(this->Saved.data() + l * K, this->Saved.data() + (l + 1) * K, st);
        for (int i = 0; i < n; ++i)
        {
          w[i] = CascadeStep(s, line[i], st);
        }
        if (ahead)
        {
          std::copy(ahead + l * K, ahead + (l + 1) * K, st);
        }
        else
        {
          StartBackward(s, line[n - 1], st);
        }
        for (int i = n - 1; i >= 0; --i)
        {
          line[i] = static_cast<float>(CascadeStep(s, w[i], st));
          RecordLine(st, slot[i], l, recorded);
        }
      });
    return;
  }
  const RowBlocks g(this->Dims, this->Axis);
  ForEachRowBlock(g,
    [&](long long c, double* state[K])
    {
      for (int i = 0; i < g.Nx; ++i)
      {
        const long long l = i + g.Nx * c;
        double st[K];
        if (ahead)
        {
          std::copy(ahead + l * K, ahead + (l + 1) * K, st);
        }
        else
        {
          const double* saved = this->Saved.data() + l * (K + 1);
          std::copy(saved, saved + K, st);
          StartBackward(s, saved[K], st);
        }
        for (int j = 0; j < K; ++j)
        {
          state[j][i] = st[j];
        }
      }
      float* base = this->Volume + c * g.Outer;
      for (int r = g.N - 1; r >= 0; --r)
      {
        CascadeRowStep(base + r * g.Stride, g.Nx, s, state);
        if (slot[r] >= 0)
        {
          StoreRowStates(state, g.Nx, c, recorded[slot[r]].data(), K);
        }
      }
    });
}

void SmoothGaussianSeparable(
  const float* src, float* dst, const int dims[3], const double sigmaVoxels[3])
{
  // z first: a volume smoothed slab by slab along z (dsSmoothSlabs.h) then runs its x and y
  // passes once, on each slab's final slices, whichever filter z takes (docs/METHOD.md §9.7).
  if (src != dst)
  {
    const std::ptrdiff_t slice = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
    vtkSMPTools::For(0, dims[2],
      [&](int k0, int k1) { std::copy(src + k0 * slice, src + k1 * slice, dst + k0 * slice); });
  }
  SmoothGaussianAxis(dst, dims, 2, sigmaVoxels[2]);
  SmoothX(dst, dst, dims, MakeSmoother(sigmaVoxels[0]));
  SmoothGaussianAxis(dst, dims, 1, sigmaVoxels[1]);
}
} // namespace dsurf
