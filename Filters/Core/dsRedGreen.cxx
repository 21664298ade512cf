// SPDX-License-Identifier: BSD-3-Clause
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

/// Whether some triangle shares all three of its edges with one other triangle (topology built).
bool HasDoubledTriangle(const TriangleMesh& mesh)
{
  for (int t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    int other[3];
    for (int k = 0; k < 3; ++k)
    {
      const auto& pair = mesh.EdgeTriangles[mesh.TriangleEdges[t][k]];
      other[k] = pair[0] == t ? pair[1] : pair[0];
    }
    if (other[0] >= 0 && other[0] == other[1] && other[1] == other[2])
    {
      return true;
    }
  }
  return false;
}
} // namespace

bool RedGreenRefiner::Initialize(TriangleMesh& mesh, std::string* error)
{
  this->Greens.clear();
  this->Midpoints.clear();
  this->Level = 0;
  mesh.Labels.assign(mesh.Points.size(), LabelN);
  mesh.CornerLabels.clear();
  mesh.Levels.assign(mesh.Points.size(), 0);
  mesh.Depths.assign(mesh.Points.size(), 0);
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
  if (HasDoubledTriangle(mesh))
  {
    // Two triangles on the same three vertices (a closed two-triangle "pillow" is a valid
    // 2-manifold) share their midpoints: their 1 -> 4 splits give four triangles on one edge.
    if (error)
    {
      *error = "two triangles use the same three vertices (the surface folds flat onto itself)";
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

std::vector<unsigned char> RedGreenRefiner::ComputeLabels(int numberOfPoints) const
{
  // Priority M > C > D > N (see the class comment): rank by a number and keep the max.
  static const int rank[4] = { 0, 2, 3, 1 }; // N, C, M, D
  std::vector<unsigned char> labels(numberOfPoints, LabelN);
  auto put = [&](int v, unsigned char label)
  {
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

std::vector<std::array<unsigned char, 3>> RedGreenRefiner::ComputeCornerLabels(
  const TriangleMesh& mesh) const
{
  std::vector<std::array<unsigned char, 3>> corners(
    mesh.Triangles.size(), { LabelN, LabelN, LabelN });
  for (size_t t = 0; t < corners.size(); ++t)
  {
    const std::array<int, 3>& tri = mesh.Triangles[t];
    const int g = t < this->TriangleGreen.size() ? this->TriangleGreen[t] : -1;
    for (int c = 0; c < 3 && g >= 0; ++c)
    {
      // The role in this green alone (docs/METHOD.md §6.4): its midpoint M, the ends of its
      // split edge C, its opposite corner D, whatever the vertex is in other greens.
      const Green& green = this->Greens[g];
      const int v = tri[c];
      corners[t][c] = v == green.Midpoint                ? LabelM
        : v == green.Parent[(green.SplitCorner + 2) % 3] ? LabelD
                                                         : LabelC;
    }
  }
  return corners;
}

/// The working state of one Refine() call: the base mesh (greens merged into their
/// parents), which base triangles own each whole edge, the new points, and the red
/// closure queue. The phases of Refine() are its member functions.
class RedGreenRefiner::Step
{
public:
  Step(RedGreenRefiner& refiner, const TriangleMesh& mesh)
    : Refiner(refiner)
    , Mesh(mesh)
    , OldPoints(mesh.NumberOfPoints())
  {
  }

  void BuildBase(const std::vector<char>& markedTriangles);
  void RedSplitAndClose(RefinementCounts& counts);
  std::vector<Vec3> PlaceNewPoints(Prolongation mode, RefinementCounts& counts) const;
  void EmitConforming(std::vector<std::array<int, 3>>& triangles, std::vector<int>& triangleGreen,
    std::vector<Green>& greens, RefinementCounts& counts) const;

  /// Edge (a, b) of each new point, in creation order.
  const std::vector<std::array<int, 2>>& NewPointEdges() const { return this->NewEdges; }

private:
  void AddOwner(int i);
  void RemoveOwner(int i);
  int MidpointOf(int a, int b) const;
  bool NeedsRed(int i) const;
  int GetOrCreateMidpoint(int a, int b);
  void Enqueue(int i);
  void EnqueueIfNeeded(int i);
  void EnqueueOwnersOf(int a, int b);
  void CheckCoarserOwner(int x, int y);
  void RedSplit(int i);

  RedGreenRefiner& Refiner;
  const TriangleMesh& Mesh;
  const int OldPoints;
  std::vector<BaseTriangle> Base;
  std::vector<char> BaseMarked;
  /// Edge -> the (at most two) alive base triangles that have it as a whole edge.
  std::unordered_map<unsigned long long, std::array<int, 2>> Owners;
  /// New points: created in order, positions filled after the closure.
  std::vector<std::array<int, 2>> NewEdges;
  std::deque<int> Queue;
  std::vector<char> Queued;
};

// --- 1. The base mesh: plain triangles as they are, each green pair as its parent.
void RedGreenRefiner::Step::BuildBase(const std::vector<char>& markedTriangles)
{
  const int nOldTriangles = this->Mesh.NumberOfTriangles();
  const std::vector<int>& triangleGreen = this->Refiner.TriangleGreen;
  const std::vector<Green>& oldGreens = this->Refiner.Greens;
  this->Base.reserve(static_cast<size_t>(nOldTriangles) * 2);
  for (int t = 0; t < nOldTriangles; ++t)
  {
    if (triangleGreen[t] < 0)
    {
      this->Base.push_back({ this->Mesh.Triangles[t], true, -1 });
      this->BaseMarked.push_back(markedTriangles[t] ? 1 : 0);
    }
  }
  std::vector<char> greenMarked(oldGreens.size(), 0);
  for (int t = 0; t < nOldTriangles; ++t)
  {
    if (triangleGreen[t] >= 0 && markedTriangles[t])
    {
      greenMarked[triangleGreen[t]] = 1;
    }
  }
  for (size_t g = 0; g < oldGreens.size(); ++g)
  {
    this->Base.push_back({ oldGreens[g].Parent, true, static_cast<int>(g) });
    this->BaseMarked.push_back(greenMarked[g]);
  }
  this->Owners.reserve(this->Base.size() * 4);
  for (int i = 0; i < static_cast<int>(this->Base.size()); ++i)
  {
    this->AddOwner(i);
  }
}

void RedGreenRefiner::Step::AddOwner(int i)
{
  const std::array<int, 3>& v = this->Base[i].V;
  for (int k = 0; k < 3; ++k)
  {
    auto ins = this->Owners.emplace(EdgeKey(v[k], v[(k + 1) % 3]), std::array<int, 2>{ i, -1 });
    if (!ins.second)
    {
      auto& o = ins.first->second;
      (o[0] == -1 ? o[0] : o[1]) = i;
    }
  }
}

void RedGreenRefiner::Step::RemoveOwner(int i)
{
  const std::array<int, 3>& v = this->Base[i].V;
  for (int k = 0; k < 3; ++k)
  {
    auto it = this->Owners.find(EdgeKey(v[k], v[(k + 1) % 3]));
    if (it != this->Owners.end())
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
}

int RedGreenRefiner::Step::MidpointOf(int a, int b) const
{
  auto it = this->Refiner.Midpoints.find(EdgeKey(a, b));
  return it == this->Refiner.Midpoints.end() ? -1 : it->second;
}

// Red is needed with two or more split edges, or with a split edge whose half is split
// again (the other side is two levels finer: a green here would keep a T-vertex).
bool RedGreenRefiner::Step::NeedsRed(int i) const
{
  int split = 0;
  for (int k = 0; k < 3; ++k)
  {
    const int a = this->Base[i].V[k], b = this->Base[i].V[(k + 1) % 3];
    const int m = this->MidpointOf(a, b);
    if (m >= 0)
    {
      ++split;
      if (this->MidpointOf(a, m) >= 0 || this->MidpointOf(m, b) >= 0)
      {
        return true;
      }
    }
  }
  return split >= 2;
}

int RedGreenRefiner::Step::GetOrCreateMidpoint(int a, int b)
{
  const unsigned long long key = EdgeKey(a, b);
  auto it = this->Refiner.Midpoints.find(key);
  if (it != this->Refiner.Midpoints.end())
  {
    return it->second;
  }
  const int m = this->OldPoints + static_cast<int>(this->NewEdges.size());
  this->NewEdges.push_back({ a, b });
  this->Refiner.Midpoints.emplace(key, m);
  return m;
}

void RedGreenRefiner::Step::Enqueue(int i)
{
  if (i >= 0 && this->Base[i].Alive && !this->Queued[i])
  {
    this->Queued[i] = 1;
    this->Queue.push_back(i);
  }
}

void RedGreenRefiner::Step::EnqueueIfNeeded(int i)
{
  if (i >= 0 && this->Base[i].Alive && !this->Queued[i] && this->NeedsRed(i))
  {
    this->Enqueue(i);
  }
}

void RedGreenRefiner::Step::EnqueueOwnersOf(int a, int b)
{
  auto it = this->Owners.find(EdgeKey(a, b));
  if (it != this->Owners.end())
  {
    this->EnqueueIfNeeded(it->second[0]);
    this->EnqueueIfNeeded(it->second[1]);
  }
}

// The coarse triangle holding edge (p, q) whose midpoint is x, when x is a midpoint
// and the other end is one of p, q: splitting (x, y) may force that triangle red.
void RedGreenRefiner::Step::CheckCoarserOwner(int x, int y)
{
  const std::array<int, 2> pe =
    x < this->OldPoints ? this->Refiner.ParentEdge[x] : this->NewEdges[x - this->OldPoints];
  if (pe[0] >= 0 && (pe[0] == y || pe[1] == y))
  {
    this->EnqueueOwnersOf(pe[0], pe[1]);
  }
}

// --- 2. Red splits of the marked triangles, closure to a fixed point.
void RedGreenRefiner::Step::RedSplitAndClose(RefinementCounts& counts)
{
  this->Queued.assign(this->Base.size(), 0);
  int markedRed = 0;
  for (int i = 0; i < static_cast<int>(this->Base.size()); ++i)
  {
    if (this->BaseMarked[i])
    {
      this->Enqueue(i);
      ++markedRed;
    }
  }
  while (!this->Queue.empty())
  {
    const int i = this->Queue.front();
    this->Queue.pop_front();
    if (this->Base[i].Alive)
    {
      this->RedSplit(i);
      ++counts.RedSplits;
    }
  }
  counts.ClosureRedSplits = counts.RedSplits - markedRed;
}

void RedGreenRefiner::Step::RedSplit(int i)
{
  const std::array<int, 3> v = this->Base[i].V;
  int m[3];
  for (int k = 0; k < 3; ++k)
  {
    m[k] = this->GetOrCreateMidpoint(v[k], v[(k + 1) % 3]);
  }
  this->RemoveOwner(i);
  this->Base[i].Alive = false;
  // Corner children keep the parent's orientation; m[k] lies on edge (v[k], v[k+1]).
  std::array<int, 3> children[4];
  SplitInFour(v, m, children);
  const int firstChild = static_cast<int>(this->Base.size());
  for (const auto& c : children)
  {
    this->Base.push_back({ c, true, -1 });
    this->Queued.push_back(0);
    this->AddOwner(static_cast<int>(this->Base.size()) - 1);
  }
  // Same-level or coarser neighbours across the split edges now see a split edge.
  for (int k = 0; k < 3; ++k)
  {
    this->EnqueueOwnersOf(v[k], v[(k + 1) % 3]);
    // v[k], v[k+1] may be midpoints of a coarser edge: splitting (v[k], v[k+1]) puts a
    // quarter point on that coarse triangle's edge.
    this->CheckCoarserOwner(v[k], v[(k + 1) % 3]);
    this->CheckCoarserOwner(v[(k + 1) % 3], v[k]);
  }
  // Children next to a finer region (their edge's half is already split) go red too.
  for (int c = 0; c < 4; ++c)
  {
    this->EnqueueIfNeeded(firstChild + c);
  }
}

// --- 3. Positions of the new points, on the mesh before this step.
std::vector<Vec3> RedGreenRefiner::Step::PlaceNewPoints(
  Prolongation mode, RefinementCounts& counts) const
{
  const TriangleMesh& mesh = this->Mesh;
  const int nOldPoints = this->OldPoints;
  const int nNew = static_cast<int>(this->NewEdges.size());
  std::vector<Vec3> newPoints(nNew);
  // Stencils are read at each edge's level: greens as their parents (docs/METHOD.md §6.5).
  ButterflyHierarchy hierarchy;
  hierarchy.ParentEdges = &this->Refiner.ParentEdge;
  hierarchy.Depths = &mesh.Depths;
  for (int j = 0; j < nNew; ++j)
  {
    const int a = this->NewEdges[j][0], b = this->NewEdges[j][1];
    const Vec3& pa = a < nOldPoints ? mesh.Points[a] : newPoints[a - nOldPoints];
    const Vec3& pb = b < nOldPoints ? mesh.Points[b] : newPoints[b - nOldPoints];
    const int e = (a < nOldPoints && b < nOldPoints) ? mesh.FindEdge(a, b) : -1;
    ButterflyRule rule = ButterflyRule::Midpoint;
    if (mode == Prolongation::Butterfly && e >= 0)
    {
      newPoints[j] = ButterflyEdgePoint(mesh, e, nullptr, &rule, hierarchy);
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
  return newPoints;
}

// --- 4. Emit the conforming mesh: plain triangles and green pairs.
void RedGreenRefiner::Step::EmitConforming(std::vector<std::array<int, 3>>& triangles,
  std::vector<int>& triangleGreen, std::vector<Green>& greens, RefinementCounts& counts) const
{
  for (const auto& b : this->Base)
  {
    if (b.OldGreen >= 0 && !b.Alive)
    {
      ++counts.UndoneGreens;
    }
  }
  triangles.reserve(this->Base.size());
  triangleGreen.reserve(this->Base.size());
  for (const auto& b : this->Base)
  {
    if (!b.Alive)
    {
      continue;
    }
    int splitCorner = -1, mid = -1;
    for (int k = 0; k < 3; ++k)
    {
      const int mk = this->MidpointOf(b.V[k], b.V[(k + 1) % 3]);
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
    const int p0 = b.V[splitCorner], p1 = b.V[(splitCorner + 1) % 3],
              p2 = b.V[(splitCorner + 2) % 3];
    triangles.push_back({ p0, mid, p2 });
    triangles.push_back({ mid, p1, p2 });
    triangleGreen.push_back(g);
    triangleGreen.push_back(g);
  }
  counts.Greens = static_cast<int>(greens.size());
}

std::string RedGreenRefiner::CheckRefineInput(
  const TriangleMesh& mesh, const std::vector<char>& markedTriangles) const
{
  if (this->ExpectedPoints < 0)
  {
    return "the refiner was not initialised on this mesh";
  }
  const int nOldTriangles = mesh.NumberOfTriangles();
  if (mesh.NumberOfPoints() != this->ExpectedPoints || nOldTriangles != this->ExpectedTriangles ||
    static_cast<int>(mesh.TriangleEdges.size()) != nOldTriangles)
  {
    return "the mesh connectivity changed since the last refinement";
  }
  if (static_cast<int>(mesh.Depths.size()) != this->ExpectedPoints)
  {
    return "the mesh's Depths changed since the last refinement";
  }
  if (static_cast<int>(markedTriangles.size()) != nOldTriangles)
  {
    return "one mark per triangle is needed";
  }
  return std::string();
}

RefinementCounts RedGreenRefiner::Refine(
  TriangleMesh& mesh, const std::vector<char>& markedTriangles, Prolongation mode)
{
  RefinementCounts counts;
  counts.Error = this->CheckRefineInput(mesh, markedTriangles);
  if (!counts.Error.empty())
  {
    return counts;
  }
  Step step(*this, mesh);
  step.BuildBase(markedTriangles);
  step.RedSplitAndClose(counts);
  const std::vector<Vec3> newPoints = step.PlaceNewPoints(mode, counts);
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> triangleGreen;
  std::vector<Green> greens;
  step.EmitConforming(triangles, triangleGreen, greens, counts);

  // --- 5. Commit.
  ++this->Level;
  mesh.Points.insert(mesh.Points.end(), newPoints.begin(), newPoints.end());
  mesh.Triangles.swap(triangles);
  mesh.Levels.resize(mesh.Points.size(), this->Level);
  const auto& newPointEdges = step.NewPointEdges();
  this->ParentEdge.insert(this->ParentEdge.end(), newPointEdges.begin(), newPointEdges.end());
  for (const auto& e : newPointEdges) // in creation order: an edge's ends come first
  {
    mesh.Depths.push_back(1 + std::max(mesh.Depths[e[0]], mesh.Depths[e[1]]));
  }
  this->Greens.swap(greens);
  this->TriangleGreen.swap(triangleGreen);
  mesh.Labels = this->ComputeLabels(mesh.NumberOfPoints());
  mesh.CornerLabels = this->ComputeCornerLabels(mesh);
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
  auto fail = [message](const std::string& msg)
  {
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
    return fail("Euler characteristic " + std::to_string(m->EulerCharacteristic()) +
      " != " + std::to_string(expectedEuler));
  }
  if (message)
  {
    message->clear();
  }
  return true;
}
} // namespace dsurf
