// SPDX-License-Identifier: BSD-3-Clause
#include "dsFieldBricks.h"

#include "dsThreads.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

namespace dsurf
{
bool FieldBricks::Initialize(
  const ImageView& image, const ScaleSpaceParameters& parameters, double reach, std::string* error)
{
  this->Grid = image.Geometry;
  this->Parameters = parameters;
  // A piece's hooks (dsPieceField.h) capture its caller's locals and are used here only:
  // the bricks computed later must not reach them.
  this->Parameters.Smooth = nullptr;
  this->Parameters.GradientMaximum = nullptr;
  this->Reach = reach;
  this->Potential.clear();
  this->Force.clear();
  this->BrickFinite.clear();
  this->FreeSlots.clear();
  this->MissCount = 0;
  this->Smooth.reset(new float[static_cast<std::size_t>(image.Geometry.NumberOfVoxels())]);
  if (!SmoothForPotential(image, parameters, this->Smooth.get(), this->Gains, error))
  {
    this->Smooth.reset();
    return false;
  }
  // Brick b along an axis holds the cells whose lower corner is b * BrickSize ... + BrickSize - 1.
  for (int a = 0; a < 3; ++a)
  {
    this->Bricks[a] = (this->Grid.Dimensions[a] - 2) / BrickSize + 1;
  }
  this->Slots.assign(
    static_cast<std::size_t>(this->Bricks[0]) * this->Bricks[1] * this->Bricks[2], -1);
  return true;
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
  PotentialAndForceInBox(this->Smooth.get(), this->Grid, box, this->OwnBox(b), this->Gains,
    this->Potential[slot].data(), this->Force[slot].data());
}

void FieldBricks::CompleteBrick(const int b[3], int slot)
{
  const VoxelBox box = this->BrickBox(b), own = this->OwnBox(b);
  float* potential = this->Potential[slot].data();
  float* force = this->Force[slot].data();
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
          PotentialAndForceInBox(
            this->Smooth.get(), this->Grid, box, voxel, this->Gains, potential, force);
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
  std::vector<char> needed(this->Slots.size(), 0);
  for (const Vec3& p : mesh.Points)
  {
    double ijk[3];
    this->Grid.WorldToIndex(p.data(), ijk);
    int lo[3], hi[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a)
    {
      const double r = this->Reach / this->Grid.Spacing[a] + 1.0;
      const double last = this->Grid.Dimensions[a] - 2;
      const double from = std::max(0.0, std::floor(ijk[a] - r));
      const double to = std::min(last, std::floor(ijk[a] + r));
      inside = inside && from <= to; // also false for NaN
      lo[a] = inside ? static_cast<int>(from) / BrickSize : 0;
      hi[a] = inside ? static_cast<int>(to) / BrickSize : -1;
    }
    for (int k = lo[2]; inside && k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          needed[(static_cast<std::size_t>(k) * this->Bricks[1] + j) * this->Bricks[0] + i] = 1;
        }
  }
  std::vector<int> fresh; // brick ids to compute
  for (std::size_t id = 0; id < needed.size(); ++id)
  {
    if (needed[id] && this->Slots[id] < 0)
    {
      fresh.push_back(static_cast<int>(id));
    }
  }
  this->DropUnreachedOverBudget(needed, fresh.size());
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
  // brick of 8^3 voxels): more than the box's field, which the memory check counts on
  // (FieldBytesPerVoxel). Past that, the bricks no vertex can reach are dropped; a brick
  // computed again holds the same values, so nothing but time depends on it.
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
  return bytes;
}
} // namespace dsurf
