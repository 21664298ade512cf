// SPDX-License-Identifier: BSD-3-Clause
#include "dsTriangleMesh.h"

#include <algorithm>
#include <unordered_map>

namespace dsurf
{
bool TriangleMesh::BuildTopology(std::string* error)
{
  const int nPts = this->NumberOfPoints();
  auto fail = [error](const std::string& msg)
  {
    if (error)
    {
      *error = msg;
    }
    return false;
  };
  if (static_cast<int>(this->Labels.size()) != nPts)
  {
    this->Labels.assign(nPts, LabelN);
  }
  if (static_cast<int>(this->Levels.size()) != nPts)
  {
    this->Levels.assign(nPts, 0);
  }

  std::string message = this->BuildVertexTriangles();
  if (message.empty())
  {
    message = this->BuildEdges();
  }
  if (!message.empty())
  {
    return fail(message);
  }
  this->BuildRings();
  return true;
}

std::string TriangleMesh::BuildVertexTriangles()
{
  const int nPts = this->NumberOfPoints();
  const int nTri = this->NumberOfTriangles();
  // Vertex -> triangles (CSR).
  this->VertexTriangleOffsets.assign(nPts + 1, 0);
  for (int t = 0; t < nTri; ++t)
  {
    const auto& tri = this->Triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] < 0 || tri[k] >= nPts)
      {
        return "triangle " + std::to_string(t) + " has a point index out of range";
      }
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
    {
      return "triangle " + std::to_string(t) + " is degenerate (a repeated vertex)";
    }
    for (int k = 0; k < 3; ++k)
    {
      ++this->VertexTriangleOffsets[tri[k] + 1];
    }
  }
  for (int v = 0; v < nPts; ++v)
  {
    this->VertexTriangleOffsets[v + 1] += this->VertexTriangleOffsets[v];
  }
  this->VertexTriangles.assign(this->VertexTriangleOffsets[nPts], -1);
  {
    std::vector<int> fill(
      this->VertexTriangleOffsets.begin(), this->VertexTriangleOffsets.end() - 1);
    for (int t = 0; t < nTri; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        this->VertexTriangles[fill[this->Triangles[t][k]]++] = t;
      }
    }
  }
  return std::string();
}

std::string TriangleMesh::BuildEdges()
{
  // Unique edges and the triangles on each side, numbered in order of first use along the
  // triangles. An edge met again is found through the earlier triangles of its end with the
  // smaller valence (no hash map: linear in the triangles for bounded valence).
  const int nTri = this->NumberOfTriangles();
  this->Edges.clear();
  this->EdgeTriangles.clear();
  this->TriangleEdges.assign(nTri, { -1, -1, -1 });
  for (int t = 0; t < nTri; ++t)
  {
    const auto& tri = this->Triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      const int a = tri[k], b = tri[(k + 1) % 3];
      int e = this->EdgeBefore(a, b, t);
      if (e < 0)
      {
        e = static_cast<int>(this->Edges.size());
        this->Edges.push_back({ std::min(a, b), std::max(a, b) });
        this->EdgeTriangles.push_back({ t, -1 });
      }
      else
      {
        auto& et = this->EdgeTriangles[e];
        if (et[1] != -1)
        {
          return "non-manifold edge (" + std::to_string(a) + ", " + std::to_string(b) +
            ") is shared by three or more triangles";
        }
        et[1] = t;
      }
      this->TriangleEdges[t][k] = e;
    }
  }
  return std::string();
}

int TriangleMesh::EdgeBefore(int a, int b, int before) const
{
  const int* offsets = this->VertexTriangleOffsets.data();
  const int v = offsets[a + 1] - offsets[a] <= offsets[b + 1] - offsets[b] ? a : b;
  for (int i = offsets[v]; i < offsets[v + 1]; ++i)
  {
    const int t = this->VertexTriangles[i]; // ascending
    if (t >= before)
    {
      break;
    }
    const auto& tri = this->Triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      const int p = tri[k], q = tri[(k + 1) % 3];
      if ((p == a && q == b) || (p == b && q == a))
      {
        return this->TriangleEdges[t][k];
      }
    }
  }
  return -1;
}

void TriangleMesh::BuildRings()
{
  const int nPts = this->NumberOfPoints();
  // One-rings (CSR, each sorted) and boundary flags.
  this->BoundaryVertex.assign(nPts, 0);
  this->NeighborOffsets.assign(nPts + 1, 0);
  for (size_t e = 0; e < this->Edges.size(); ++e)
  {
    const int a = this->Edges[e][0], b = this->Edges[e][1];
    ++this->NeighborOffsets[a + 1];
    ++this->NeighborOffsets[b + 1];
    if (this->EdgeTriangles[e][1] == -1)
    {
      this->BoundaryVertex[a] = this->BoundaryVertex[b] = 1;
    }
  }
  for (int v = 0; v < nPts; ++v)
  {
    this->NeighborOffsets[v + 1] += this->NeighborOffsets[v];
  }
  this->Neighbors.resize(this->NeighborOffsets[nPts]);
  std::vector<int> fill(this->NeighborOffsets.begin(), this->NeighborOffsets.end() - 1);
  for (const auto& edge : this->Edges)
  {
    this->Neighbors[fill[edge[0]]++] = edge[1];
    this->Neighbors[fill[edge[1]]++] = edge[0];
  }
  for (int v = 0; v < nPts; ++v)
  {
    std::sort(this->Neighbors.begin() + this->NeighborOffsets[v],
      this->Neighbors.begin() + this->NeighborOffsets[v + 1]);
  }
}

int TriangleMesh::FindEdge(int a, int b) const
{
  const int n = static_cast<int>(this->VertexTriangleOffsets.size()) - 1;
  if (a < 0 || b < 0 || a >= n || b >= n || this->TriangleEdges.size() != this->Triangles.size())
  {
    return -1;
  }
  return this->EdgeBefore(a, b, this->NumberOfTriangles());
}

bool TriangleMesh::IsClosed() const
{
  for (const auto& et : this->EdgeTriangles)
  {
    if (et[1] == -1)
    {
      return false;
    }
  }
  return true;
}

bool TriangleMesh::IsConsistentlyOriented() const
{
  for (size_t e = 0; e < this->Edges.size(); ++e)
  {
    const auto& et = this->EdgeTriangles[e];
    if (et[1] == -1)
    {
      continue;
    }
    // Direction in which each triangle traverses the edge: +1 when a -> b.
    int dir[2];
    for (int s = 0; s < 2; ++s)
    {
      const auto& tri = this->Triangles[et[s]];
      dir[s] = 0;
      for (int k = 0; k < 3; ++k)
      {
        if (tri[k] == this->Edges[e][0] && tri[(k + 1) % 3] == this->Edges[e][1])
        {
          dir[s] = 1;
        }
        else if (tri[k] == this->Edges[e][1] && tri[(k + 1) % 3] == this->Edges[e][0])
        {
          dir[s] = -1;
        }
      }
    }
    if (dir[0] == dir[1])
    {
      return false;
    }
  }
  return true;
}

int TriangleMesh::OrientConsistently()
{
  const int nTri = this->NumberOfTriangles();
  // +1 when triangle t traverses edge e from Edges[e][0] to Edges[e][1].
  auto direction = [this](int t, int e)
  {
    const auto& tri = this->Triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] == this->Edges[e][0] && tri[(k + 1) % 3] == this->Edges[e][1])
      {
        return 1;
      }
    }
    return -1;
  };
  std::vector<signed char> flip(nTri, -1); // -1 unvisited, 0 keep, 1 flip
  std::vector<int> piece, queue;
  int flipped = 0;
  for (int seed = 0; seed < nTri; ++seed)
  {
    if (flip[seed] != -1)
    {
      continue;
    }
    piece.clear();
    queue.assign(1, seed);
    flip[seed] = 0;
    for (size_t head = 0; head < queue.size(); ++head)
    {
      const int t = queue[head];
      piece.push_back(t);
      for (int k = 0; k < 3; ++k)
      {
        const int e = this->TriangleEdges[t][k];
        const int other =
          this->EdgeTriangles[e][0] == t ? this->EdgeTriangles[e][1] : this->EdgeTriangles[e][0];
        if (other < 0 || flip[other] != -1)
        {
          continue;
        }
        // After the flips, the two must traverse e in opposite directions.
        const bool same = direction(t, e) == direction(other, e);
        flip[other] = static_cast<signed char>(flip[t] ^ (same ? 1 : 0));
        queue.push_back(other);
      }
    }
    int count = 0;
    for (int t : piece)
    {
      count += flip[t];
    }
    const bool invert = 2 * count > static_cast<int>(piece.size()); // keep the majority
    for (int t : piece)
    {
      if ((flip[t] != 0) != invert)
      {
        std::swap(this->Triangles[t][1], this->Triangles[t][2]);
        ++flipped;
      }
    }
  }
  if (flipped > 0)
  {
    this->BuildTopology(nullptr);
  }
  return flipped;
}

int TriangleMesh::OrientPiecesOutward()
{
  // Pieces = triangles connected across edges; each closed piece with a negative signed
  // volume is turned inside out.
  const int nTri = this->NumberOfTriangles();
  std::vector<int> piece(nTri, -1), queue;
  std::vector<double> volume;
  std::vector<char> closed;
  for (int seed = 0; seed < nTri; ++seed)
  {
    if (piece[seed] >= 0)
    {
      continue;
    }
    const int id = static_cast<int>(volume.size());
    volume.push_back(0.0);
    closed.push_back(1);
    queue.assign(1, seed);
    piece[seed] = id;
    for (size_t head = 0; head < queue.size(); ++head)
    {
      const int t = queue[head];
      const auto& tri = this->Triangles[t];
      volume[id] += Dot(this->Points[tri[0]], Cross(this->Points[tri[1]], this->Points[tri[2]]));
      for (int e : this->TriangleEdges[t])
      {
        const int other =
          this->EdgeTriangles[e][0] == t ? this->EdgeTriangles[e][1] : this->EdgeTriangles[e][0];
        if (other < 0)
        {
          closed[id] = 0;
        }
        else if (piece[other] < 0)
        {
          piece[other] = id;
          queue.push_back(other);
        }
      }
    }
  }
  int flipped = 0;
  for (int t = 0; t < nTri; ++t)
  {
    if (closed[piece[t]] && volume[piece[t]] < 0)
    {
      std::swap(this->Triangles[t][1], this->Triangles[t][2]);
      ++flipped;
    }
  }
  if (flipped > 0)
  {
    this->BuildTopology(nullptr);
  }
  return flipped;
}

int TriangleMesh::CountNonManifoldVertices() const
{
  // Walk each vertex's triangles across shared edges; more than one connected
  // fan means two sheets touch at the vertex.
  int count = 0;
  std::vector<int> seen;
  for (int v = 0; v < this->NumberOfPoints(); ++v)
  {
    const int begin = this->VertexTriangleOffsets[v], end = this->VertexTriangleOffsets[v + 1];
    if (end - begin == 0)
    {
      continue;
    }
    seen.assign(end - begin, 0);
    std::vector<int> stack{ 0 };
    seen[0] = 1;
    int reached = 1;
    while (!stack.empty())
    {
      const int i = stack.back();
      stack.pop_back();
      const int t = this->VertexTriangles[begin + i];
      for (int k = 0; k < 3; ++k)
      {
        const int e = this->TriangleEdges[t][k];
        if (this->Edges[e][0] != v && this->Edges[e][1] != v)
        {
          continue;
        }
        for (int s = 0; s < 2; ++s)
        {
          const int other = this->EdgeTriangles[e][s];
          if (other < 0 || other == t)
          {
            continue;
          }
          for (int j = 0; j < end - begin; ++j)
          {
            if (!seen[j] && this->VertexTriangles[begin + j] == other)
            {
              seen[j] = 1;
              ++reached;
              stack.push_back(j);
            }
          }
        }
      }
    }
    if (reached != end - begin)
    {
      ++count;
    }
  }
  return count;
}

double TriangleMesh::SignedVolume() const
{
  double vol = 0.0;
  for (const auto& tri : this->Triangles)
  {
    vol += Dot(this->Points[tri[0]], Cross(this->Points[tri[1]], this->Points[tri[2]]));
  }
  return vol / 6.0;
}

int TriangleMesh::NumberOfObjects() const
{
  return this->Objects.empty() ? 1
                               : 1 + *std::max_element(this->Objects.begin(), this->Objects.end());
}

void TriangleMesh::ExtendObjects()
{
  const int n = this->NumberOfPoints();
  if (this->Objects.empty() || static_cast<int>(this->Objects.size()) >= n)
  {
    return;
  }
  // Breadth first from the points that have an object: a new point is joined by edges to the
  // points of its component only.
  std::vector<int> queue;
  for (int v = 0; v < static_cast<int>(this->Objects.size()); ++v)
  {
    queue.push_back(v);
  }
  this->Objects.resize(n, -1);
  for (std::size_t q = 0; q < queue.size(); ++q)
  {
    const int v = queue[q];
    for (int i = this->NeighborOffsets[v]; i < this->NeighborOffsets[v + 1]; ++i)
    {
      const int w = this->Neighbors[i];
      if (this->Objects[w] < 0)
      {
        this->Objects[w] = this->Objects[v];
        queue.push_back(w);
      }
    }
  }
  std::replace(this->Objects.begin(), this->Objects.end(), -1, 0); // isolated points
}

double TriangleMesh::MeanEdgeLength() const
{
  if (this->Edges.empty())
  {
    return 0.0;
  }
  double sum = 0.0;
  for (const auto& e : this->Edges)
  {
    sum += Norm(this->Points[e[1]] - this->Points[e[0]]);
  }
  return sum / static_cast<double>(this->Edges.size());
}

Vec3 TriangleMesh::AreaWeightedNormal(int v) const
{
  const int first = this->VertexTriangleOffsets[v];
  return dsurf::AreaWeightedNormal(this->Points.data(), this->VertexTriangleOffsets[v + 1] - first,
    [this, first](int i) -> const std::array<int, 3>&
    { return this->Triangles[this->VertexTriangles[first + i]]; });
}

double TriangleMesh::MinAngleDegrees(int t) const
{
  const auto& tri = this->Triangles[t];
  double minAngle = 180.0;
  for (int k = 0; k < 3; ++k)
  {
    const Vec3 a = this->Points[tri[(k + 1) % 3]] - this->Points[tri[k]];
    const Vec3 b = this->Points[tri[(k + 2) % 3]] - this->Points[tri[k]];
    const double na = Norm(a), nb = Norm(b);
    if (na <= 0 || nb <= 0)
    {
      return 0.0;
    }
    const double c = std::max(-1.0, std::min(1.0, Dot(a, b) / (na * nb)));
    minAngle = std::min(minAngle, std::acos(c) * 180.0 / 3.14159265358979323846);
  }
  return minAngle;
}

bool TriangleMesh::SubdivideUniformly(std::string* error)
{
  if (this->TriangleEdges.size() != this->Triangles.size() && !this->BuildTopology(error))
  {
    return false;
  }
  // Edge ids number the midpoints: each edge is split once, whichever triangle meets it first.
  const int nPts = this->NumberOfPoints();
  this->Points.reserve(this->Points.size() + this->Edges.size());
  for (const auto& e : this->Edges)
  {
    const Vec3 midpoint = 0.5 * (this->Points[e[0]] + this->Points[e[1]]);
    this->Points.push_back(midpoint);
  }
  std::vector<std::array<int, 3>> finer;
  finer.reserve(4 * this->Triangles.size());
  for (std::size_t t = 0; t < this->Triangles.size(); ++t)
  {
    const std::array<int, 3>& edges = this->TriangleEdges[t];
    const int m[3] = { nPts + edges[0], nPts + edges[1], nPts + edges[2] };
    std::array<int, 3> children[4];
    SplitInFour(this->Triangles[t], m, children);
    finer.insert(finer.end(), children, children + 4);
  }
  this->Triangles.swap(finer);
  this->Labels.assign(this->Points.size(), LabelN);
  this->Levels.assign(this->Points.size(), 0);
  return this->BuildTopology(error);
}
namespace
{
/// Bisects triangle t at the midpoint (from `midpoints`) of its longest edge found there, and
/// each half again at its own, until no edge of a piece is in `midpoints`: the conforming
/// split of a triangle whose neighbours split the same edges.
void BisectAtSplitEdges(const std::array<int, 3>& t, const std::vector<Vec3>& points,
  const std::unordered_map<unsigned long long, int>& midpoints,
  std::vector<std::array<int, 3>>& out)
{
  int longest = -1;
  double length = -1;
  for (int k = 0; k < 3; ++k)
  {
    const int a = t[k], b = t[(k + 1) % 3];
    const double l = Norm(points[b] - points[a]);
    if (midpoints.count(EdgeKey(a, b)) && l > length)
    {
      longest = k;
      length = l;
    }
  }
  if (longest < 0)
  {
    out.push_back(t);
    return;
  }
  const int a = t[longest], b = t[(longest + 1) % 3], c = t[(longest + 2) % 3];
  const int m = midpoints.at(EdgeKey(a, b));
  BisectAtSplitEdges({ a, m, c }, points, midpoints, out);
  BisectAtSplitEdges({ m, b, c }, points, midpoints, out);
}

/// The edges longer than `minLength` and twice the shortest edge of a triangle they border.
std::vector<int> ElongatedEdges(const TriangleMesh& m, double minLength)
{
  std::vector<double> shortest(m.Triangles.size());
  for (std::size_t t = 0; t < m.Triangles.size(); ++t)
  {
    const auto& v = m.Triangles[t];
    shortest[t] = std::min({ Norm(m.Points[v[1]] - m.Points[v[0]]),
      Norm(m.Points[v[2]] - m.Points[v[1]]), Norm(m.Points[v[0]] - m.Points[v[2]]) });
  }
  std::vector<int> edges;
  for (std::size_t e = 0; e < m.Edges.size(); ++e)
  {
    const auto& ends = m.Edges[e];
    const double l = Norm(m.Points[ends[1]] - m.Points[ends[0]]);
    double reference = l;
    for (int t : m.EdgeTriangles[e])
    {
      reference = t >= 0 ? std::min(reference, shortest[t]) : reference;
    }
    if (l > minLength && l > 2.0 * reference)
    {
      edges.push_back(static_cast<int>(e));
    }
  }
  return edges;
}
} // namespace

int TriangleMesh::SplitElongatedEdges(double minLength, long long maxPoints, std::string* error)
{
  int split = 0;
  for (int round = 0; round < 16; ++round) // each round halves the long edges: a bound
  {
    if (this->TriangleEdges.size() != this->Triangles.size() && !this->BuildTopology(error))
    {
      return -1;
    }
    const std::vector<int> edges = ElongatedEdges(*this, minLength);
    if (edges.empty() || static_cast<long long>(this->Points.size() + edges.size()) > maxPoints)
    {
      break;
    }
    std::unordered_map<unsigned long long, int> midpoints;
    for (int e : edges)
    {
      const auto& ends = this->Edges[e];
      midpoints[EdgeKey(ends[0], ends[1])] = this->NumberOfPoints();
      this->Points.push_back(0.5 * (this->Points[ends[0]] + this->Points[ends[1]]));
    }
    split += static_cast<int>(edges.size());
    std::vector<std::array<int, 3>> finer;
    for (const auto& t : this->Triangles)
    {
      BisectAtSplitEdges(t, this->Points, midpoints, finer);
    }
    this->Triangles.swap(finer);
    this->Labels.assign(this->Points.size(), LabelN);
    this->Levels.assign(this->Points.size(), 0);
    if (!this->BuildTopology(error))
    {
      return -1;
    }
  }
  return split;
}
} // namespace dsurf
