#include "dsSolver.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <thread>

namespace dsurf
{
namespace
{
/// Weight sum of vertex v and the normalised weight it gives neighbour slot i.
/// Uniform fallback when the label weights of v sum to zero (an M vertex whose only
/// neighbours are M cannot occur in a valid red-green mesh, but must not divide by 0).
struct RingWeights
{
  double InvW = 0;   ///< 1 / sum of weights
  bool Uniform = true;
};

template <bool AllN>
inline RingWeights ComputeRingWeights(const TriangleMesh& m, int v)
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
inline double SlotWeight(const TriangleMesh& m, int v, int q, const RingWeights& rw)
{
  if (AllN || rw.Uniform)
  {
    return rw.InvW;
  }
  return UmbrellaWeight(m.Labels[v], m.Labels[q]) * rw.InvW;
}

/// U(v) and the normalised weight that v gives the vertex `other` (0 if not a neighbour).
template <bool AllN>
inline Vec3 UmbrellaOf(const TriangleMesh& m, int v, int other, double* weightOfOther)
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

int ResolveThreads(int requested)
{
  if (requested > 0)
  {
    return requested;
  }
  const unsigned hc = std::thread::hardware_concurrency();
  return hc > 0 ? static_cast<int>(hc) : 1;
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
}

Vec3 Solver::Umbrella(int v) const
{
  double unused = 0;
  if (this->Mesh->NeighborOffsets[v + 1] == this->Mesh->NeighborOffsets[v])
  {
    return { 0, 0, 0 };
  }
  return UmbrellaOf<false>(*this->Mesh, v, -1, &unused);
}

void Solver::UpdateVertex(int v)
{
  TriangleMesh& m = *this->Mesh;
  const int begin = m.NeighborOffsets[v], end = m.NeighborOffsets[v + 1];
  const double tau = this->Parameters.Tau, gamma = this->Parameters.Gamma;

  // U(p), U^2(p) and alpha (SPEC §3 with the §6.4 weights).
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

  // External force and the SPEC §5 rule: along the umbrella when F points the same
  // way, otherwise along the normal; the projection keeps F from sliding vertices
  // tangentially over each other.
  Vec3 force{ 0, 0, 0 };
  Vec3 applied{ 0, 0, 0 };
  this->OutsideFlags[v] = 0;
  if (this->Field && this->Sampler)
  {
    double f[3] = { 0, 0, 0 };
    if (this->Sampler(this->Field, m.Points[v].data(), f))
    {
      force = { this->ForceScale * f[0], this->ForceScale * f[1], this->ForceScale * f[2] };
    }
    else
    {
      this->OutsideFlags[v] = 1;
    }
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
        const Vec3 nrm = m.AreaWeightedNormal(v);
        const double nn = Dot(nrm, nrm);
        if (nn > 0)
        {
          applied = (Dot(force, nrm) / nn) * nrm;
        }
      }
    }
  }

  const Vec3 c = gamma * (internal + applied);
  m.Points[v] = m.Points[v] + c;
  this->ErrorIndicatorValues[v] = gamma * Norm(internal);
  this->DisplacementValues[v] = Norm(c);
  this->ForceValues[v] = Norm(force);
}

SweepStatistics Solver::Sweep()
{
  SweepStatistics stats;
  if (!this->Mesh)
  {
    return stats;
  }
  TriangleMesh& m = *this->Mesh;
  const int n = m.NumberOfPoints();
  if (static_cast<int>(m.NeighborOffsets.size()) != n + 1)
  {
    return stats; // no topology: nothing can move
  }
  if (this->ColoredPoints != n)
  {
    this->BuildColoring();
  }
  this->ErrorIndicatorValues.assign(n, 0.0);
  this->DisplacementValues.assign(n, 0.0);
  this->ForceValues.assign(n, 0.0);
  this->OutsideFlags.assign(n, 0);

  const int numColors = this->NumberOfColors();
  const int numThreads = ResolveThreads(this->Parameters.NumberOfThreads);
  const int total = this->ClassOffsets.back();
  if (numThreads <= 1 || total < 256)
  {
    for (int k = 0; k < total; ++k)
    {
      this->UpdateVertex(this->ClassVertices[k]);
    }
  }
  else
  {
    // One parallel region per sweep (thread start-up is the dominant cost of a
    // vtkSMPTools::For with STDThread, and there are ~10-20 colours). Workers claim
    // chunks of the current colour; a worker moves to the next colour only when every
    // chunk of this one is done. A worker waits only for chunks being processed by a
    // running worker, so this cannot deadlock even if the backend ran the jobs one
    // after another.
    constexpr int chunk = 32;
    std::vector<int> chunkOffsets(numColors + 1, 0);
    for (int c = 0; c < numColors; ++c)
    {
      const int size = this->ClassOffsets[c + 1] - this->ClassOffsets[c];
      chunkOffsets[c + 1] = chunkOffsets[c] + (size + chunk - 1) / chunk;
    }
    const int totalChunks = chunkOffsets[numColors];
    std::atomic<int> nextChunk{ 0 };
    std::vector<std::atomic<int>> done(numColors);
    for (auto& d : done)
    {
      d.store(0, std::memory_order_relaxed);
    }
    auto worker = [&](vtkIdType, vtkIdType) {
      int color = 0;
      int complete = 0; // colours [0, complete) are known to be finished
      for (;;)
      {
        const int k = nextChunk.fetch_add(1, std::memory_order_relaxed);
        if (k >= totalChunks)
        {
          return;
        }
        while (k >= chunkOffsets[color + 1])
        {
          ++color;
        }
        // Chunks are claimed in order, so chunk k's colour is never earlier than any
        // chunk this worker did before; wait until the previous colour is complete.
        for (; complete < color; ++complete)
        {
          const int need = chunkOffsets[complete + 1] - chunkOffsets[complete];
          while (done[complete].load(std::memory_order_acquire) < need)
          {
            std::this_thread::yield();
          }
        }
        const int cBegin = this->ClassOffsets[color];
        const int cEnd = this->ClassOffsets[color + 1];
        const int first = cBegin + (k - chunkOffsets[color]) * chunk;
        const int last = std::min(first + chunk, cEnd);
        for (int i = first; i < last; ++i)
        {
          this->UpdateVertex(this->ClassVertices[i]);
        }
        done[color].fetch_add(1, std::memory_order_acq_rel);
      }
    };
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ numThreads, "STDThread", false },
      [&]() { vtkSMPTools::For(0, numThreads, 1, worker); });
  }

  // Serial reduction in vertex order: identical for any thread count.
  double sum = 0, maxC = 0;
  for (int k = 0; k < total; ++k)
  {
    const int v = this->ClassVertices[k];
    const double d = this->DisplacementValues[v];
    sum += d;
    maxC = std::max(maxC, d);
    stats.OutsideVertices += this->OutsideFlags[v];
  }
  stats.MovedVertices = total;
  stats.MeanCorrection = total > 0 ? sum / total : 0.0;
  stats.MaxCorrection = maxC;
  return stats;
}
} // namespace dsurf
