// SPDX-License-Identifier: BSD-3-Clause
// The locally normalised potential at chosen voxels, computed slab by slab along z
// (LocalPotentialAt, dsScaleSpace.h; docs/METHOD.md §9.7): the sigma_0 probe's potential and the
// tiles of a field in bricks whose G_sigma * f is not held over its box.
#include "dsScaleSpace.h"
#include "dsScaleSpaceKernels.h"

#include "dsGaussianSmoother.h"
#include "dsSmoothSlabs.h"
#include "dsVoxelSet.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

namespace dsurf
{
using namespace scalespace;

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
  // the slices that either Gaussian's pass along z reads (a sampled one's reach on either
  // side), the core's candidates; the recorded states of both passes along z and what a pass
  // along z holds besides while it runs: the state carried between slabs, the states it records
  // and a RecursiveAxisPass's own (21 doubles a line, as SmoothInSlabsBytes).
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
/// read), in any order: along z sampled from the slab's reach of slices, or, recursive, from a
/// RecursiveSlabsZ prepared by a pass up and down the slabs; then along x and y.
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
        [this](int z0, int z1, float* out) { SlicesAsFloat(this->Image, z0, z1, out); }));
      this->Recursive->Prepare();
    }
  }
  void Slab(int s, std::vector<float>& out)
  {
    const int* dims = this->Image.Geometry.Dimensions;
    const std::ptrdiff_t sz = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
    const int f0 = std::max(0, this->Cores[s] - 1), f1 = std::min(dims[2], this->Cores[s + 1] + 1);
    if (this->Recursive)
    {
      this->Recursive->Slab(s, out);
    }
    else
    {
      const int r = std::max(0, GaussianAxisReach(this->Sigma[2]));
      const int w0 = std::max(0, f0 - r), w1 = std::min(dims[2], f1 + r);
      this->Window.resize(static_cast<std::size_t>((w1 - w0) * sz));
      SlicesAsFloat(this->Image, w0, w1, this->Window.data());
      out.resize(static_cast<std::size_t>((f1 - f0) * sz));
      const int wdims[3] = { dims[0], dims[1], w1 - w0 };
      SampledAxisZ(this->Window.data(), out.data(), wdims, this->Sigma[2], f0 - w0, f1 - w0);
    }
    SmoothSlabXY(out.data(), dims[0], dims[1], f1 - f0, this->Sigma);
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
/// each); g of each core is the input of the second Gaussian's RecursiveSlabsZ, which runs up
/// the slabs and then down them, where each slab, smoothed along x and y at 2 sigma, is final
/// and scanned.
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
  };
  RecursiveSlabsZ wideZ(dims, 2 * sv[2], cores, 0, wideInput);
  wideZ.Prepare(
    [&](int s, std::vector<float>& wide)
    {
      assert(made == s); // the pass made this slab's G_2sigma * g just now, from `smooth`
      const int z0 = cores[s], z1 = cores[s + 1], f0 = std::max(0, z0 - 1);
      SmoothSlabXY(wide.data(), dims[0], dims[1], z1 - z0, wideXY);
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
} // namespace dsurf
