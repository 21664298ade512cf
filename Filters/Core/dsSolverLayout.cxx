// SPDX-License-Identifier: BSD-3-Clause
// What Solver's sweeps run on, made once per mesh: the docs/METHOD.md §6.4 weights of each vertex's
// ring, the greedy distance-2 colouring (vertices of one colour move independently, so a sweep
// gives the same result for any number of threads) and the breadth-first local copy of the
// mesh the sweeps read and write.
#include "dsSolver.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <vector>

namespace dsurf
{
void Solver::SetMesh(TriangleMesh* mesh)
{
  this->Mesh = mesh;
  this->BuildColoring();
}

namespace
{
/// The normalised weights vertex v gives its ring, into w[NeighborOffsets[v] ..
/// NeighborOffsets[v+1]): the docs/METHOD.md §6.4 table, applied per green. The paper's table
/// (Lürig, Kobbelt and Ertl 2000, the adaptive multilevel solver) is stated for one green
/// pair: the row is the updated vertex's role in it, the column its neighbour's. So an edge
/// of a green half takes the roles of its ends in that green (averaged when both triangles
/// on the edge are greens), and a vertex that is C of one green and D of another still gives
/// the second green's M weight 0. Any other edge joins v to a vertex whose roles belong to
/// greens without this edge: v's row (its label) with column N. (One label per vertex would
/// give an M next to another green's M weight 0 where a single refined triangle meets three
/// greens: the flat sheet of TestHierarchyScatter folds then.) Without CornerLabels (labels
/// set by hand) the table applies to the vertex labels. Uniform when the weights sum to
/// zero.
/// `greens` is scratch space (the number of greens on each edge of v).
void RingWeights(const TriangleMesh& m, int v, double* w, std::vector<int>& greens)
{
  const int begin = m.NeighborOffsets[v], end = m.NeighborOffsets[v + 1];
  const int* ring = m.Neighbors.data();
  const bool perGreen = m.CornerLabels.size() == m.Triangles.size();
  greens.assign(end - begin, 0);
  std::fill(w + begin, w + end, 0.0);
  for (int i = m.VertexTriangleOffsets[v]; i < m.VertexTriangleOffsets[v + 1] && perGreen; ++i)
  {
    const int t = m.VertexTriangles[i];
    const auto& tri = m.Triangles[t];
    const int c = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
    if (m.CornerLabels[t][c] == LabelN)
    {
      continue; // not a green half
    }
    for (int k = 1; k <= 2; ++k)
    {
      const int slot =
        static_cast<int>(std::lower_bound(ring + begin, ring + end, tri[(c + k) % 3]) - ring);
      w[slot] += UmbrellaWeight(m.CornerLabels[t][c], m.CornerLabels[t][(c + k) % 3]);
      ++greens[slot - begin];
    }
  }
  // The deepest neighbour: v's edges to it are its finest (docs/METHOD.md §6.4). Depth, not the
  // step that made a point: a coarse triangle split late makes coarse edges in a late step.
  const std::vector<int>& depth = m.Depths.size() == m.Points.size() ? m.Depths : m.Levels;
  int finest = 0;
  for (int i = begin; i < end; ++i)
  {
    finest = std::max(finest, depth[m.Neighbors[i]]);
  }
  for (int i = begin; i < end; ++i)
  {
    const int q = m.Neighbors[i];
    const int g = greens[i - begin];
    if (g > 0)
    {
      w[i] /= g;
    }
    else if (!perGreen)
    {
      w[i] = UmbrellaWeight(m.Labels[v], m.Labels[q]);
    }
    else
    {
      // C weighs its fine side 2 and its coarse side 1 (its D); an edge of no green on the
      // coarse side (where a refined region's border turns a corner) is coarse too.
      const bool coarse = m.Labels[v] == LabelC && depth[q] < finest;
      w[i] = UmbrellaWeight(m.Labels[v], coarse ? LabelD : LabelN);
    }
  }
  double sum = 0;
  for (int i = begin; i < end; ++i)
  {
    sum += w[i];
  }
  const double invW = sum > 0 ? 1.0 / sum : 1.0 / (end - begin);
  for (int i = begin; i < end; ++i)
  {
    w[i] = sum > 0 ? w[i] * invW : invW;
  }
}

/// Greedy distance-2 colouring in vertex order (deterministic): a vertex takes the
/// smallest colour not used within two edges, so vertices of one colour neither
/// share an edge nor appear in each other's U^2 stencil or normal fan. Returns the
/// number of colours.
int ColorAtDistanceTwo(const TriangleMesh& m, std::vector<int>& color)
{
  const int n = m.NumberOfPoints();
  color.assign(n, -1);
  std::vector<int> stamp; // stamp[c] == v: colour c is forbidden for v
  int numColors = 0;
  for (int v = 0; v < n; ++v)
  {
    auto forbid = [&](int u)
    {
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
  return numColors;
}

/// Each weight's index into `values`, its distinct values (told apart by their bits, so the
/// lookup gives back each weight exactly).
void IndexWeights(
  const std::vector<double>& weights, std::vector<std::uint32_t>& ids, std::vector<double>& values)
{
  std::map<std::uint64_t, std::uint32_t> index;
  ids.resize(weights.size());
  values.clear();
  for (std::size_t i = 0; i < weights.size(); ++i)
  {
    std::uint64_t bits;
    std::memcpy(&bits, &weights[i], sizeof bits);
    const auto inserted = index.try_emplace(bits, static_cast<std::uint32_t>(values.size()));
    if (inserted.second)
    {
      values.push_back(weights[i]);
    }
    ids[i] = inserted.first->second;
  }
}

/// Whether vertex v moves in a sweep: not on an open boundary, not isolated.
bool Moves(const TriangleMesh& m, int v)
{
  return !m.BoundaryVertex[v] && m.NeighborOffsets[v + 1] > m.NeighborOffsets[v];
}
} // namespace

void Solver::BuildColoring()
{
  this->Colors = ColorClasses();
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
  this->UniformWeights =
    std::all_of(m.Labels.begin(), m.Labels.end(), [](unsigned char l) { return l == LabelN; });
  this->WeightIds.clear();
  this->WeightValues.clear();
  if (!this->UniformWeights)
  {
    std::vector<double> weights(m.Neighbors.size());
    std::vector<int> greens;
    for (int v = 0; v < n; ++v)
    {
      RingWeights(m, v, weights.data(), greens);
    }
    IndexWeights(weights, this->WeightIds, this->WeightValues);
  }
  std::vector<int> color;
  const int numColors = ColorAtDistanceTwo(m, color);

  // Colour classes of the vertices that move (CSR, ascending ids within a class).
  std::vector<int> counts(numColors + 1, 0);
  for (int v = 0; v < n; ++v)
  {
    if (Moves(m, v))
    {
      ++counts[color[v] + 1];
    }
  }
  for (int c = 0; c < numColors; ++c)
  {
    counts[c + 1] += counts[c];
  }
  this->Colors.Offsets = counts;
  this->Colors.Vertices.assign(counts[numColors], -1);
  for (int v = 0; v < n; ++v)
  {
    if (Moves(m, v))
    {
      this->Colors.Vertices[counts[color[v]]++] = v;
    }
  }
  this->BuildLocalLayout();
}

void Solver::OrderBreadthFirst()
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
}

void Solver::CopyTopologyToLocal()
{
  const TriangleMesh& m = *this->Mesh;
  const int n = m.NumberOfPoints();
  // Neighbour lists and triangle fans in local ids, each in the mesh's order, so every
  // sum is evaluated in the same order as on the mesh itself.
  this->LocalNeighborOffsets.assign(n + 1, 0);
  this->LocalNeighbors.resize(m.Neighbors.size());
  this->LocalFanOffsets.assign(n + 1, 0);
  this->LocalFan.resize(m.VertexTriangles.size());
  this->LocalWeightIds.resize(this->WeightIds.size());
  this->LocalPoints.resize(n);
  for (int l = 0; l < n; ++l)
  {
    const int v = this->Original[l];
    int k = this->LocalNeighborOffsets[l];
    for (int i = m.NeighborOffsets[v]; i < m.NeighborOffsets[v + 1]; ++i)
    {
      if (!this->WeightIds.empty())
      {
        this->LocalWeightIds[k] = this->WeightIds[i];
      }
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
}

void Solver::BuildLocalColors()
{
  // The colour classes in local ids, ascending: a thread's share of a colour is a
  // contiguous run of it, hence a compact region.
  const int numColors = this->NumberOfColors();
  this->LocalColors.Offsets = this->Colors.Offsets;
  this->LocalColors.Vertices.resize(this->Colors.Vertices.size());
  for (int c = 0; c < numColors; ++c)
  {
    for (int k = this->Colors.Offsets[c]; k < this->Colors.Offsets[c + 1]; ++k)
    {
      this->LocalColors.Vertices[k] = this->Local[this->Colors.Vertices[k]];
    }
    std::sort(this->LocalColors.Vertices.begin() + this->Colors.Offsets[c],
      this->LocalColors.Vertices.begin() + this->Colors.Offsets[c + 1]);
  }
  this->ColorSlot.assign(this->Mesh->NumberOfPoints(), -1);
  for (int k = 0; k < this->Colors.Offsets.back(); ++k)
  {
    this->ColorSlot[this->LocalColors.Vertices[k]] = k;
  }
}

void Solver::BuildLocalLayout()
{
  this->OrderBreadthFirst();
  this->CopyTopologyToLocal();
  this->BuildLocalColors();
  this->RingCoefficientsMode = -1; // for the weights the next sweeps use (Sweeps)

  const int n = this->Mesh->NumberOfPoints();
  // Fixed vertices keep 0; moving ones are overwritten by every sweep.
  this->ErrorIndicatorValues.assign(n, 0.0);
  this->DisplacementValues.assign(n, 0.0);
  this->ForceValues.assign(n, 0.0);
  this->LocalResults.assign(this->Colors.Offsets.back(), VertexResult());
}
} // namespace dsurf
