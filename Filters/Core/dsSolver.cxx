// SPDX-License-Identifier: BSD-3-Clause
#include "dsSolver.h"

#include "dsContact.h"
#include "dsRegion.h"
#include "dsSelfIntersectionRule.h"
#include "dsStepScheduler.h"
#include "dsThreads.h"

#include <algorithm>
#include <functional>

namespace dsurf
{
namespace
{
/// What the umbrella operators read: the mesh itself (Solver::Umbrella) or the
/// solver's breadth-first copy (the sweeps). Same arithmetic either way. The normalised weight
/// of neighbour slot i (docs/METHOD.md §6.4) is WeightValues[WeightIds[i]]; not read when every
/// weight is 1 (AllN).
struct MeshView
{
  const int* NeighborOffsets;
  const int* Neighbors;
  const double* WeightValues;
  const std::uint32_t* WeightIds;
  const Vec3* Points;
};

template <bool AllN>
inline double SlotWeight(const MeshView& m, int v, int slot)
{
  return AllN ? 1.0 / (m.NeighborOffsets[v + 1] - m.NeighborOffsets[v])
              : m.WeightValues[m.WeightIds[slot]];
}

/// U(v) = sum_i w_i q_i - v (the weights normalised).
template <bool AllN>
inline Vec3 UmbrellaOf(const MeshView& m, int v)
{
  const int begin = m.NeighborOffsets[v], end = m.NeighborOffsets[v + 1];
  double s0 = 0, s1 = 0, s2 = 0;
  for (int i = begin; i < end; ++i)
  {
    const int q = m.Neighbors[i];
    const double w = SlotWeight<AllN>(m, v, i);
    const Vec3& x = m.Points[q];
    s0 += w * x[0];
    s1 += w * x[1];
    s2 += w * x[2];
  }
  const Vec3& p = m.Points[v];
  return { s0 - p[0], s1 - p[1], s2 - p[2] };
}
} // namespace

Vec3 Solver::Umbrella(int v) const
{
  const TriangleMesh& m = *this->Mesh;
  if (m.NeighborOffsets[v + 1] == m.NeighborOffsets[v])
  {
    return { 0, 0, 0 };
  }
  const MeshView view{ m.NeighborOffsets.data(), m.Neighbors.data(), this->WeightValues.data(),
    this->WeightIds.data(), m.Points.data() };
  return this->UniformWeights ? UmbrellaOf<true>(view, v) : UmbrellaOf<false>(view, v);
}

Vec3 Solver::InternalCorrection(int v, Vec3& u) const
{
  const MeshView m{ this->LocalNeighborOffsets.data(), this->LocalNeighbors.data(),
    this->WeightValues.data(), this->LocalWeightIds.data(), this->LocalPoints.data() };
  const int begin = m.NeighborOffsets[v], end = m.NeighborOffsets[v + 1];
  const double tau = this->Parameters.Tau;

  // U(p), U^2(p) = sum_i w_i U(q_i) - U(p) and alpha (docs/METHOD.md §3 with the §6.4 weights),
  // the ring's umbrellas read from LocalUmbrellas.
  u = this->LocalUmbrellas[v];
  Vec3 u2acc{ 0, 0, 0 };
  const auto accumulate = [&](auto allN)
  {
    constexpr bool AllN = decltype(allN)::value;
    for (int i = begin; i < end; ++i)
    {
      u2acc = u2acc + SlotWeight<AllN>(m, v, i) * this->LocalUmbrellas[m.Neighbors[i]];
    }
  };
  if (this->AllNeighboursAlike())
  {
    accumulate(std::true_type{});
  }
  else
  {
    accumulate(std::false_type{});
  }
  const double alpha = this->LocalAlpha[v];
  const Vec3 u2 = u2acc - u;
  const Vec3& c1 = u;
  const Vec3 c2 = (-1.0 / alpha) * u2;
  // docs/METHOD.md §4 as written: c2 is Kobbelt's full Gauss-Seidel step of the thin plate
  // (alpha is U^2's coefficient of p), and (1 - tau) alpha c2 = -(1 - tau) U^2 turns it back into
  // the residual, the same units as tau c1; gamma is the step on the sum.
  return tau * c1 + ((1.0 - tau) * alpha) * c2;
}

Vec3 Solver::ExternalForce(int v, int& outside, Vec3& normal, bool& haveNormal) const
{
  Vec3 force{ 0, 0, 0 };
  const Vec3& p = this->LocalPoints[v];
  if (this->Field && this->Sampler)
  {
    double f[3] = { 0, 0, 0 };
    if (this->Sampler(this->Field, p.data(), f))
    {
      force = { this->ForceScale * f[0], this->ForceScale * f[1], this->ForceScale * f[2] };
    }
    else
    {
      outside = 1;
    }
  }
  if (this->RegionImage.Data)
  {
    // The region force along the unit normal (dsRegion.h); the normal is kept for the rule.
    bool inside = false;
    const double intensity = SampleVolume(this->RegionImage, p.data(), &inside);
    normal = this->FanNormal(v);
    haveNormal = true;
    const double nn = Norm(normal);
    if (inside && nn > 0)
    {
      const RegionModel& model =
        this->RegionModels[this->LocalObjects.empty() ? 0 : this->LocalObjects[v]];
      double speed = model.On ? RegionSpeed(intensity, model.Low, model.High) : 0.0;
      if (model.On && model.MidpointVoxel > 0)
      {
        speed = this->LocalMidpointSpeed(p, (1.0 / nn) * normal, model, intensity, speed);
      }
      speed = model.OutwardOnly ? std::max(speed, 0.0) : speed;
      if (model.DropInwardEdgePull && speed > 0)
      {
        force = WithoutInwardEdgePull(force, (1.0 / nn) * normal, speed);
      }
      force = force + (this->RegionScale * model.Scale * speed / nn) * normal;
    }
  }
  return force;
}

double Solver::LocalMidpointSpeed(
  const Vec3& p, const Vec3& n, const RegionModel& model, double intensity, double speed) const
{
  // The means of the image at a few depths on either side: one sample each is noise.
  double inside = 0, outside = 0;
  for (double depth : MidpointDepthsVoxels)
  {
    const Vec3 step = (depth * model.MidpointVoxel) * n;
    bool in = false, out = false;
    inside += SampleVolume(this->RegionImage, (p - step).data(), &in);
    outside += SampleVolume(this->RegionImage, (p + step).data(), &out);
    if (!in || !out)
    {
      return speed; // at the image's border
    }
  }
  constexpr double samples = sizeof(MidpointDepthsVoxels) / sizeof(MidpointDepthsVoxels[0]);
  return MidpointSpeed(
    intensity, inside / samples, outside / samples, model.Low, model.High, speed);
}

void Solver::UpdateRange(int first, int last)
{
  const int* vertices = this->LocalColors.Vertices.data();
  if (!this->HasExternalForce())
  {
    for (int k = first; k < last; ++k)
    {
      this->CorrectVertex(k, false, Vec3{ 0, 0, 0 }, 0, nullptr);
    }
    return;
  }
  // A batch's forces are sampled in a loop of their own, then its vertices corrected: the
  // samples are independent, so the processor overlaps their cache misses in the force field
  // and the image (one at a time when each sample waited behind a vertex's whole update). The
  // same results: a vertex's force depends only on its own position and its fan, which no
  // vertex of its colour moves (the distance-2 colouring, as for the force exchange).
  constexpr int Batch = 32;
  struct Sampled
  {
    Vec3 Force, Normal;
    int Outside;
    bool HaveNormal;
  } batch[Batch];
  for (int b = first; b < last; b += Batch)
  {
    const int n = std::min(Batch, last - b);
    for (int i = 0; i < n; ++i)
    {
      Sampled& s = batch[i];
      s.Outside = 0;
      s.HaveNormal = false;
      s.Force = this->ExternalForce(vertices[b + i], s.Outside, s.Normal, s.HaveNormal);
    }
    for (int i = 0; i < n; ++i)
    {
      const Sampled& s = batch[i];
      this->CorrectVertex(b + i, true, s.Force, s.Outside, s.HaveNormal ? &s.Normal : nullptr);
    }
  }
}

void Solver::SampleVertexForce(int v, VertexForce& out) const
{
  Vec3 normal;
  bool haveNormal = false;
  out.Position = this->LocalPoints[v];
  out.Outside = 0;
  out.Force = { 0, 0, 0 };
  if (this->HasExternalForce())
  {
    // The region force's normal is not kept: phase (c) recomputes it when the rule needs it
    // (the same value: no vertex of the colour moves v's fan).
    out.Force = this->ExternalForce(v, out.Outside, normal, haveNormal);
  }
}

void Solver::CorrectVertex(int k, bool external, const Vec3& force, int outside, const Vec3* normal)
{
  const int v = this->LocalColors.Vertices[k];
  Vec3 u;
  const Vec3 internal = this->InternalCorrection(v, u);

  // The docs/METHOD.md §5 rule on the external force (dsSelfIntersectionRule.h).
  Vec3 applied{ 0, 0, 0 };
  if (external)
  {
    applied = !this->Parameters.ProjectExternalForce
      ? force
      : SelfIntersectionRule(force, u, [&]() { return normal ? *normal : this->FanNormal(v); });
  }

  const double gamma = this->Parameters.Gamma;
  Vec3 c = gamma * (internal + applied);
  if (this->Bounds && !this->Bounds->Empty())
  {
    // Several objects, or one kept off itself: shortened to stay within the contact bounds
    // (dsContact.h).
    c = ContactStepScale(*this->Bounds, this->Original[v], this->LocalPoints[v], c) * c;
  }
  Vec3& point = this->LocalPoints[v];
  point = point + c;
  // The umbrellas the move changes: v's own and its ring's. No other vertex of v's colour
  // reads or moves them (the distance-2 colouring), so the threads never share one.
  this->LocalUmbrellas[v] = this->LocalUmbrellas[v] - c;
  for (int i = this->LocalNeighborOffsets[v]; i < this->LocalNeighborOffsets[v + 1]; ++i)
  {
    Vec3& uq = this->LocalUmbrellas[this->LocalNeighbors[i]];
    uq = uq + this->LocalBackWeights[i] * c;
  }
  VertexResult& result = this->LocalResults[k];
  result.Outside = outside;
  result.ErrorIndicator = gamma * Norm(internal);
  result.Displacement = Norm(c);
  result.Force = Norm(force);
}

void Solver::SampleRange(int colorBegin, int first, int last)
{
  for (int k = first; k < last; ++k)
  {
    this->SampleVertexForce(this->LocalColors.Vertices[k], this->ColorForces[k - colorBegin]);
  }
}

void Solver::CorrectRange(int colorBegin, int first, int last)
{
  for (int k = first; k < last; ++k)
  {
    const VertexForce& f = this->ColorForces[k - colorBegin];
    this->CorrectVertex(k, true, f.Force, f.Outside, nullptr);
  }
}

void Solver::ExchangeColor(int color)
{
  const int count = this->LocalColors.Offsets[color + 1] - this->LocalColors.Offsets[color];
  this->Exchange(this->ColorForces.data(), count);
}

Vec3 Solver::FanNormal(int v) const
{
  const int first = this->LocalFanOffsets[v];
  return AreaWeightedNormal(this->LocalPoints.data(), this->LocalFanOffsets[v + 1] - first,
    [this, first](int i) -> const std::array<int, 3>& { return this->LocalFan[first + i]; });
}

void Solver::CopyOut(int first, int last)
{
  TriangleMesh& m = *this->Mesh;
  for (int l = first; l < last; ++l)
  {
    const int v = this->Original[l];
    const int k = this->ColorSlot[l];
    const VertexResult result = k >= 0 ? this->LocalResults[k] : VertexResult();
    m.Points[v] = this->LocalPoints[l];
    this->ErrorIndicatorValues[v] = result.ErrorIndicator;
    this->DisplacementValues[v] = result.Displacement;
    this->ForceValues[v] = result.Force;
  }
}

SweepStatistics Solver::Sweep()
{
  SweepStatistics stats;
  this->Sweeps(1,
    [&stats](const SweepStatistics& s)
    {
      stats = s;
      return true;
    });
  return stats;
}

namespace
{
/// The statistics are summed per chunk of the colour-ordered (local) vertex list, then over the
/// chunks in order: the chunks do not depend on the number of threads, so neither does
/// the rounding, and the chunks can be summed in parallel.
constexpr int StatisticsChunk = 256;
}

void Solver::ChunkStatistics(int chunk, ChunkSums& out) const
{
  const int total = this->Colors.Offsets.back();
  const int first = chunk * StatisticsChunk, last = std::min(first + StatisticsChunk, total);
  double sum = 0, maxC = 0;
  int outside = 0;
  for (int k = first; k < last; ++k)
  {
    const VertexResult& result = this->LocalResults[k];
    sum += result.Displacement;
    maxC = std::max(maxC, result.Displacement);
    outside += result.Outside;
  }
  out.Sum = sum;
  out.Max = maxC;
  out.Outside = outside;
}

SweepStatistics Solver::CombineStatistics(const std::vector<ChunkSums>& chunks) const
{
  SweepStatistics stats;
  const int total = this->Colors.Offsets.back();
  double sum = 0;
  for (const ChunkSums& c : chunks)
  {
    sum += c.Sum;
    stats.MaxCorrection = std::max(stats.MaxCorrection, c.Max);
    stats.OutsideVertices += c.Outside;
  }
  stats.MovedVertices = total;
  stats.MeanCorrection = total > 0 ? sum / total : 0.0;
  return stats;
}

void Solver::ComputeUmbrellas(int first, int last)
{
  const MeshView m{ this->LocalNeighborOffsets.data(), this->LocalNeighbors.data(),
    this->WeightValues.data(), this->LocalWeightIds.data(), this->LocalPoints.data() };
  const bool allN = this->AllNeighboursAlike();
  for (int l = first; l < last; ++l)
  {
    this->LocalUmbrellas[l] = m.NeighborOffsets[l + 1] == m.NeighborOffsets[l]
      ? Vec3{ 0, 0, 0 }
      : (allN ? UmbrellaOf<true>(m, l) : UmbrellaOf<false>(m, l));
  }
}

void Solver::BuildRingCoefficients()
{
  const MeshView m{ this->LocalNeighborOffsets.data(), this->LocalNeighbors.data(),
    this->WeightValues.data(), this->LocalWeightIds.data(), this->LocalPoints.data() };
  const bool allN = this->AllNeighboursAlike();
  this->RingCoefficientsMode = allN ? 1 : 0;
  const int n = static_cast<int>(this->LocalNeighborOffsets.size()) - 1;
  this->LocalBackWeights.assign(this->LocalNeighbors.size(), 0.0);
  this->LocalAlpha.assign(n, 1.0);
  this->LocalUmbrellas.assign(n, Vec3{ 0, 0, 0 });
  for (int v = 0; v < n; ++v)
  {
    for (int i = m.NeighborOffsets[v]; i < m.NeighborOffsets[v + 1]; ++i)
    {
      const int q = m.Neighbors[i];
      double back = 0; // the normalised weight q gives v (0 if v is not in q's ring)
      for (int j = m.NeighborOffsets[q]; j < m.NeighborOffsets[q + 1]; ++j)
      {
        if (m.Neighbors[j] == v)
        {
          back = allN ? SlotWeight<true>(m, q, j) : SlotWeight<false>(m, q, j);
        }
      }
      this->LocalBackWeights[i] = back;
      this->LocalAlpha[v] += (allN ? SlotWeight<true>(m, v, i) : SlotWeight<false>(m, v, i)) * back;
    }
  }
}

void Solver::RefreshLocal(int first, int last)
{
  // The caller may have moved points since the last call (labels are read by SetMesh()), and
  // changed the objects.
  const TriangleMesh& m = *this->Mesh;
  const bool objects = !this->LocalObjects.empty();
  for (int l = first; l < last; ++l)
  {
    const int v = this->Original[l];
    this->LocalPoints[l] = m.Points[v];
    if (objects)
    {
      this->LocalObjects[l] =
        std::min(m.Objects[v], static_cast<int>(this->RegionModels.size()) - 1);
    }
  }
}

bool Solver::ReadyToSweep()
{
  if (!this->Mesh)
  {
    return false;
  }
  const TriangleMesh& m = *this->Mesh;
  const int n = m.NumberOfPoints();
  if (static_cast<int>(m.NeighborOffsets.size()) != n + 1)
  {
    return false; // no topology: nothing can move
  }
  if (this->ColoredPoints != n)
  {
    this->BuildColoring();
  }
  return this->ColoredPoints == n; // else no labels yet: nothing was coloured
}

int Solver::Sweeps(int maxSweeps, const std::function<bool(const SweepStatistics&)>& afterSweep)
{
  if (maxSweeps <= 0 || !this->ReadyToSweep())
  {
    return 0;
  }
  if (this->RingCoefficientsMode != (this->AllNeighboursAlike() ? 1 : 0))
  {
    this->BuildRingCoefficients(); // a new mesh, or the label weights switched
  }
  if (this->Exchange)
  {
    int largest = 0;
    for (int c = 0; c < this->NumberOfColors(); ++c)
    {
      largest = std::max(largest, this->Colors.Offsets[c + 1] - this->Colors.Offsets[c]);
    }
    this->ColorForces.resize(largest);
  }
  // Sized here, filled by RefreshLocal with the points.
  const std::size_t n = static_cast<std::size_t>(this->Mesh->NumberOfPoints());
  const bool objects =
    this->RegionImage.Data && this->RegionModels.size() > 1 && this->Mesh->Objects.size() == n;
  this->LocalObjects.assign(objects ? n : 0, 0);
  const int numThreads = ResolveThreads(this->Parameters.NumberOfThreads);
  if (numThreads <= 1 || this->Colors.Offsets.back() < 256)
  {
    return this->SerialSweeps(maxSweeps, afterSweep);
  }
  return this->ParallelSweeps(numThreads, maxSweeps, afterSweep);
}

int Solver::SerialSweeps(
  int maxSweeps, const std::function<bool(const SweepStatistics&)>& afterSweep)
{
  const int n = this->Mesh->NumberOfPoints();
  const int total = this->Colors.Offsets.back();
  const int numChunks = (total + StatisticsChunk - 1) / StatisticsChunk;
  std::vector<ChunkSums> chunks(numChunks);
  this->RefreshLocal(0, n);
  for (int sweep = 1;; ++sweep)
  {
    this->ComputeUmbrellas(0, n);
    if (this->Exchange)
    {
      for (int color = 0; color < this->NumberOfColors(); ++color)
      {
        const int begin = this->LocalColors.Offsets[color];
        const int end = this->LocalColors.Offsets[color + 1];
        this->SampleRange(begin, begin, end);
        this->ExchangeColor(color);
        this->CorrectRange(begin, begin, end);
      }
    }
    else
    {
      for (int color = 0; color < this->NumberOfColors(); ++color)
      {
        this->UpdateRange(this->LocalColors.Offsets[color], this->LocalColors.Offsets[color + 1]);
      }
    }
    for (int c = 0; c < numChunks; ++c)
    {
      this->ChunkStatistics(c, chunks[c]);
    }
    if (!afterSweep(this->CombineStatistics(chunks)) || sweep == maxSweeps)
    {
      this->CopyOut(0, n);
      return sweep;
    }
  }
}

/// The parallel sweeps as steps of a StepScheduler: step 0 copies the mesh into the local
/// layout; then per sweep one step for the umbrellas, one per colour (its vertices updated in
/// place; with a force exchange two: the forces sampled, ending with the exchange, then the
/// vertices corrected) and one for the statistics, which ends with the caller's callback; the
/// step after the last sweep copies the results back to the mesh.
class Solver::SweepJob : public StepScheduler::Job
{
public:
  SweepJob(Solver& solver, int blocks, int maxSweeps,
    const std::function<bool(const SweepStatistics&)>& afterSweep)
    : S(solver)
    , Blocks(blocks)
    , MaxSweeps(maxSweeps)
    , AfterSweep(afterSweep)
    , Points(solver.Mesh->NumberOfPoints())
    , PhasesPerColor(solver.Exchange ? 2 : 1)
    , StepsPerSweep(1 + solver.NumberOfColors() * PhasesPerColor + 1)
    , Chunks((solver.Colors.Offsets.back() + StatisticsChunk - 1) / StatisticsChunk)
  {
  }

  void RunBlock(long long step, int block) override
  {
    int first = 0, last = 0;
    if (this->Finishing || step == 0)
    {
      StepScheduler::BlockRange(this->Points, block, this->Blocks, first, last);
      this->Finishing ? this->S.CopyOut(first, last) : this->S.RefreshLocal(first, last);
      return;
    }
    const int phase = this->Phase(step);
    if (phase == 0)
    {
      StepScheduler::BlockRange(this->Points, block, this->Blocks, first, last);
      this->S.ComputeUmbrellas(first, last);
      return;
    }
    if (phase == this->StepsPerSweep - 1)
    {
      StepScheduler::BlockRange(
        static_cast<long long>(this->Chunks.size()), block, this->Blocks, first, last);
      for (int c = first; c < last; ++c)
      {
        this->S.ChunkStatistics(c, this->Chunks[c]);
      }
      return;
    }
    const int color = (phase - 1) / this->PhasesPerColor;
    const int cBegin = this->S.LocalColors.Offsets[color];
    StepScheduler::BlockRange(
      this->S.LocalColors.Offsets[color + 1] - cBegin, block, this->Blocks, first, last);
    if (this->PhasesPerColor == 1)
    {
      this->S.UpdateRange(cBegin + first, cBegin + last);
    }
    else if ((phase - 1) % 2 == 0)
    {
      this->S.SampleRange(cBegin, cBegin + first, cBegin + last);
    }
    else
    {
      this->S.CorrectRange(cBegin, cBegin + first, cBegin + last);
    }
  }

  bool HasEnd(long long step) const override
  {
    if (step == 0)
    {
      return false;
    }
    const int phase = this->Phase(step);
    return phase == this->StepsPerSweep - 1 ||
      (this->PhasesPerColor == 2 && phase > 0 && (phase - 1) % 2 == 0);
  }

  bool EndStep(long long step) override
  {
    const int phase = this->Phase(step);
    if (phase != this->StepsPerSweep - 1)
    {
      this->S.ExchangeColor((phase - 1) / 2); // every force of the colour is sampled
      return false;
    }
    // Every chunk is summed: combine and report; the other threads wait meanwhile.
    ++this->SweepsDone;
    this->Finishing = !this->AfterSweep(this->S.CombineStatistics(this->Chunks)) ||
      this->SweepsDone >= this->MaxSweeps;
    return this->Finishing;
  }

  int SweepsDone = 0;

private:
  int Phase(long long step) const { return static_cast<int>((step - 1) % this->StepsPerSweep); }

  Solver& S;
  const int Blocks, MaxSweeps;
  const std::function<bool(const SweepStatistics&)>& AfterSweep;
  const int Points, PhasesPerColor, StepsPerSweep;
  std::vector<ChunkSums> Chunks;
  bool Finishing = false; ///< the last step: write the results back to the mesh
};

int Solver::ParallelSweeps(
  int numThreads, int maxSweeps, const std::function<bool(const SweepStatistics&)>& afterSweep)
{
  const StepScheduler scheduler(numThreads);
  SweepJob job(*this, scheduler.NumberOfBlocks(), maxSweeps, afterSweep);
  scheduler.Run(job);
  return job.SweepsDone;
}
} // namespace dsurf
