#include "dsSolver.h"

#include "dsRegion.h"
#include "dsThreads.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <functional>
#include <memory>
#include <thread>

namespace dsurf
{
namespace
{
/// What the umbrella operators read: the mesh itself (Solver::Umbrella) or the
/// solver's breadth-first copy (the sweeps). Same arithmetic either way.
struct MeshView
{
  const int* NeighborOffsets;
  const int* Neighbors;
  const unsigned char* Labels;
  const Vec3* Points;
};

/// Weight sum of vertex v and the normalised weight it gives neighbour slot i.
/// Uniform fallback when the label weights of v sum to zero: an M vertex whose only
/// neighbours are M, which red-green cascades do produce now and then (measured: 19 times
/// in 300 random multi-level runs; docs/METHOD.md §6.4 lets rare cascading cases be ignored).
struct RingWeights
{
  double InvW = 0;   ///< 1 / sum of weights
  bool Uniform = true;
};

template <bool AllN>
inline RingWeights ComputeRingWeights(const MeshView& m, int v)
{
  const int begin = m.NeighborOffsets[v], end = m.NeighborOffsets[v + 1];
  RingWeights rw;
  if (AllN)
  {
    rw.InvW = 1.0 / (end - begin);
    return rw;
  }
  double w = 0;
  const unsigned char lv = m.Labels[v];
  for (int i = begin; i < end; ++i)
  {
    w += UmbrellaWeight(lv, m.Labels[m.Neighbors[i]]);
  }
  if (w > 0)
  {
    rw.InvW = 1.0 / w;
    rw.Uniform = false;
  }
  else
  {
    rw.InvW = 1.0 / (end - begin);
  }
  return rw;
}

template <bool AllN>
inline double SlotWeight(const MeshView& m, int v, int q, const RingWeights& rw)
{
  if (AllN || rw.Uniform)
  {
    return rw.InvW;
  }
  return UmbrellaWeight(m.Labels[v], m.Labels[q]) * rw.InvW;
}

/// U(v) and the normalised weight that v gives the vertex `other` (0 if not a neighbour).
template <bool AllN>
inline Vec3 UmbrellaOf(const MeshView& m, int v, int other, double* weightOfOther)
{
  const int begin = m.NeighborOffsets[v], end = m.NeighborOffsets[v + 1];
  const RingWeights rw = ComputeRingWeights<AllN>(m, v);
  double s0 = 0, s1 = 0, s2 = 0;
  for (int i = begin; i < end; ++i)
  {
    const int q = m.Neighbors[i];
    const double w = SlotWeight<AllN>(m, v, q, rw);
    const Vec3& x = m.Points[q];
    s0 += w * x[0];
    s1 += w * x[1];
    s2 += w * x[2];
    if (q == other)
    {
      *weightOfOther = w;
    }
  }
  const Vec3& p = m.Points[v];
  return { s0 - p[0], s1 - p[1], s2 - p[2] };
}

/// Spin briefly, then give the core away: the other thread is usually microseconds
/// from done, but on a loaded machine it may be descheduled.
inline void WaitPause(int& spins)
{
  if (++spins < 256)
  {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  else
  {
    std::this_thread::yield();
  }
}

} // namespace

void Solver::SetMesh(TriangleMesh* mesh)
{
  this->Mesh = mesh;
  this->BuildColoring();
}

void Solver::BuildColoring()
{
  this->ClassOffsets.assign(1, 0);
  this->ClassVertices.clear();
  this->ColoredPoints = -1;
  if (!this->Mesh)
  {
    return;
  }
  const TriangleMesh& m = *this->Mesh;
  const int n = m.NumberOfPoints();
  if (static_cast<int>(m.NeighborOffsets.size()) != n + 1 || static_cast<int>(m.Labels.size()) != n)
  {
    return; // no topology yet
  }
  this->ColoredPoints = n;
  this->UniformWeights = true;
  for (int v = 0; v < n; ++v)
  {
    if (m.Labels[v] != LabelN)
    {
      this->UniformWeights = false;
      break;
    }
  }

  // Greedy distance-2 colouring in vertex order (deterministic): a vertex takes the
  // smallest colour not used within two edges, so vertices of one colour neither
  // share an edge nor appear in each other's U^2 stencil or normal fan.
  std::vector<int> color(n, -1);
  std::vector<int> stamp; // stamp[c] == v: colour c is forbidden for v
  int numColors = 0;
  for (int v = 0; v < n; ++v)
  {
    auto forbid = [&](int u) {
      const int c = color[u];
      if (c >= 0)
      {
        stamp[c] = v;
      }
    };
    for (int i = m.NeighborOffsets[v]; i < m.NeighborOffsets[v + 1]; ++i)
    {
      const int q = m.Neighbors[i];
      forbid(q);
      for (int j = m.NeighborOffsets[q]; j < m.NeighborOffsets[q + 1]; ++j)
      {
        forbid(m.Neighbors[j]);
      }
    }
    int c = 0;
    while (c < numColors && stamp[c] == v)
    {
      ++c;
    }
    if (c == numColors)
    {
      ++numColors;
      stamp.push_back(-1);
    }
    color[v] = c;
  }

  // Colour classes of the vertices that move (CSR, ascending ids within a class).
  std::vector<int> counts(numColors + 1, 0);
  for (int v = 0; v < n; ++v)
  {
    if (!m.BoundaryVertex[v] && m.NeighborOffsets[v + 1] > m.NeighborOffsets[v])
    {
      ++counts[color[v] + 1];
    }
  }
  for (int c = 0; c < numColors; ++c)
  {
    counts[c + 1] += counts[c];
  }
  this->ClassOffsets = counts;
  this->ClassVertices.assign(counts[numColors], -1);
  for (int v = 0; v < n; ++v)
  {
    if (!m.BoundaryVertex[v] && m.NeighborOffsets[v + 1] > m.NeighborOffsets[v])
    {
      this->ClassVertices[counts[color[v]]++] = v;
    }
  }
  this->BuildLocalLayout();
}

void Solver::BuildLocalLayout()
{
  const TriangleMesh& m = *this->Mesh;
  const int n = m.NumberOfPoints();
  // Breadth-first order, component by component: any prefix of it is a compact patch,
  // so contiguous shares of it are compact regions with short borders.
  this->Original.clear();
  this->Original.reserve(n);
  this->Local.assign(n, -1);
  for (int seed = 0; seed < n; ++seed)
  {
    if (this->Local[seed] >= 0)
    {
      continue;
    }
    std::size_t head = this->Original.size();
    this->Local[seed] = static_cast<int>(this->Original.size());
    this->Original.push_back(seed);
    for (; head < this->Original.size(); ++head)
    {
      const int v = this->Original[head];
      for (int i = m.NeighborOffsets[v]; i < m.NeighborOffsets[v + 1]; ++i)
      {
        const int q = m.Neighbors[i];
        if (this->Local[q] < 0)
        {
          this->Local[q] = static_cast<int>(this->Original.size());
          this->Original.push_back(q);
        }
      }
    }
  }

  // Neighbour lists and triangle fans in local ids, each in the mesh's order, so every
  // sum is evaluated in the same order as on the mesh itself.
  this->LocalNeighborOffsets.assign(n + 1, 0);
  this->LocalNeighbors.resize(m.Neighbors.size());
  this->LocalFanOffsets.assign(n + 1, 0);
  this->LocalFan.resize(m.VertexTriangles.size());
  this->LocalLabels.resize(n);
  this->LocalPoints.resize(n);
  for (int l = 0; l < n; ++l)
  {
    const int v = this->Original[l];
    int k = this->LocalNeighborOffsets[l];
    for (int i = m.NeighborOffsets[v]; i < m.NeighborOffsets[v + 1]; ++i)
    {
      this->LocalNeighbors[k++] = this->Local[m.Neighbors[i]];
    }
    this->LocalNeighborOffsets[l + 1] = k;
    int f = this->LocalFanOffsets[l];
    for (int i = m.VertexTriangleOffsets[v]; i < m.VertexTriangleOffsets[v + 1]; ++i)
    {
      const auto& tri = m.Triangles[m.VertexTriangles[i]];
      this->LocalFan[f++] = { this->Local[tri[0]], this->Local[tri[1]], this->Local[tri[2]] };
    }
    this->LocalFanOffsets[l + 1] = f;
  }

  // The colour classes in local ids, ascending: a thread's share of a colour is a
  // contiguous run of it, hence a compact region.
  const int numColors = this->NumberOfColors();
  this->WorkOffsets = this->ClassOffsets;
  this->WorkVertices.resize(this->ClassVertices.size());
  for (int c = 0; c < numColors; ++c)
  {
    for (int k = this->ClassOffsets[c]; k < this->ClassOffsets[c + 1]; ++k)
    {
      this->WorkVertices[k] = this->Local[this->ClassVertices[k]];
    }
    std::sort(this->WorkVertices.begin() + this->ClassOffsets[c],
      this->WorkVertices.begin() + this->ClassOffsets[c + 1]);
  }

  // Fixed vertices keep 0; moving ones are overwritten by every sweep.
  this->ErrorIndicatorValues.assign(n, 0.0);
  this->DisplacementValues.assign(n, 0.0);
  this->ForceValues.assign(n, 0.0);
  this->LocalResults.assign(n, VertexResult());
}

Vec3 Solver::Umbrella(int v) const
{
  double unused = 0;
  const TriangleMesh& m = *this->Mesh;
  if (m.NeighborOffsets[v + 1] == m.NeighborOffsets[v])
  {
    return { 0, 0, 0 };
  }
  const MeshView view{ m.NeighborOffsets.data(), m.Neighbors.data(), m.Labels.data(), m.Points.data() };
  return UmbrellaOf<false>(view, v, -1, &unused);
}

void Solver::UpdateVertex(int v)
{
  const MeshView m{ this->LocalNeighborOffsets.data(), this->LocalNeighbors.data(), this->LocalLabels.data(),
    this->LocalPoints.data() };
  const int begin = m.NeighborOffsets[v], end = m.NeighborOffsets[v + 1];
  const double tau = this->Parameters.Tau, gamma = this->Parameters.Gamma;

  // U(p), U^2(p) and alpha (docs/METHOD.md §3 with the §6.4 weights).
  Vec3 u, u2acc{ 0, 0, 0 };
  double alpha = 1.0;
  double unused = 0;
  const auto accumulate = [&](auto allN) {
    constexpr bool AllN = decltype(allN)::value;
    u = UmbrellaOf<AllN>(m, v, -1, &unused);
    const RingWeights rw = ComputeRingWeights<AllN>(m, v);
    for (int i = begin; i < end; ++i)
    {
      const int q = m.Neighbors[i];
      const double w = SlotWeight<AllN>(m, v, q, rw);
      double back = 0; // the normalised weight q gives p
      const Vec3 uq = UmbrellaOf<AllN>(m, q, v, &back);
      u2acc = u2acc + w * uq;
      alpha += w * back;
    }
  };
  if (this->UniformWeights || !this->Parameters.UseLabelWeights)
  {
    accumulate(std::true_type{});
  }
  else
  {
    accumulate(std::false_type{});
  }
  const Vec3 u2 = u2acc - u;
  const Vec3& c1 = u;
  const Vec3 c2 = (-1.0 / alpha) * u2;
  const Vec3 internal = tau * c1 + ((1.0 - tau) * alpha) * c2;

  // External force and the docs/METHOD.md §5 rule: along the umbrella when F points the same
  // way, otherwise along the normal; the projection keeps F from sliding vertices
  // tangentially over each other.
  Vec3 force{ 0, 0, 0 };
  Vec3 applied{ 0, 0, 0 };
  int outside = 0;
  Vec3* points = this->LocalPoints.data();
  if (this->Field && this->Sampler)
  {
    double f[3] = { 0, 0, 0 };
    if (this->Sampler(this->Field, points[v].data(), f))
    {
      force = { this->ForceScale * f[0], this->ForceScale * f[1], this->ForceScale * f[2] };
    }
    else
    {
      outside = 1;
    }
  }
  // The area-weighted normal, computed once: the region force and the projection rule need it.
  Vec3 normal{ 0, 0, 0 };
  bool haveNormal = false;
  if (this->RegionScalars)
  {
    bool inside = false;
    const double intensity = SampleVolume(this->RegionScalars, this->RegionGeometry, points[v].data(), &inside);
    normal = this->FanNormal(v);
    haveNormal = true;
    const Vec3& n = normal;
    const double nn = Norm(n);
    if (inside && nn > 0)
    {
      double speed = RegionSpeed(intensity, this->RegionLow, this->RegionHigh);
      speed = this->RegionOutwardOnly ? std::max(speed, 0.0) : speed;
      force = force + (this->RegionScale * speed / nn) * n;
    }
  }
  if ((this->Field && this->Sampler) || this->RegionScalars)
  {
    if (!this->Parameters.ProjectExternalForce)
    {
      applied = force;
    }
    else
    {
      const double fu = Dot(force, u);
      if (fu > 0)
      {
        applied = (fu / Dot(u, u)) * u;
      }
      else
      {
        const Vec3 nrm = haveNormal ? normal : this->FanNormal(v);
        const double nn = Dot(nrm, nrm);
        if (nn > 0)
        {
          applied = (Dot(force, nrm) / nn) * nrm;
        }
      }
    }
  }

  const Vec3 c = gamma * (internal + applied);
  points[v] = points[v] + c;
  VertexResult& result = this->LocalResults[v];
  result.Outside = outside;
  result.ErrorIndicator = gamma * Norm(internal);
  result.Displacement = Norm(c);
  result.Force = Norm(force);
}

Vec3 Solver::FanNormal(int v) const
{
  // As TriangleMesh::AreaWeightedNormal, on the local copy.
  const Vec3* points = this->LocalPoints.data();
  Vec3 nrm{ 0, 0, 0 };
  for (int i = this->LocalFanOffsets[v]; i < this->LocalFanOffsets[v + 1]; ++i)
  {
    const auto& tri = this->LocalFan[i];
    nrm = nrm + Cross(points[tri[1]] - points[tri[0]], points[tri[2]] - points[tri[0]]);
  }
  return nrm;
}

void Solver::CopyOut(int first, int last)
{
  TriangleMesh& m = *this->Mesh;
  for (int l = first; l < last; ++l)
  {
    const int v = this->Original[l];
    const VertexResult& result = this->LocalResults[l];
    m.Points[v] = this->LocalPoints[l];
    this->ErrorIndicatorValues[v] = result.ErrorIndicator;
    this->DisplacementValues[v] = result.Displacement;
    this->ForceValues[v] = result.Force;
  }
}

SweepStatistics Solver::Sweep()
{
  SweepStatistics stats;
  this->Sweeps(1, [&stats](const SweepStatistics& s) {
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
  const int total = this->ClassOffsets.back();
  const int first = chunk * StatisticsChunk, last = std::min(first + StatisticsChunk, total);
  double sum = 0, maxC = 0;
  int outside = 0;
  for (int k = first; k < last; ++k)
  {
    const VertexResult& result = this->LocalResults[this->WorkVertices[k]];
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
  const int total = this->ClassOffsets.back();
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

int Solver::Sweeps(int maxSweeps, const std::function<bool(const SweepStatistics&)>& afterSweep)
{
  if (!this->Mesh || maxSweeps <= 0)
  {
    return 0;
  }
  TriangleMesh& m = *this->Mesh;
  const int n = m.NumberOfPoints();
  if (static_cast<int>(m.NeighborOffsets.size()) != n + 1)
  {
    return 0; // no topology: nothing can move
  }
  if (this->ColoredPoints != n)
  {
    this->BuildColoring();
    if (this->ColoredPoints != n)
    {
      return 0; // no labels yet: nothing was coloured
    }
  }

  const int numColors = this->NumberOfColors();
  const int numThreads = ResolveThreads(this->Parameters.NumberOfThreads);
  const int total = this->ClassOffsets.back();
  const int numChunks = (total + StatisticsChunk - 1) / StatisticsChunk;
  std::vector<ChunkSums> chunks(numChunks);
  // The caller may have moved points (or relabelled them) since the last call.
  const auto refresh = [&](int first, int last) {
    for (int l = first; l < last; ++l)
    {
      const int v = this->Original[l];
      this->LocalPoints[l] = m.Points[v];
      this->LocalLabels[l] = m.Labels[v];
    }
  };
  if (numThreads <= 1 || total < 256)
  {
    refresh(0, n);
    for (int sweep = 0; sweep < maxSweeps;)
    {
      for (int k = 0; k < total; ++k)
      {
        this->UpdateVertex(this->WorkVertices[k]);
      }
      for (int c = 0; c < numChunks; ++c)
      {
        this->ChunkStatistics(c, chunks[c]);
      }
      ++sweep;
      if (!afterSweep(this->CombineStatistics(chunks)) || sweep == maxSweeps)
      {
        this->CopyOut(0, n);
        return sweep;
      }
    }
  }

  // One parallel region for all the sweeps: VTK 9.2's STDThread backend starts its
  // threads on every For, which costs about as much as a quarter of a sweep of 12 288
  // triangles. The region is a sequence of steps: the copy of the mesh into the local
  // layout, then per sweep one step per colour and one for the statistics, and last the
  // copy of the results back to the mesh. Each step
  // is cut into blocks, `perThread` consecutive ones per thread (its region): thread t
  // first takes the blocks of its own region (the same part of the surface in every
  // step and sweep, so its points stay in its cache), then blocks left in the other
  // regions, then waits for the step to finish. A thread waits only for blocks a
  // running thread has taken, so this cannot deadlock even if the backend ran the jobs
  // one after another, and the share of a thread descheduled on a busy machine is
  // taken over. Counters live on their own cache lines: a thread touches another's
  // only to take over its work or to see whether the step is done.
  constexpr int perThread = 8;
  const int blocks = numThreads * perThread;
  const int stepsPerSweep = numColors + 1;
  struct alignas(64) ThreadSlot
  {
    std::atomic<long long> Next{ 0 };     ///< blocks of this region taken, over all steps
    std::atomic<long long> Finished{ 0 }; ///< blocks this thread completed, over all steps
  };
  std::unique_ptr<ThreadSlot[]> slots(new ThreadSlot[numThreads]);
  alignas(64) std::atomic<long long> statisticsBlocks{ 0 };
  std::atomic<bool> stop{ false };
  int sweepsDone = 0; // written by the thread that completes a sweep's statistics

  // Runs block b of a step; returns false if the block's completion was already
  // counted (the last statistics block, which counts only after the callback).
  const auto runBlock = [&](long long step, int b, ThreadSlot& mine, bool copyOut) {
    if (copyOut)
    {
      this->CopyOut(static_cast<int>(static_cast<long long>(n) * b / blocks),
        static_cast<int>(static_cast<long long>(n) * (b + 1) / blocks));
      return true;
    }
    if (step == 0)
    {
      refresh(static_cast<int>(static_cast<long long>(n) * b / blocks),
        static_cast<int>(static_cast<long long>(n) * (b + 1) / blocks));
      return true;
    }
    const int phase = static_cast<int>((step - 1) % stepsPerSweep);
    if (phase == numColors)
    {
      for (int c = static_cast<int>(static_cast<long long>(numChunks) * b / blocks);
           c < static_cast<long long>(numChunks) * (b + 1) / blocks; ++c)
      {
        this->ChunkStatistics(c, chunks[c]);
      }
      const long long sweepIndex = (step - 1) / stepsPerSweep;
      if (statisticsBlocks.fetch_add(1, std::memory_order_acq_rel) + 1 == (sweepIndex + 1) * blocks)
      {
        // Every chunk is summed: combine, report, then let the others go on.
        ++sweepsDone;
        if (!afterSweep(this->CombineStatistics(chunks)) || sweepsDone >= maxSweeps)
        {
          stop.store(true, std::memory_order_relaxed);
        }
        mine.Finished.fetch_add(1, std::memory_order_release);
        return false;
      }
      return true;
    }
    const int cBegin = this->WorkOffsets[phase];
    const long long size = this->WorkOffsets[phase + 1] - cBegin;
    const int first = cBegin + static_cast<int>(size * b / blocks);
    const int last = cBegin + static_cast<int>(size * (b + 1) / blocks);
    for (int k = first; k < last; ++k)
    {
      this->UpdateVertex(this->WorkVertices[k]);
    }
    return true;
  };
  const auto take = [&](int region, long long step) {
    ThreadSlot& slot = slots[region];
    long long k = slot.Next.load(std::memory_order_relaxed);
    while (k < (step + 1) * perThread)
    {
      if (slot.Next.compare_exchange_weak(k, k + 1, std::memory_order_acquire))
      {
        return region * perThread + static_cast<int>(k - step * perThread);
      }
    }
    return -1;
  };
  const auto worker = [&](vtkIdType jobBegin, vtkIdType jobEnd) {
    for (vtkIdType job = jobBegin; job < jobEnd; ++job)
    {
      const int t = static_cast<int>(job);
      ThreadSlot& mine = slots[t];
      bool copyOut = false; // the last step: write the results back to the mesh
      for (long long step = 0;; ++step)
      {
        for (int r = 0; r < numThreads; ++r)
        {
          const int region = (t + r) % numThreads;
          for (int b = take(region, step); b >= 0; b = take(region, step))
          {
            if (runBlock(step, b, mine, copyOut))
            {
              mine.Finished.fetch_add(1, std::memory_order_release);
            }
          }
        }
        if (copyOut)
        {
          break; // the For returns when every block is done
        }
        const long long target = (step + 1) * blocks;
        int spins = 0;
        for (;;)
        {
          long long finished = 0;
          for (int r = 0; r < numThreads; ++r)
          {
            finished += slots[r].Finished.load(std::memory_order_acquire);
          }
          if (finished >= target)
          {
            break;
          }
          WaitPause(spins);
        }
        copyOut = step > 0 && (step - 1) % stepsPerSweep == numColors && stop.load(std::memory_order_relaxed);
      }
    }
  };
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ numThreads, "STDThread", false },
    [&]() { vtkSMPTools::For(0, numThreads, 1, worker); });
  return sweepsDone;
}
} // namespace dsurf
