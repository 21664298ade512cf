#include "dsRedGreen.h"

#include <algorithm>
#include <deque>

namespace dsurf
{
namespace
{
/// A triangle of the base mesh (greens merged into their parents) during one step.
struct BaseTriangle
{
  std::array<int, 3> V;
  bool Alive = true;
  int OldGreen = -1; ///< index of the green pair this base triangle merges, -1 otherwise
};
} // namespace

bool RedGreenRefiner::Initialize(TriangleMesh& mesh, std::string* error)
{
  this->Greens.clear();
  this->Midpoints.clear();
  this->Level = 0;
  mesh.Labels.assign(mesh.Points.size(), LabelN);
  mesh.Levels.assign(mesh.Points.size(), 0);
  if (!mesh.BuildTopology(error))
  {
    this->ExpectedPoints = this->ExpectedTriangles = -1;
    return false;
  }
  if (mesh.CountNonManifoldVertices() != 0)
  {
    if (error)
    {
      *error = "the mesh has non-manifold (pinched) vertices";
    }
    this->ExpectedPoints = this->ExpectedTriangles = -1;
    return false;
  }
  this->TriangleGreen.assign(mesh.Triangles.size(), -1);
  this->ParentEdge.assign(mesh.Points.size(), { -1, -1 });
  this->ExpectedPoints = mesh.NumberOfPoints();
  this->ExpectedTriangles = mesh.NumberOfTriangles();
  return true;
}

std::vector<char> RedGreenRefiner::GreenFlags() const
{
  std::vector<char> flags(this->TriangleGreen.size(), 0);
  for (size_t t = 0; t < flags.size(); ++t)
  {
    flags[t] = this->TriangleGreen[t] >= 0 ? 1 : 0;
  }
  return flags;
}

int RedGreenRefiner::CountTVertices(const TriangleMesh& mesh) const
{
  int count = 0;
  for (const auto& e : mesh.Edges)
  {
    count += this->Midpoints.count(EdgeKey(e[0], e[1])) ? 1 : 0;
  }
  return count;
}

std::vector<unsigned char> RedGreenRefiner::ExpectedLabels(int numberOfPoints) const
{
  // Priority M > C > D > N (see the class comment): rank by a number and keep the max.
  static const int rank[4] = { 0, 2, 3, 1 }; // N, C, M, D
  std::vector<unsigned char> labels(numberOfPoints, LabelN);
  auto put = [&](int v, unsigned char label) {
    if (v >= 0 && v < numberOfPoints && rank[label] > rank[labels[v]])
    {
      labels[v] = label;
    }
  };
  for (const auto& g : this->Greens)
  {
    put(g.Midpoint, LabelM);
    put(g.Parent[g.SplitCorner], LabelC);
    put(g.Parent[(g.SplitCorner + 1) % 3], LabelC);
    put(g.Parent[(g.SplitCorner + 2) % 3], LabelD);
  }
  return labels;
}

RefinementCounts RedGreenRefiner::Refine(
  TriangleMesh& mesh, const std::vector<char>& markedTriangles, Prolongation mode)
{
  RefinementCounts counts;
  const int nOldPoints = mesh.NumberOfPoints();
  const int nOldTriangles = mesh.NumberOfTriangles();
  if (this->ExpectedPoints < 0)
  {
    counts.Error = "the refiner was not initialised on this mesh";
    return counts;
  }
  if (nOldPoints != this->ExpectedPoints || nOldTriangles != this->ExpectedTriangles ||
    static_cast<int>(mesh.TriangleEdges.size()) != nOldTriangles)
  {
    counts.Error = "the mesh connectivity changed since the last refinement";
    return counts;
  }
  if (static_cast<int>(markedTriangles.size()) != nOldTriangles)
  {
    counts.Error = "one mark per triangle is needed";
    return counts;
  }

  // --- 1. The base mesh: plain triangles as they are, each green pair as its parent.
  std::vector<BaseTriangle> base;
  base.reserve(static_cast<size_t>(nOldTriangles) * 2);
  std::vector<char> baseMarked;
  for (int t = 0; t < nOldTriangles; ++t)
  {
    if (this->TriangleGreen[t] < 0)
    {
      base.push_back({ mesh.Triangles[t], true, -1 });
      baseMarked.push_back(markedTriangles[t] ? 1 : 0);
    }
  }
  std::vector<char> greenMarked(this->Greens.size(), 0);
  for (int t = 0; t < nOldTriangles; ++t)
  {
    if (this->TriangleGreen[t] >= 0 && markedTriangles[t])
    {
      greenMarked[this->TriangleGreen[t]] = 1;
    }
  }
  for (size_t g = 0; g < this->Greens.size(); ++g)
  {
    base.push_back({ this->Greens[g].Parent, true, static_cast<int>(g) });
    baseMarked.push_back(greenMarked[g]);
  }

  // Edge -> the (at most two) alive base triangles that have it as a whole edge.
  std::unordered_map<unsigned long long, std::array<int, 2>> owners;
  owners.reserve(base.size() * 4);
  auto addOwner = [&](int i) {
    for (int k = 0; k < 3; ++k)
    {
      auto ins = owners.emplace(EdgeKey(base[i].V[k], base[i].V[(k + 1) % 3]), std::array<int, 2>{ i, -1 });
      if (!ins.second)
      {
        auto& o = ins.first->second;
        (o[0] == -1 ? o[0] : o[1]) = i;
      }
    }
  };
  auto removeOwner = [&](int i) {
    for (int k = 0; k < 3; ++k)
    {
      auto it = owners.find(EdgeKey(base[i].V[k], base[i].V[(k + 1) % 3]));
      if (it != owners.end())
      {
        for (int& o : it->second)
        {
          if (o == i)
          {
            o = -1;
          }
        }
      }
    }
  };
  for (int i = 0; i < static_cast<int>(base.size()); ++i)
  {
    addOwner(i);
  }

  auto midpointOf = [&](int a, int b) {
    auto it = this->Midpoints.find(EdgeKey(a, b));
    return it == this->Midpoints.end() ? -1 : it->second;
  };
  // Red is needed with two or more split edges, or with a split edge whose half is split
  // again (the other side is two levels finer: a green here would keep a T-vertex).
  auto needsRed = [&](int i) {
    int split = 0;
    for (int k = 0; k < 3; ++k)
    {
      const int a = base[i].V[k], b = base[i].V[(k + 1) % 3];
      const int m = midpointOf(a, b);
      if (m >= 0)
      {
        ++split;
        if (midpointOf(a, m) >= 0 || midpointOf(m, b) >= 0)
        {
          return true;
        }
      }
    }
    return split >= 2;
  };

  // New points: created in order, positions filled after the closure.
  std::vector<std::array<int, 2>> newPointEdges;
  auto getOrCreateMidpoint = [&](int a, int b) {
    const unsigned long long key = EdgeKey(a, b);
    auto it = this->Midpoints.find(key);
    if (it != this->Midpoints.end())
    {
      return it->second;
    }
    const int m = nOldPoints + static_cast<int>(newPointEdges.size());
    newPointEdges.push_back({ a, b });
    this->Midpoints.emplace(key, m);
    return m;
  };

  // --- 2. Red splits of the marked triangles, closure to a fixed point.
  std::deque<int> queue;
  std::vector<char> queued(base.size(), 0);
  auto enqueue = [&](int i) {
    if (i >= 0 && base[i].Alive && !queued[i])
    {
      queued[i] = 1;
      queue.push_back(i);
    }
  };
  auto enqueueIfNeeded = [&](int i) {
    if (i >= 0 && base[i].Alive && !queued[i] && needsRed(i))
    {
      enqueue(i);
    }
  };
  // The coarse triangle holding edge (p, q) whose midpoint is x, when x is a midpoint
  // and the other end is one of p, q: splitting (x, y) may force that triangle red.
  auto checkCoarserOwner = [&](int x, int y) {
    const std::array<int, 2> pe = x < nOldPoints ? this->ParentEdge[x] : newPointEdges[x - nOldPoints];
    if (pe[0] >= 0 && (pe[0] == y || pe[1] == y))
    {
      auto it = owners.find(EdgeKey(pe[0], pe[1]));
      if (it != owners.end())
      {
        enqueueIfNeeded(it->second[0]);
        enqueueIfNeeded(it->second[1]);
      }
    }
  };

  for (int i = 0; i < static_cast<int>(base.size()); ++i)
  {
    if (baseMarked[i])
    {
      enqueue(i);
    }
  }
  int markedRed = 0;
  for (int i = 0; i < static_cast<int>(base.size()); ++i)
  {
    markedRed += baseMarked[i] ? 1 : 0;
  }
  while (!queue.empty())
  {
    const int i = queue.front();
    queue.pop_front();
    if (!base[i].Alive)
    {
      continue;
    }
    const std::array<int, 3> v = base[i].V;
    int m[3];
    for (int k = 0; k < 3; ++k)
    {
      m[k] = getOrCreateMidpoint(v[k], v[(k + 1) % 3]);
    }
    removeOwner(i);
    base[i].Alive = false;
    ++counts.RedSplits;
    // Corner children keep the parent's orientation; m[k] lies on edge (v[k], v[k+1]).
    const std::array<int, 3> children[4] = { { v[0], m[0], m[2] }, { m[0], v[1], m[1] },
      { m[2], m[1], v[2] }, { m[0], m[1], m[2] } };
    const int firstChild = static_cast<int>(base.size());
    for (const auto& c : children)
    {
      base.push_back({ c, true, -1 });
      queued.push_back(0);
      addOwner(static_cast<int>(base.size()) - 1);
    }
    // Same-level or coarser neighbours across the split edges now see a split edge.
    for (int k = 0; k < 3; ++k)
    {
      auto it = owners.find(EdgeKey(v[k], v[(k + 1) % 3]));
      if (it != owners.end())
      {
        enqueueIfNeeded(it->second[0]);
        enqueueIfNeeded(it->second[1]);
      }
      // v[k], v[k+1] may be midpoints of a coarser edge: splitting (v[k], v[k+1]) puts a
      // quarter point on that coarse triangle's edge.
      checkCoarserOwner(v[k], v[(k + 1) % 3]);
      checkCoarserOwner(v[(k + 1) % 3], v[k]);
    }
    // Children next to a finer region (their edge's half is already split) go red too.
    for (int c = 0; c < 4; ++c)
    {
      enqueueIfNeeded(firstChild + c);
    }
  }
  counts.ClosureRedSplits = counts.RedSplits - markedRed;

  // --- 3. Positions of the new points, on the mesh before this step.
  const int nNew = static_cast<int>(newPointEdges.size());
  std::vector<Vec3> newPoints(nNew);
  const std::vector<char> greenFlags = this->GreenFlags();
  for (int j = 0; j < nNew; ++j)
  {
    const int a = newPointEdges[j][0], b = newPointEdges[j][1];
    const Vec3& pa = a < nOldPoints ? mesh.Points[a] : newPoints[a - nOldPoints];
    const Vec3& pb = b < nOldPoints ? mesh.Points[b] : newPoints[b - nOldPoints];
    const int e = (a < nOldPoints && b < nOldPoints) ? mesh.FindEdge(a, b) : -1;
    ButterflyRule rule = ButterflyRule::Midpoint;
    if (mode == Prolongation::Butterfly && e >= 0)
    {
      newPoints[j] = ButterflyEdgePoint(mesh, e, &greenFlags, &rule);
    }
    else
    {
      newPoints[j] = 0.5 * (pa + pb);
    }
    if (rule == ButterflyRule::Midpoint)
    {
      ++counts.FallbackVertices;
    }
    else
    {
      ++counts.ButterflyVertices;
    }
  }
  if (mode == Prolongation::Linear)
  {
    counts.FallbackVertices = 0;
  }
  counts.NewVertices = nNew;

  // --- 4. Emit the conforming mesh: plain triangles and green pairs.
  for (const auto& b : base)
  {
    if (b.OldGreen >= 0 && !b.Alive)
    {
      ++counts.UndoneGreens;
    }
  }
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(base.size());
  std::vector<int> triangleGreen;
  triangleGreen.reserve(base.size());
  std::vector<Green> greens;
  for (const auto& b : base)
  {
    if (!b.Alive)
    {
      continue;
    }
    int splitCorner = -1, mid = -1;
    for (int k = 0; k < 3; ++k)
    {
      const int mk = midpointOf(b.V[k], b.V[(k + 1) % 3]);
      if (mk >= 0)
      {
        splitCorner = k;
        mid = mk;
      }
    }
    if (splitCorner < 0)
    {
      triangles.push_back(b.V);
      triangleGreen.push_back(-1);
      continue;
    }
    const int g = static_cast<int>(greens.size());
    greens.push_back({ b.V, splitCorner, mid });
    const int p0 = b.V[splitCorner], p1 = b.V[(splitCorner + 1) % 3], p2 = b.V[(splitCorner + 2) % 3];
    triangles.push_back({ p0, mid, p2 });
    triangles.push_back({ mid, p1, p2 });
    triangleGreen.push_back(g);
    triangleGreen.push_back(g);
  }
  counts.Greens = static_cast<int>(greens.size());

  // --- 5. Commit.
  ++this->Level;
  mesh.Points.insert(mesh.Points.end(), newPoints.begin(), newPoints.end());
  mesh.Triangles.swap(triangles);
  mesh.Levels.resize(mesh.Points.size(), this->Level);
  this->ParentEdge.insert(this->ParentEdge.end(), newPointEdges.begin(), newPointEdges.end());
  this->Greens.swap(greens);
  this->TriangleGreen.swap(triangleGreen);
  mesh.Labels = this->ExpectedLabels(mesh.NumberOfPoints());
  std::string error;
  if (!mesh.BuildTopology(&error))
  {
    counts.Error = "refinement produced an invalid mesh: " + error;
    return counts;
  }
  this->ExpectedPoints = mesh.NumberOfPoints();
  this->ExpectedTriangles = mesh.NumberOfTriangles();
  counts.Ok = true;
  return counts;
}

bool CheckTopologyInvariants(
  const TriangleMesh& mesh, int expectedEuler, bool mustBeClosed, std::string* message)
{
  auto fail = [message](const std::string& msg) {
    if (message)
    {
      *message = msg;
    }
    return false;
  };
  const TriangleMesh* m = &mesh;
  TriangleMesh copy;
  if (static_cast<int>(mesh.TriangleEdges.size()) != mesh.NumberOfTriangles() ||
    static_cast<int>(mesh.NeighborOffsets.size()) != mesh.NumberOfPoints() + 1)
  {
    copy.Points = mesh.Points;
    copy.Triangles = mesh.Triangles;
    std::string error;
    if (!copy.BuildTopology(&error))
    {
      return fail(error);
    }
    m = &copy;
  }
  if (mustBeClosed && !m->IsClosed())
  {
    int open = 0;
    for (const auto& et : m->EdgeTriangles)
    {
      open += et[1] == -1 ? 1 : 0;
    }
    return fail(std::to_string(open) + " edge(s) with one triangle (a hole or a T-vertex)");
  }
  if (!m->IsConsistentlyOriented())
  {
    return fail("inconsistent orientation: two triangles traverse a shared edge the same way");
  }
  const int pinched = m->CountNonManifoldVertices();
  if (pinched != 0)
  {
    return fail(std::to_string(pinched) + " non-manifold vertex/vertices");
  }
  // Isolated points would shift the Euler characteristic without being a topology change
  // of the surface; refinement never makes them, so they count as an error too.
  for (int v = 0; v < m->NumberOfPoints(); ++v)
  {
    if (m->VertexTriangleOffsets[v + 1] == m->VertexTriangleOffsets[v])
    {
      return fail("point " + std::to_string(v) + " is used by no triangle");
    }
  }
  if (m->EulerCharacteristic() != expectedEuler)
  {
    return fail("Euler characteristic " + std::to_string(m->EulerCharacteristic()) + " != " +
      std::to_string(expectedEuler));
  }
  if (message)
  {
    message->clear();
  }
  return true;
}
} // namespace dsurf
