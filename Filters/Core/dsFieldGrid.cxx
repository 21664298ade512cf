// SPDX-License-Identifier: BSD-3-Clause
#include "dsFieldGrid.h"

#include "dsFieldBricks.h"
#include "dsSmoothSlabs.h"

#include "dsThreads.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dsurf
{
int DecimationFactor(double sigma, const ImageGeometry& geometry)
{
  double samples = std::numeric_limits<double>::max();
  for (int a = 0; a < 3; ++a)
  {
    samples = std::min(samples, sigma / (SamplesPerSigma * geometry.Spacing[a]));
  }
  // In double first: an unvalidated sigma (huge, infinite or NaN) must not reach the cast.
  const double largest =
    std::max({ geometry.Dimensions[0], geometry.Dimensions[1], geometry.Dimensions[2], 1 });
  if (!(samples < largest))
  {
    samples = largest;
  }
  int f = std::max(1, static_cast<int>(std::floor(samples)));
  f -= 1 - f % 2; // odd: blocks centred on voxels (BlockMeans)
  // Keep at least two coarse voxels along every axis (a 3-D image for the scale space).
  for (int a = 0; a < 3; ++a)
  {
    while (f > 1 && (geometry.Dimensions[a] - 1) / f + 1 < 2)
    {
      f -= 2;
    }
  }
  return f;
}

AxisBlocks::AxisBlocks(int n, int f)
  : Voxels(n)
  , Factor(f)
  , Count((n - 1) / f + 1)
  , First((n - 1 - ((n - 1) / f) * f) / 2)
{
}

void AxisBlocks::Range(int I, int& begin, int& end) const
{
  const int h = this->Factor / 2;
  begin = I == 0 ? 0 : this->First + I * this->Factor - h;
  end = I == this->Count - 1 ? this->Voxels : this->First + I * this->Factor + h + 1;
}

namespace
{
/// Adds each voxel of one row of the image to its block's sum along x, voxel by voxel in the
/// row's order within each block (so every block's sum is the same double as a plain loop over
/// its voxels gives). The blocks between the two end blocks all hold f voxels: they are added
/// a voxel of every block at a time, so that their sums form independent chains of additions.
template <typename T>
void AddRowToBlocks(const T* line, const AxisBlocks& blocks, double* sum)
{
  const int f = blocks.Factor, m = blocks.Count;
  for (int I = 0; I < m; I += std::max(1, m - 1)) // the end blocks
  {
    int b, e;
    blocks.Range(I, b, e);
    for (int i = b; i < e; ++i)
    {
      sum[I] += AsFloat(line[i]);
    }
  }
  if (m <= 2)
  {
    return;
  }
  const T* first = line + blocks.First + f - f / 2; // block 1's first voxel
  for (int t = 0; t < f; ++t)
  {
    for (int I = 1; I < m - 1; ++I)
    {
      sum[I] += AsFloat(first[(I - 1) * f + t]);
    }
  }
}
} // namespace

void BlockMeans(const ImageView& image, int f, std::vector<float>& coarse,
  ImageGeometry& coarseGeometry, int numberOfThreads)
{
  const ImageGeometry& geometry = image.Geometry;
  // Blocks centred on voxels (AxisBlocks): the coarse grid is the image's, only sparser.
  const int* n = geometry.Dimensions;
  const AxisBlocks blocks[3] = { AxisBlocks(n[0], f), AxisBlocks(n[1], f), AxisBlocks(n[2], f) };
  int m[3];
  double firstIndex[3];
  for (int a = 0; a < 3; ++a)
  {
    m[a] = blocks[a].Count;
    firstIndex[a] = blocks[a].First;
    coarseGeometry.Dimensions[a] = m[a];
    coarseGeometry.Spacing[a] = f * geometry.Spacing[a];
  }
  geometry.IndexToWorld(firstIndex, coarseGeometry.Origin);
  std::copy(geometry.Direction, geometry.Direction + 9, coarseGeometry.Direction);

  coarse.assign(static_cast<std::size_t>(m[0]) * m[1] * m[2], 0.0f);
  std::vector<int> width(m[0]); // voxels of each block along x
  for (int I = 0; I < m[0]; ++I)
  {
    int b, e;
    blocks[0].Range(I, b, e);
    width[I] = e - b;
  }
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ ResolveThreads(numberOfThreads), "STDThread", false },
    [&]
    {
      VisitValues(image,
        [&](const auto* values)
        {
          vtkSMPTools::For(0, m[2],
            [&](int kBegin, int kEnd)
            {
              std::vector<double> sum(m[0]);
              for (int K = kBegin; K < kEnd; ++K)
              {
                int k0, k1;
                blocks[2].Range(K, k0, k1);
                for (int J = 0; J < m[1]; ++J)
                {
                  int j0, j1;
                  blocks[1].Range(J, j0, j1);
                  std::fill(sum.begin(), sum.end(), 0.0);
                  for (int k = k0; k < k1; ++k)
                  {
                    for (int j = j0; j < j1; ++j)
                    {
                      AddRowToBlocks(values + image.RowOffset(j, k), blocks[0], sum.data());
                    }
                  }
                  const int rows = (k1 - k0) * (j1 - j0);
                  float* out = coarse.data() + (static_cast<std::size_t>(K) * m[1] + J) * m[0];
                  for (int I = 0; I < m[0]; ++I)
                  {
                    out[I] = static_cast<float>(sum[I] / (rows * width[I]));
                  }
                }
              }
            });
        });
    });
}

double RemainingSigma(double sigma, const ImageGeometry& geometry, int f)
{
  const double spacing =
    std::max({ geometry.Spacing[0], geometry.Spacing[1], geometry.Spacing[2] });
  const double boxVariance = (static_cast<double>(f) * f - 1.0) / 12.0 * spacing * spacing;
  return std::sqrt(std::max(0.0, sigma * sigma - boxVariance));
}

VoxelBox FieldCut(const VoxelBox& box, const ImageGeometry& whole, double sigma)
{
  const bool ownGrid = DecimationFactor(sigma, whole) <= 1;
  return ownGrid || 2 * box.NumberOfVoxels() <= whole.NumberOfVoxels() ? box
                                                                       : VoxelBox::Whole(whole);
}

double FieldReach(EdgeNormalization normalization, double sigma)
{
  return (normalization == EdgeNormalization::Local ? NeighbourhoodSigmasLocal
                                                    : NeighbourhoodSigmas) *
    sigma;
}

VoxelBox SurfaceNeighbourhood(const TriangleMesh& mesh, const ImageGeometry& geometry, double reach)
{
  double lo[3] = { std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
    std::numeric_limits<double>::max() };
  double hi[3] = { -lo[0], -lo[1], -lo[2] };
  for (const Vec3& p : mesh.Points)
  {
    double ijk[3];
    geometry.WorldToIndex(p.data(), ijk);
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], ijk[a]);
      hi[a] = std::max(hi[a], ijk[a]);
    }
  }
  VoxelBox box = VoxelBox::Whole(geometry);
  for (int a = 0; a < 3; ++a)
  {
    const double grow = reach / geometry.Spacing[a] + 1.0;
    if (lo[a] <= hi[a]) // an empty mesh keeps the whole image
    {
      // Clamped to the image in double before the cast: a start far outside it (sigma_0's probe
      // sees every start) has indices beyond int.
      const double n = geometry.Dimensions[a];
      box.Begin[a] = static_cast<int>(std::min(n, std::max(0.0, std::floor(lo[a] - grow))));
      box.End[a] = static_cast<int>(std::max(0.0, std::min(n, std::ceil(hi[a] + grow) + 1.0)));
      // at least two voxels, for a 3-D image
      box.Begin[a] = std::min(box.Begin[a], geometry.Dimensions[a] - 2);
      box.End[a] = std::max(box.End[a], box.Begin[a] + 2);
    }
  }
  return box;
}

int FieldCutFactor(const VoxelBox& box, const ImageGeometry& whole, double sigma, VoxelBox& cut)
{
  cut = FieldCut(box, whole, sigma);
  ImageGeometry g = whole;
  for (int a = 0; a < 3; ++a)
  {
    g.Dimensions[a] = cut.End[a] - cut.Begin[a];
  }
  return DecimationFactor(sigma, g);
}

double FieldGridVoxels(const VoxelBox& cut, int f)
{
  if (f <= 1)
  {
    return static_cast<double>(cut.NumberOfVoxels());
  }
  double coarse = 1;
  for (int a = 0; a < 3; ++a)
  {
    coarse *= (cut.End[a] - cut.Begin[a]) / f + 1;
  }
  return coarse;
}

bool FieldInBricks(
  const VoxelBox& box, const ImageGeometry& whole, const ScaleSpaceParameters& parameters)
{
  VoxelBox cut;
  return FieldCutFactor(box, whole, parameters.Sigma, cut) <= 1;
}

double FieldBytesPerVoxel(bool bricked)
{
  const double shared = std::pow((FieldBricks::BrickSize + 1.0) / FieldBricks::BrickSize, 3);
  return (bricked ? shared : 1.0) * ForceFieldBytesPerVoxel + sizeof(float);
}

bool FieldInSlabs(const VoxelBox& cut, const ImageGeometry& whole)
{
  return static_cast<double>(cut.NumberOfVoxels()) >
    SlabSmoothingShare * static_cast<double>(whole.NumberOfVoxels());
}

double FieldBytes(const VoxelBox& box, const ImageGeometry& whole,
  const ScaleSpaceParameters& parameters, const TriangleMesh* surface)
{
  VoxelBox cut;
  const int f = FieldCutFactor(box, whole, parameters.Sigma, cut);
  const bool bricked = f <= 1 && FieldInBricks(box, whole, parameters);
  const bool inSlabs = bricked && FieldInSlabs(cut, whole);
  const bool local = LocallyNormalised(parameters);
  // (A geometry the scale space refuses is refused when the field is made: counted plainly.)
  if (bricked && surface && ScaleSpaceProblem(whole, parameters.Sigma).empty())
  {
    // The field's first bricks and G_sigma * f (the locally normalised P's tiles, made in slabs
    // or in one pass: ComputeBrickedForce); Cover checks the bricks added later.
    return FieldBricks::InitialBytes(BoxGeometry(whole, cut), parameters,
      BrickReachSigmas * parameters.Sigma, *surface, inSlabs || local,
      local && !inSlabs ? FieldBricks::LocalOnePass : 0);
  }
  const double slabs =
    inSlabs ? SmoothInSlabsBytes(BoxGeometry(whole, cut), parameters.Sigma, 0) : 0.0;
  return FieldGridVoxels(cut, f) * FieldBytesPerVoxel(bricked) + slabs;
}

bool ComputeBrickedForce(const ImageView& part, const ScaleSpaceParameters& parameters,
  const TriangleMesh& surface, ForceField& out, std::string* error, bool inSlabs, bool checkAsAdded,
  const SlabSource& source)
{
  auto bricks = std::make_shared<FieldBricks>();
  const double reach = BrickReachSigmas * parameters.Sigma;
  // The locally normalised P is kept at the tiles' voxels only, whatever the box: computed in
  // slabs over a box of more than half the image, in one pass over a smaller one, as G_sigma * f
  // is smoothed (docs/METHOD.md §9.7).
  const bool local = LocallyNormalised(parameters);
  if (!(inSlabs || local ? bricks->InitializeInSlabs(part, parameters, reach, surface,
                             local && !inSlabs ? FieldBricks::LocalOnePass : 0, error, source)
                         : bricks->Initialize(part, parameters, reach, error)))
  {
    return false;
  }
  if (checkAsAdded)
  {
    bricks->CheckMemoryAsAdded();
  }
  bricks->Cover(surface);
  if (!bricks->Shortfall().empty())
  {
    if (error)
    {
      *error = bricks->Shortfall();
    }
    return false;
  }
  if (!bricks->Finite())
  {
    if (error)
    {
      *error = "the force field is not finite: sigma (" + std::to_string(parameters.Sigma) +
        ") or the weights are too large";
    }
    return false;
  }
  out.Geometry = part.Geometry;
  out.Sigma = parameters.Sigma;
  out.Bricks = std::move(bricks);
  return true;
}

bool ComputeForceAtScale(const ImageView& image, const VoxelBox& box,
  const ScaleSpaceParameters& parameters, ForceField& out, std::string* error,
  const TriangleMesh* surface)
{
  // The last level's field is released first (docs/METHOD.md §9.6), and on the image's own grid
  // the field covers its box only (FieldCut): the whole image only when the surface's
  // neighbourhood spans it.
  out = ForceField();
  // Checked on the image itself, so that a sigma too large is named as the user gave it.
  const std::string problem =
    image.Data ? ScaleSpaceProblem(image.Geometry, parameters.Sigma) : "no data";
  if (!problem.empty())
  {
    if (error)
    {
      *error = problem;
    }
    return false;
  }
  VoxelBox part;
  const int f = FieldCutFactor(box, image.Geometry, parameters.Sigma, part);
  const ImageView cut =
    part.NumberOfVoxels() < image.Geometry.NumberOfVoxels() ? image.Box(part) : image;
  if (f <= 1)
  {
    const bool inSlabs = FieldInSlabs(part, image.Geometry);
    const bool ok = surface
      ? ComputeBrickedForce(cut, parameters, *surface, out, error, inSlabs, true)
      : ComputeScaleSpaceForce(cut, parameters, out, error);
    out.Image = image.Geometry;
    return ok;
  }
  std::vector<float> coarse;
  ImageGeometry coarseGeometry;
  BlockMeans(cut, f, coarse, coarseGeometry, parameters.NumberOfThreads);
  ScaleSpaceParameters remaining = parameters;
  remaining.Sigma = RemainingSigma(parameters.Sigma, cut.Geometry, f);
  if (!ComputeScaleSpaceForce(coarse.data(), coarseGeometry, remaining, out, error))
  {
    return false;
  }
  out.Sigma = parameters.Sigma;
  out.Image = image.Geometry;
  return true;
}
} // namespace dsurf
