// SPDX-License-Identifier: BSD-3-Clause
#include "dsFieldBricks.h"

#include "dsMemory.h"
#include "dsSmoothSlabs.h"
#include "dsThreads.h"
#include "dsVoxelSet.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <sstream>

namespace dsurf
{
namespace
{
/// A row of a tile into a brick's neighbourhood: the brick's own BrickSize values, or the one or
/// two values of a neighbouring tile, without a call to memmove (most rows are one of these, and
/// a call per row was the largest cost of a field kept in tiles).
inline void CopyRow(const float* from, int n, float* to)
{
  assert(n > 0);
  if (n == FieldBricks::BrickSize)
  {
    std::memcpy(to, from, sizeof(float) * FieldBricks::BrickSize);
  }
  else if (n <= 2)
  {
    to[0] = from[0];
    if (n == 2)
    {
      to[1] = from[1];
    }
  }
  else
  {
    std::copy(from, from + n, to);
  }
}

/// Marks every brick within `grow` bricks along axis `a` of a marked one (bricks: the grid's
/// bricks along each axis, x fastest), by a running count along each line of bricks.
void GrowMarks(std::vector<char>& mark, const int bricks[3], int a, int grow)
{
  const std::ptrdiff_t step[3] = { 1, bricks[0],
    static_cast<std::ptrdiff_t>(bricks[0]) * bricks[1] };
  const int n = bricks[a];
  const int u = a == 0 ? 1 : 0, v = a == 2 ? 1 : 2; // the other two axes
  std::vector<int> before(n + 1);
  for (int q = 0; q < bricks[v]; ++q)
    for (int p = 0; p < bricks[u]; ++p)
    {
      char* line = mark.data() + p * step[u] + q * step[v];
      for (int i = 0; i < n; ++i)
      {
        before[i + 1] = before[i] + (line[i * step[a]] ? 1 : 0);
      }
      for (int i = 0; i < n; ++i)
      {
        line[i * step[a]] = before[std::min(n, i + grow + 1)] > before[std::max(0, i - grow)];
      }
    }
}
} // namespace

bool FieldBricks::Initialize(
  const ImageView& image, const ScaleSpaceParameters& parameters, double reach, std::string* error)
{
  this->Reset(image.Geometry, parameters, reach);
  this->Smooth.reset(new float[static_cast<std::size_t>(image.Geometry.NumberOfVoxels())]);
  if (!SmoothForPotential(image, parameters, this->Smooth.get(), this->Gains, error))
  {
    this->Smooth.reset();
    return false;
  }
  return true;
}

bool FieldBricks::InitializeInSlabs(const ImageView& image, const ScaleSpaceParameters& parameters,
  double reach, const TriangleMesh& surface, int coreSlices, std::string* error,
  const SlabSource& source)
{
  // A piece's part of a distributed image smooths in slabs from the states of the other pieces
  // (`source`), not through its Smooth hook, which runs over a volume held whole.
  // Nor is a piece's maximum taken with the local normalisation here (dsPieceField.h refuses it).
  if (parameters.Smooth || (parameters.GradientMaximum && LocallyNormalised(parameters)))
  {
    if (error)
    {
      *error = parameters.Smooth
        ? "a piece's field is smoothed in slabs from its source, not its Smooth hook"
        : "a piece's locally normalised field is not made in slabs";
    }
    return false;
  }
  this->Reset(image.Geometry, parameters, reach);
  this->Source = image;
  this->Slabs = source;
  this->FirstMaximum = parameters.GradientMaximum;
  this->SlabCore = coreSlices;
  this->Tiles.assign(this->Slots.size(), std::vector<float>());
  // The tiles the bricks within reach read (a brick's values read its neighbours' voxels: one
  // brick more), and as far again, so that Cover computes bricks for a surface that moved up to
  // a reach before the tiles are smoothed again (a pass over the box).
  this->TileMargin = reach;
  std::vector<char> keep;
  this->MarkNearSurface(surface, reach + this->TileMargin, keep);
  return this->FillTiles(keep, error);
}

void FieldBricks::SetBox(
  const ImageGeometry& grid, const ScaleSpaceParameters& parameters, double reach)
{
  this->Grid = grid;
  this->Parameters = parameters;
  // A piece's hooks (dsPieceField.h) capture its caller's locals and are used here only:
  // the bricks computed later must not reach them.
  this->Parameters.Smooth = nullptr;
  this->Parameters.GradientMaximum = nullptr;
  this->Reach = reach;
  // Brick b along an axis holds the cells whose lower corner is b * BrickSize ... + BrickSize - 1.
  for (int a = 0; a < 3; ++a)
  {
    this->Bricks[a] = (this->Grid.Dimensions[a] - 2) / BrickSize + 1;
  }
}

std::size_t FieldBricks::BrickCount() const
{
  return static_cast<std::size_t>(this->Bricks[0]) * this->Bricks[1] * this->Bricks[2];
}

void FieldBricks::Reset(
  const ImageGeometry& grid, const ScaleSpaceParameters& parameters, double reach)
{
  this->SetBox(grid, parameters, reach);
  this->Potential.clear();
  this->Force.clear();
  this->BrickFinite.clear();
  this->FreeSlots.clear();
  this->MissCount = 0;
  this->Smooth.reset();
  this->Source = ImageView();
  this->Slabs = nullptr;
  this->FirstMaximum = nullptr;
  this->Tiles.clear();
  this->Smoothings = 0;
  this->CheckGrowth = false;
  this->Available = -1.0;
  this->ShortfallMessage.clear();
  this->Slots.assign(this->BrickCount(), -1);
}

VoxelBox FieldBricks::TileBox(const int b[3]) const
{
  VoxelBox box;
  for (int a = 0; a < 3; ++a)
  {
    box.Begin[a] = b[a] * BrickSize;
    box.End[a] = b[a] + 1 < this->Bricks[a] ? box.Begin[a] + BrickSize : this->Grid.Dimensions[a];
  }
  return box;
}

bool FieldBricks::SmoothTiles(const std::vector<char>& keep, std::string* error)
{
  for (std::size_t id = 0; id < keep.size(); ++id)
  {
    std::vector<float>().swap(this->Tiles[id]);
  }
  // The kept bricks of each layer along z, so that a slab visits only the ones it holds.
  std::vector<std::vector<int>> layers(this->Bricks[2]);
  for (std::size_t id = 0; id < keep.size(); ++id)
  {
    if (keep[id])
    {
      layers[id / (static_cast<std::size_t>(this->Bricks[0]) * this->Bricks[1])].push_back(
        static_cast<int>(id));
    }
  }
  const std::ptrdiff_t nx = this->Grid.Dimensions[0];
  const std::ptrdiff_t slice = nx * this->Grid.Dimensions[1];
  const auto store = [&](const SmoothSlab& slab)
  {
    const int lastLayer = this->Bricks[2] - 1;
    for (int z = std::min(lastLayer, slab.Core0 / BrickSize);
         z <= std::min(lastLayer, (slab.Core1 - 1) / BrickSize); ++z)
    {
      const std::vector<int>& ids = layers[z];
      vtkSMPTools::For(0, static_cast<int>(ids.size()),
        [&](int begin, int end)
        {
          for (int t = begin; t < end; ++t)
          {
            const int id = ids[t];
            const int b[3] = { id % this->Bricks[0], (id / this->Bricks[0]) % this->Bricks[1], z };
            const VoxelBox tile = this->TileBox(b);
            std::vector<float>& values = this->Tiles[id];
            values.resize(static_cast<std::size_t>(tile.NumberOfVoxels()));
            const std::ptrdiff_t tx = tile.End[0] - tile.Begin[0];
            const std::ptrdiff_t ty = tile.End[1] - tile.Begin[1];
            for (int k = std::max(tile.Begin[2], slab.Core0); k < std::min(tile.End[2], slab.Core1);
                 ++k)
              for (int j = tile.Begin[1]; j < tile.End[1]; ++j)
              {
                const float* from = slab.Values + (k - slab.First) * slice + j * nx + tile.Begin[0];
                CopyRow(from, static_cast<int>(tx),
                  values.data() + (j - tile.Begin[1]) * tx + (k - tile.Begin[2]) * tx * ty);
              }
          }
        });
    }
  };
  // A piece's maximum is reduced over every process once, by the first smoothing (the hook
  // then goes: it holds its caller's locals); the gains found then are kept, and equal those of
  // the smoothings after it on a whole image, which therefore gather no edge statistics.
  ScaleSpaceParameters parameters = this->Parameters;
  parameters.GradientMaximum = this->FirstMaximum;
  this->FirstMaximum = nullptr;
  const bool first = this->Smoothings++ == 0;
  // store runs in the SMP scope SmoothForPotentialInSlabs sets (the parameters' threads).
  return SmoothForPotentialInSlabs(
    this->Source, parameters, this->SlabCore, store, this->Gains, error, this->Slabs, first);
}

VoxelSet FieldBricks::TileVoxels(const std::vector<char>& keep, std::vector<int>& kept) const
{
  VoxelSet voxels(this->Grid.NumberOfVoxels());
  kept.clear();
  for (std::size_t id = 0; id < keep.size(); ++id)
  {
    if (keep[id])
    {
      kept.push_back(static_cast<int>(id));
      this->ForEachTileRow(static_cast<int>(id),
        [&](std::ptrdiff_t v, std::ptrdiff_t n, std::ptrdiff_t)
        {
          for (std::ptrdiff_t i = 0; i < n; ++i)
          {
            voxels.Insert(v + i);
          }
        });
    }
  }
  voxels.Finish();
  return voxels;
}

bool FieldBricks::LocalPotentialOfBox(
  const VoxelSet& wanted, std::vector<float>& potential, std::string* error) const
{
  // Both maxima over the box, as ComputeScaleSpaceForce takes them.
  ScaleSpaceParameters local = this->Parameters;
  local.ComputeForce = false;
  for (int a = 0; a < 3; ++a)
  {
    local.MaximumBegin[a] = 0;
    local.MaximumEnd[a] = this->Grid.Dimensions[a];
  }
  if (this->SlabCore != LocalOnePass)
  {
    return LocalPotentialAt(this->Source, local, wanted, potential, error, this->SlabCore);
  }
  // One pass over the whole box (at most half the image), read at the wanted voxels.
  ForceField whole;
  if (!ComputeScaleSpaceForce(this->Source, local, whole, error))
  {
    return false;
  }
  potential.resize(static_cast<std::size_t>(wanted.Size()));
  wanted.ForEachIn(0, this->Grid.NumberOfVoxels(),
    [&](long long v, long long rank) { potential[rank] = whole.Potential[v]; });
  return true;
}

bool FieldBricks::LocalTiles(const std::vector<char>& keep, std::string* error)
{
  for (std::size_t id = 0; id < keep.size(); ++id)
  {
    std::vector<float>().swap(this->Tiles[id]);
  }
  std::vector<int> kept;
  const VoxelSet wanted = this->TileVoxels(keep, kept);
  std::vector<float> potential;
  ++this->Smoothings;
  if (!this->LocalPotentialOfBox(wanted, potential, error))
  {
    return false;
  }
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ ResolveThreads(this->Parameters.NumberOfThreads), "STDThread", false },
    [&]
    {
      vtkSMPTools::For(0, static_cast<int>(kept.size()),
        [&](int begin, int end)
        {
          for (int t = begin; t < end; ++t)
          {
            std::vector<float>& values = this->Tiles[kept[t]];
            const int b[3] = { kept[t] % this->Bricks[0],
              (kept[t] / this->Bricks[0]) % this->Bricks[1],
              kept[t] / (this->Bricks[0] * this->Bricks[1]) };
            values.resize(static_cast<std::size_t>(this->TileBox(b).NumberOfVoxels()));
            this->ForEachTileRow(kept[t],
              [&](std::ptrdiff_t v, std::ptrdiff_t n, std::ptrdiff_t at)
              {
                // A row's voxels are all wanted: consecutive ranks.
                std::copy_n(potential.data() + wanted.Rank(v), n, values.data() + at);
              });
          }
        });
    });
  return true;
}

void FieldBricks::MarkNear(
  const std::vector<Vec3>& points, double reach, int grow, std::vector<char>& mark) const
{
  mark.assign(this->BrickCount(), 0);
  for (const Vec3& p : points)
  {
    double ijk[3];
    this->Grid.WorldToIndex(p.data(), ijk);
    int lo[3], hi[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a)
    {
      const double r = reach / this->Grid.Spacing[a] + 1.0;
      const double last = this->Grid.Dimensions[a] - 2;
      const double from = std::max(0.0, std::floor(ijk[a] - r));
      const double to = std::min(last, std::floor(ijk[a] + r));
      inside = inside && from <= to; // also false for NaN
      lo[a] = inside ? std::max(0, static_cast<int>(from) / BrickSize - grow) : 0;
      hi[a] = inside ? std::min(this->Bricks[a] - 1, static_cast<int>(to) / BrickSize + grow) : -1;
    }
    for (int k = lo[2]; inside && k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          mark[(static_cast<std::size_t>(k) * this->Bricks[1] + j) * this->Bricks[0] + i] = 1;
        }
  }
}

void FieldBricks::MarkNearSurface(
  const TriangleMesh& mesh, double reach, std::vector<char>& mark) const
{
  // The bricks holding a point of the surface (its vertices, and on every triangle a grid of
  // spacing at most h along its edges, so every point of the triangle lies within h of one: a
  // coarse start's vertices lie far apart, a sphere of radius 219 voxels with 48 x 48 vertices
  // 29 voxels, and its refined surface between them), then grown along each axis by the bricks
  // reach + h and a voxel span, and one more: a superset of MarkNear's bricks for those points,
  // in time that grows with the bricks, not with the points times the reach's volume.
  const double h = 0.5 * BrickSize *
    std::min({ this->Grid.Spacing[0], this->Grid.Spacing[1], this->Grid.Spacing[2] });
  const double r = reach + h;
  mark.assign(this->BrickCount(), 0);
  const auto markPoint = [&](const Vec3& p)
  {
    double ijk[3];
    this->Grid.WorldToIndex(p.data(), ijk);
    int b[3];
    for (int a = 0; a < 3; ++a)
    {
      const double last = this->Grid.Dimensions[a] - 2;
      const double within = r / this->Grid.Spacing[a] + 1.0;
      if (!(ijk[a] >= -within && ijk[a] <= last + within)) // also false for NaN
      {
        return;
      }
      b[a] = static_cast<int>(std::min(last, std::max(0.0, std::floor(ijk[a])))) / BrickSize;
    }
    mark[(static_cast<std::size_t>(b[2]) * this->Bricks[1] + b[1]) * this->Bricks[0] + b[0]] = 1;
  };
  for (const Vec3& p : mesh.Points)
  {
    markPoint(p);
  }
  for (const auto& t : mesh.Triangles)
  {
    const Vec3 &a = mesh.Points[t[0]], &b = mesh.Points[t[1]], &c = mesh.Points[t[2]];
    const double longest = std::max({ Norm(b - a), Norm(c - b), Norm(a - c) });
    if (!std::isfinite(longest))
    {
      continue; // its points mark nothing (markPoint)
    }
    const int n = static_cast<int>(std::min(1e4, std::ceil(longest / h)));
    for (int i = 0; n > 1 && i <= n; ++i)
      for (int j = 0; j <= n - i; ++j)
      {
        markPoint(
          a + (static_cast<double>(i) / n) * (b - a) + (static_cast<double>(j) / n) * (c - a));
      }
  }
  for (int a = 0; a < 3; ++a)
  {
    const int grow = static_cast<int>(std::ceil((r / this->Grid.Spacing[a] + 1.0) / BrickSize)) + 1;
    GrowMarks(mark, this->Bricks, a, grow);
  }
}

bool FieldBricks::EnsureTiles(const TriangleMesh& mesh, const std::vector<int>& fresh)
{
  if (this->Smooth || fresh.empty())
  {
    return true;
  }
  bool held = true;
  for (std::size_t f = 0; held && f < fresh.size(); ++f)
  {
    const int id = fresh[f];
    const int b[3] = { id % this->Bricks[0], (id / this->Bricks[0]) % this->Bricks[1],
      id / (this->Bricks[0] * this->Bricks[1]) };
    for (int k = std::max(0, b[2] - 1); held && k <= std::min(this->Bricks[2] - 1, b[2] + 1); ++k)
      for (int j = std::max(0, b[1] - 1); held && j <= std::min(this->Bricks[1] - 1, b[1] + 1); ++j)
        for (int i = std::max(0, b[0] - 1); held && i <= std::min(this->Bricks[0] - 1, b[0] + 1);
             ++i)
        {
          held =
            !this->Tiles[(static_cast<std::size_t>(k) * this->Bricks[1] + j) * this->Bricks[0] + i]
               .empty();
        }
  }
  if (held)
  {
    return true;
  }
  // The surface went past the tiles kept: smoothed again, the margin doubled, so that a surface
  // growing across the box (a click's seed) smooths it a logarithmic number of times.
  this->TileMargin *= 2.0;
  std::vector<char> keep;
  this->MarkNearSurface(mesh, this->Reach + this->TileMargin, keep);
  // The tiles held now are freed first; counted as if not, to be safe.
  const double tiles = static_cast<double>(std::count(keep.begin(), keep.end(), char(1)));
  const double more =
    tiles * TileBytes + TileMakingBytes(this->Grid, this->Parameters, tiles, this->SlabCore);
  if (!this->Affords(more, "the force field's smoothed image near the surface, smoothed again"))
  {
    return false;
  }
  return this->FillTiles(keep, nullptr);
}

double FieldBricks::TileMakingBytes(
  const ImageGeometry& grid, const ScaleSpaceParameters& parameters, double tiles, int coreSlices)
{
  if (LocallyNormalised(parameters) && coreSlices == LocalOnePass)
  {
    // P over the box and its scratch (ComputeScaleSpaceForce without the force), the set of the
    // tiles' voxels (a quarter of a byte a voxel of the box) and P at them.
    return (3.0 * sizeof(float) + 0.25) * static_cast<double>(grid.NumberOfVoxels()) +
      sizeof(float) * tiles * BrickSize * BrickSize * BrickSize;
  }
  if (LocallyNormalised(parameters))
  {
    return LocalPotentialBytes(
      grid, parameters, tiles * BrickSize * BrickSize * BrickSize, coreSlices);
  }
  return SmoothInSlabsBytes(grid, parameters.Sigma, coreSlices);
}

bool FieldBricks::Affords(double bytes, const char* what)
{
  if (!this->CheckGrowth)
  {
    return true;
  }
  std::ostringstream text;
  text.precision(3);
  text << what << " at sigma " << this->Parameters.Sigma << " (world units)";
  this->ShortfallMessage = MemoryShortfall(bytes, text.str(), this->Available);
  if (this->ShortfallMessage.empty() && this->Available >= 0.0)
  {
    this->Available -= bytes; // a given budget is used up (the machine's is read each time)
  }
  return this->ShortfallMessage.empty();
}

double FieldBricks::InitialBytes(const ImageGeometry& grid, const ScaleSpaceParameters& parameters,
  double reach, const TriangleMesh& surface, bool inSlabs, int coreSlices)
{
  FieldBricks counter;
  counter.SetBox(grid, parameters, reach);
  std::vector<char> mark;
  counter.MarkNear(surface.Points, reach, 0, mark);
  // The bricks near the surface, and the bookkeeping of every brick of the box (its slot, its
  // tile's vector, the marks of Cover).
  double bytes = static_cast<double>(std::count(mark.begin(), mark.end(), char(1))) * BrickBytes +
    static_cast<double>(mark.size()) * (sizeof(int) + sizeof(std::vector<float>) + 2);
  if (!inSlabs)
  {
    return bytes + sizeof(float) * static_cast<double>(grid.NumberOfVoxels());
  }
  // InitializeInSlabs's tiles, and the slabs while they are smoothed.
  counter.MarkNearSurface(surface, 2.0 * reach, mark);
  const double tiles = static_cast<double>(std::count(mark.begin(), mark.end(), char(1)));
  return bytes + tiles * TileBytes + TileMakingBytes(grid, parameters, tiles, coreSlices);
}

const float* FieldBricks::SmoothAround(
  const int b[3], std::vector<float>& values, VoxelBox& over) const
{
  if (this->Smooth)
  {
    over = VoxelBox::Whole(this->Grid);
    return this->Smooth.get();
  }
  const VoxelBox box = this->BrickBox(b);
  for (int a = 0; a < 3; ++a)
  {
    over.Begin[a] = std::max(0, box.Begin[a] - 1);
    over.End[a] = std::min(this->Grid.Dimensions[a], box.End[a] + 1);
  }
  const std::ptrdiff_t ox = over.End[0] - over.Begin[0], oy = over.End[1] - over.Begin[1];
  // Every value is a tile's (the tiles cover the grid): the buffer, reused by the thread's
  // bricks, is not cleared.
  values.resize(static_cast<std::size_t>(over.NumberOfVoxels()));
  for (int tk = std::max(0, b[2] - 1); tk <= std::min(this->Bricks[2] - 1, b[2] + 1); ++tk)
    for (int tj = std::max(0, b[1] - 1); tj <= std::min(this->Bricks[1] - 1, b[1] + 1); ++tj)
      for (int ti = std::max(0, b[0] - 1); ti <= std::min(this->Bricks[0] - 1, b[0] + 1); ++ti)
      {
        const int t[3] = { ti, tj, tk };
        const std::vector<float>& tile =
          this->Tiles[(static_cast<std::size_t>(tk) * this->Bricks[1] + tj) * this->Bricks[0] + ti];
        assert(!tile.empty()); // EnsureTiles smooths again before a brick reads a tile not held
        const VoxelBox tb = this->TileBox(t);
        const std::ptrdiff_t tx = tb.End[0] - tb.Begin[0], ty = tb.End[1] - tb.Begin[1];
        const int i0 = std::max(tb.Begin[0], over.Begin[0]), i1 = std::min(tb.End[0], over.End[0]);
        for (int k = std::max(tb.Begin[2], over.Begin[2]);
             !tile.empty() && k < std::min(tb.End[2], over.End[2]); ++k)
          for (int j = std::max(tb.Begin[1], over.Begin[1]); j < std::min(tb.End[1], over.End[1]);
               ++j)
          {
            const float* from = tile.data() + (i0 - tb.Begin[0]) + (j - tb.Begin[1]) * tx +
              (k - tb.Begin[2]) * tx * ty;
            CopyRow(from, i1 - i0,
              values.data() + (i0 - over.Begin[0]) + (j - over.Begin[1]) * ox +
                (k - over.Begin[2]) * ox * oy);
          }
      }
  return values.data();
}

VoxelBox FieldBricks::BrickBox(const int b[3]) const
{
  VoxelBox box;
  for (int a = 0; a < 3; ++a)
  {
    box.Begin[a] = b[a] * BrickSize;
    box.End[a] = std::min(box.Begin[a] + BrickSize, this->Grid.Dimensions[a] - 1) + 1;
  }
  return box;
}

VoxelBox FieldBricks::OwnBox(const int b[3]) const
{
  VoxelBox own = this->BrickBox(b);
  for (int a = 0; a < 3; ++a)
  {
    own.End[a] -= b[a] + 1 < this->Bricks[a] ? 1 : 0;
  }
  return own;
}

void FieldBricks::ComputeBrick(const int b[3], int slot)
{
  const VoxelBox box = this->BrickBox(b);
  const std::size_t n = static_cast<std::size_t>(box.NumberOfVoxels());
  this->Potential[slot].resize(n);
  this->Force[slot].resize(3 * n);
  thread_local std::vector<float> around; // SmoothAround's, reused
  VoxelBox over;
  const float* smooth = this->SmoothAround(b, around, over);
  if (this->Local())
  {
    ForceOfPotentialInBox(smooth, over, this->Grid, box, this->OwnBox(b),
      this->Potential[slot].data(), this->Force[slot].data());
    return;
  }
  PotentialAndForceInBox(smooth, over, this->Grid, box, this->OwnBox(b), this->Gains,
    this->Potential[slot].data(), this->Force[slot].data());
}

void FieldBricks::CompleteBrick(const int b[3], int slot)
{
  const VoxelBox box = this->BrickBox(b), own = this->OwnBox(b);
  float* potential = this->Potential[slot].data();
  float* force = this->Force[slot].data();
  thread_local std::vector<float> around; // gathered when a voxel is computed here (reused)
  VoxelBox over;
  const float* smooth = nullptr;
  const std::ptrdiff_t bx = box.End[0] - box.Begin[0], by = box.End[1] - box.Begin[1];
  for (int k = box.Begin[2]; k < box.End[2]; ++k)
    for (int j = box.Begin[1]; j < box.End[1]; ++j)
      // Within the own box along y and z, only the x layer past it is another brick's.
      for (int i = (j < own.End[1] && k < own.End[2]) ? own.End[0] : box.Begin[0]; i < box.End[0];
           ++i)
      {
        const int p[3] = { i, j, k };
        int owner[3];
        for (int a = 0; a < 3; ++a)
        {
          owner[a] = b[a] + (p[a] < own.End[a] ? 0 : 1);
        }
        const std::ptrdiff_t o =
          (i - box.Begin[0]) + (j - box.Begin[1]) * bx + (k - box.Begin[2]) * bx * by;
        const int from =
          this->Slots[(static_cast<std::size_t>(owner[2]) * this->Bricks[1] + owner[1]) *
              this->Bricks[0] +
            owner[0]];
        if (from < 0)
        {
          const VoxelBox voxel{ { i, j, k }, { i + 1, j + 1, k + 1 } };
          smooth = smooth ? smooth : this->SmoothAround(b, around, over);
          if (this->Local())
          {
            ForceOfPotentialInBox(smooth, over, this->Grid, box, voxel, potential, force);
            continue;
          }
          PotentialAndForceInBox(
            smooth, over, this->Grid, box, voxel, this->Gains, potential, force);
          continue;
        }
        const VoxelBox ob = this->BrickBox(owner);
        const std::ptrdiff_t ox = ob.End[0] - ob.Begin[0], oy = ob.End[1] - ob.Begin[1];
        const std::ptrdiff_t q =
          (i - ob.Begin[0]) + (j - ob.Begin[1]) * ox + (k - ob.Begin[2]) * ox * oy;
        potential[o] = this->Potential[from][q];
        std::copy_n(this->Force[from].data() + 3 * q, 3, force + 3 * o);
      }
  // Checked here, in the parallel loop, while the brick is in cache.
  const auto finite = [](const std::vector<float>& v)
  { return std::all_of(v.begin(), v.end(), [](float x) { return std::isfinite(x); }); };
  this->BrickFinite[slot] = finite(this->Potential[slot]) && finite(this->Force[slot]);
}

int FieldBricks::Cover(const TriangleMesh& mesh)
{
  // The bricks holding a cell within the reach of a vertex (index space, a voxel more).
  std::vector<char> needed;
  this->MarkNear(mesh.Points, this->Reach, 0, needed);
  std::vector<int> fresh; // brick ids to compute
  for (std::size_t id = 0; id < needed.size(); ++id)
  {
    if (needed[id] && this->Slots[id] < 0)
    {
      fresh.push_back(static_cast<int>(id));
    }
  }
  if (!this->EnsureTiles(mesh, fresh))
  {
    fresh.clear(); // not computed: their samples count as misses
  }
  this->DropUnreachedOverBudget(needed, fresh.size());
  if (!fresh.empty() &&
    !this->Affords(static_cast<double>(fresh.size()) * BrickBytes,
      "the bricks of the force field the surface came near"))
  {
    return 0; // the caller ends the solve (Shortfall)
  }
  for (int id : fresh)
  {
    if (this->FreeSlots.empty())
    {
      this->Slots[id] = static_cast<int>(this->Potential.size());
      this->Potential.emplace_back();
      this->Force.emplace_back();
      this->BrickFinite.push_back(1);
    }
    else
    {
      this->Slots[id] = this->FreeSlots.back();
      this->FreeSlots.pop_back();
    }
  }
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ ResolveThreads(this->Parameters.NumberOfThreads), "STDThread", false },
    [&]
    {
      // Two passes: a brick copies the layer it shares with the next one from it, so every
      // fresh brick's own voxels are computed first.
      const auto forEachFresh = [&](void (FieldBricks::*step)(const int[3], int))
      {
        vtkSMPTools::For(0, static_cast<int>(fresh.size()),
          [&](int begin, int end)
          {
            for (int f = begin; f < end; ++f)
            {
              const int id = fresh[f];
              const int b[3] = { id % this->Bricks[0], (id / this->Bricks[0]) % this->Bricks[1],
                id / (this->Bricks[0] * this->Bricks[1]) };
              (this->*step)(b, this->Slots[id]);
            }
          });
      };
      forEachFresh(&FieldBricks::ComputeBrick);
      forEachFresh(&FieldBricks::CompleteBrick);
    });
  return static_cast<int>(fresh.size());
}

void FieldBricks::DropUnreachedOverBudget(const std::vector<char>& needed, std::size_t fresh)
{
  // A surface that travels far in a level (a seed the region force grows across the box) would
  // leave a trail of bricks behind it, and bricks hold their shared layers twice (9^3 values a
  // brick of 8^3 voxels): more than the box's field, which a piece's memory check counts on
  // (FieldBytesPerVoxel; a serial field checks its bricks as they are added, CheckMemoryAsAdded).
  // Past that, the bricks no vertex can reach are dropped; a brick computed again holds the same
  // values, so nothing but time depends on it.
  const double brickVoxels = std::pow(BrickSize + 1.0, 3);
  const double live = static_cast<double>(this->Potential.size() - this->FreeSlots.size());
  if ((live + static_cast<double>(fresh)) * brickVoxels <=
    static_cast<double>(this->Grid.NumberOfVoxels()))
  {
    return;
  }
  for (std::size_t id = 0; id < needed.size(); ++id)
  {
    const int slot = this->Slots[id];
    if (slot >= 0 && !needed[id])
    {
      std::vector<float>().swap(this->Potential[slot]);
      std::vector<float>().swap(this->Force[slot]);
      this->BrickFinite[slot] = 1;
      this->FreeSlots.push_back(slot);
      this->Slots[id] = -1;
    }
  }
}

// inline: an exported member is otherwise called through the PLT from SampleForce.
inline bool FieldBricks::Locate(const double x[3], int& slot, TrilinearCell& cell) const
{
  // The cell as LocateTrilinearCell finds it on the whole box (same clamping, same fractions),
  // then its place in its brick.
  double ijk[3];
  this->Grid.WorldToIndex(x, ijk);
  int brick[3], local[3], samples[3];
  for (int a = 0; a < 3; ++a)
  {
    const int n = this->Grid.Dimensions[a];
    if (!(ijk[a] >= -0.5 && ijk[a] <= n - 1 + 0.5))
    {
      return false;
    }
    const double v = std::min(std::max(ijk[a], 0.0), static_cast<double>(n - 1));
    // v >= 0 (NaN failed the test above), so truncation is floor, without a libm call.
    const int i0 = std::min(static_cast<int>(v), n - 2);
    cell.T[a] = v - static_cast<double>(i0);
    brick[a] = i0 / BrickSize;
    local[a] = i0 - brick[a] * BrickSize;
    samples[a] = std::min(BrickSize, n - 1 - brick[a] * BrickSize) + 1;
  }
  slot =
    this
      ->Slots[(static_cast<std::size_t>(brick[2]) * this->Bricks[1] + brick[1]) * this->Bricks[0] +
        brick[0]];
  cell.Step[0] = 1;
  cell.Step[1] = samples[0];
  cell.Step[2] = static_cast<long long>(samples[0]) * samples[1];
  cell.Base = local[0] + local[1] * cell.Step[1] + local[2] * cell.Step[2];
  return true;
}

bool FieldBricks::SampleForce(const double x[3], double f[3]) const
{
  f[0] = f[1] = f[2] = 0.0;
  int slot = -1;
  TrilinearCell c;
  if (!this->Locate(x, slot, c))
  {
    return false;
  }
  if (slot < 0)
  {
    ++this->MissCount;
    return true;
  }
  AddTrilinearVector(this->Force[slot].data(), c, f);
  return true;
}

double FieldBricks::SamplePotential(const double x[3]) const
{
  int slot = -1;
  TrilinearCell c;
  double p = 0.0;
  if (this->Locate(x, slot, c) && slot >= 0)
  {
    for (int corner = 0; corner < 8; ++corner)
    {
      p += c.Weight(corner) * this->Potential[slot][c.Corner(corner)];
    }
  }
  return p;
}

bool FieldBricks::Finite() const
{
  return std::all_of(
    this->BrickFinite.begin(), this->BrickFinite.end(), [](char finite) { return finite != 0; });
}

double FieldBricks::Bytes() const
{
  double bytes =
    this->Smooth ? sizeof(float) * static_cast<double>(this->Grid.NumberOfVoxels()) : 0.0;
  for (const auto& p : this->Potential)
  {
    bytes += 4.0 * sizeof(float) * static_cast<double>(p.size());
  }
  for (const auto& t : this->Tiles)
  {
    bytes += sizeof(float) * static_cast<double>(t.size());
  }
  return bytes;
}
} // namespace dsurf
