// SPDX-License-Identifier: BSD-3-Clause
#include "dsSeedSurface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_map>
#include <utility>

namespace dsurf
{
namespace
{
// Faces of a positively oriented tetrahedron (SeedTetSignedVolume > 0), face k opposite
// corner k, each ordered so that its right-hand normal points away from corner k.
constexpr int kFace[4][3] = { { 1, 2, 3 }, { 0, 3, 2 }, { 0, 1, 3 }, { 0, 2, 1 } };

struct UnionFind
{
  std::vector<std::int64_t> Parent;
  explicit UnionFind(std::int64_t n)
    : Parent(static_cast<std::size_t>(n))
  {
    std::iota(this->Parent.begin(), this->Parent.end(), std::int64_t(0));
  }
  std::int64_t Find(std::int64_t i)
  {
    while (this->Parent[i] != i)
    {
      this->Parent[i] = this->Parent[this->Parent[i]];
      i = this->Parent[i];
    }
    return i;
  }
  void Union(std::int64_t a, std::int64_t b)
  {
    a = this->Find(a);
    b = this->Find(b);
    if (a != b)
    {
      this->Parent[std::max(a, b)] = std::min(a, b);
    }
  }
};

// Face-to-face adjacency of the whole tetrahedrisation (independent of which are kept):
// neighbour[4t+k] = 4t'+k' of the tetrahedron across face k of t, or -1 on the hull.
std::vector<std::int64_t> FaceNeighbours(const std::vector<SeedTet>& tets)
{
  struct Entry
  {
    std::array<std::int64_t, 3> Key;
    std::int64_t Slot;
  };
  std::vector<Entry> entries;
  entries.reserve(tets.size() * 4);
  for (std::size_t t = 0; t < tets.size(); ++t)
  {
    for (int k = 0; k < 4; ++k)
    {
      std::array<std::int64_t, 3> key = { tets[t][kFace[k][0]], tets[t][kFace[k][1]],
        tets[t][kFace[k][2]] };
      std::sort(key.begin(), key.end());
      entries.push_back({ key, static_cast<std::int64_t>(4 * t + k) });
    }
  }
  std::sort(entries.begin(), entries.end(),
    [](const Entry& a, const Entry& b)
    { return a.Key < b.Key || (a.Key == b.Key && a.Slot < b.Slot); });
  std::vector<std::int64_t> neighbour(entries.size(), -1);
  for (std::size_t i = 0; i + 1 < entries.size(); ++i)
  {
    // A valid tetrahedrisation shares a face between at most two tetrahedra; a third
    // (malformed input) is left unpaired rather than guessed.
    if (entries[i].Key == entries[i + 1].Key)
    {
      neighbour[entries[i].Slot] = entries[i + 1].Slot;
      neighbour[entries[i + 1].Slot] = entries[i].Slot;
      ++i;
    }
  }
  return neighbour;
}

bool IsKept(const std::vector<unsigned char>& status, std::int64_t slot)
{
  return slot >= 0 && status[slot / 4] == SeedKept;
}

/// Positively oriented copies of the tetrahedra (so each face's outward order comes from
/// kFace), and which of them are flat (|volume| <= degenerateVolume).
std::vector<SeedTet> OrientPositively(const std::vector<Vec3>& points,
  const std::vector<SeedTet>& inTets, double degenerateVolume, std::vector<char>& flat)
{
  std::vector<SeedTet> tets = inTets;
  flat.assign(tets.size(), 0);
  for (std::size_t t = 0; t < tets.size(); ++t)
  {
    SeedTet& c = tets[t];
    const double vol = SeedTetSignedVolume(points[c[0]], points[c[1]], points[c[2]], points[c[3]]);
    if (vol < 0)
    {
      std::swap(c[0], c[1]);
    }
    flat[t] = std::abs(vol) <= degenerateVolume ? 1 : 0;
  }
  return tets;
}

/// Peels the flat kept tetrahedra that touch the boundary (status SeedRemovedDegenerate):
/// their faces have no outward side. Returns how many were peeled.
std::int64_t PeelFlatTetrahedra(const std::vector<char>& flat,
  const std::vector<std::int64_t>& neighbour, std::vector<unsigned char>& status)
{
  const std::int64_t nTets = static_cast<std::int64_t>(flat.size());
  std::int64_t peeled = 0;
  std::vector<std::int64_t> queue;
  for (std::int64_t t = 0; t < nTets; ++t)
  {
    if (flat[t] && status[t] == SeedKept)
    {
      queue.push_back(t);
    }
  }
  while (!queue.empty())
  {
    const std::int64_t t = queue.back();
    queue.pop_back();
    if (status[t] != SeedKept)
    {
      continue;
    }
    bool exposed = false;
    for (int k = 0; k < 4; ++k)
    {
      exposed = exposed || !IsKept(status, neighbour[4 * t + k]);
    }
    if (exposed)
    {
      status[t] = SeedRemovedDegenerate;
      ++peeled;
      for (int k = 0; k < 4; ++k)
      {
        const std::int64_t nb = neighbour[4 * t + k];
        if (nb >= 0 && flat[nb / 4] && status[nb / 4] == SeedKept)
        {
          queue.push_back(nb / 4);
        }
      }
    }
  }
  return peeled;
}

/// The boundary faces of the kept tetrahedra, outward: face f is face slot
/// Slot[f] = 4t+k (face k of tetrahedron t); SlotFace is the inverse (-1: not boundary).
struct BoundaryFaces
{
  std::vector<std::int64_t> Slot;
  std::vector<std::int64_t> SlotFace;
  const std::vector<SeedTet>* Tets = nullptr;

  std::int64_t Count() const { return static_cast<std::int64_t>(this->Slot.size()); }
  /// Corner j of face f (input point id), in outward order.
  std::int64_t Vertex(std::int64_t f, int j) const
  {
    const std::int64_t slot = this->Slot[f];
    return (*this->Tets)[slot / 4][kFace[slot % 4][j]];
  }
};

BoundaryFaces CollectBoundaryFaces(const std::vector<SeedTet>& tets,
  const std::vector<std::int64_t>& neighbour, const std::vector<unsigned char>& status,
  std::int64_t& keptTetrahedra)
{
  BoundaryFaces faces;
  faces.Tets = &tets;
  faces.SlotFace.assign(4 * tets.size(), -1);
  keptTetrahedra = 0;
  for (std::int64_t t = 0; t < static_cast<std::int64_t>(tets.size()); ++t)
  {
    if (status[t] != SeedKept)
    {
      continue;
    }
    ++keptTetrahedra;
    for (int k = 0; k < 4; ++k)
    {
      if (!IsKept(status, neighbour[4 * t + k]))
      {
        faces.SlotFace[4 * t + k] = faces.Count();
        faces.Slot.push_back(4 * t + k);
      }
    }
  }
  return faces;
}

/// Pairs the faces across each edge by walking through the kept tetrahedra of one solid
/// wedge around the edge: the pairing is then manifold even where 4+ faces meet.
/// partner[3f+j] = the face across edge (corner j, corner j+1) of face f, or -1.
std::vector<std::int64_t> PairFacesAcrossEdges(const BoundaryFaces& faces,
  const std::vector<SeedTet>& tets, const std::vector<std::int64_t>& neighbour,
  const std::vector<unsigned char>& status)
{
  const std::int64_t nFaces = faces.Count();
  const std::int64_t nTets = static_cast<std::int64_t>(tets.size());
  std::vector<std::int64_t> partner(3 * nFaces, -1);
  for (std::int64_t f = 0; f < nFaces; ++f)
  {
    for (int j = 0; j < 3; ++j)
    {
      const std::int64_t u = faces.Vertex(f, j), w = faces.Vertex(f, (j + 1) % 3);
      std::int64_t slot = faces.Slot[f];
      for (std::int64_t step = 0; step <= nTets; ++step)
      {
        const std::int64_t t = slot / 4;
        const int k = static_cast<int>(slot % 4);
        // The current face holds u, w and a third corner x; the next face around the edge
        // in this tetrahedron is the one opposite x.
        int x = -1;
        for (int c = 0; c < 4; ++c)
        {
          if (c != k && tets[t][c] != u && tets[t][c] != w)
          {
            x = c;
          }
        }
        const std::int64_t next = 4 * t + x;
        const std::int64_t nb = neighbour[next];
        if (!IsKept(status, nb))
        {
          partner[3 * f + j] = faces.SlotFace[next];
          break;
        }
        slot = nb;
      }
    }
  }
  return partner;
}

/// One output point per fan: the corners (f, j) are joined across paired edges, and each
/// class of corners becomes one point, numbered in order of first use.
void BuildFanSurface(const BoundaryFaces& faces, const std::vector<std::int64_t>& partner,
  const std::vector<Vec3>& points, SeedSurface& surface)
{
  const std::int64_t nFaces = faces.Count();
  UnionFind corners(3 * nFaces);
  for (std::int64_t f = 0; f < nFaces; ++f)
  {
    for (int j = 0; j < 3; ++j)
    {
      const std::int64_t g = partner[3 * f + j];
      if (g < 0)
      {
        continue;
      }
      const std::int64_t u = faces.Vertex(f, j), w = faces.Vertex(f, (j + 1) % 3);
      for (int i = 0; i < 3; ++i)
      {
        const std::int64_t gv = faces.Vertex(g, i);
        if (gv == u)
        {
          corners.Union(3 * f + j, 3 * g + i);
        }
        else if (gv == w)
        {
          corners.Union(3 * f + (j + 1) % 3, 3 * g + i);
        }
      }
    }
  }
  std::vector<int> classPoint(3 * nFaces, -1);
  surface = SeedSurface();
  surface.Triangles.assign(static_cast<std::size_t>(nFaces), std::array<int, 3>());
  for (std::int64_t f = 0; f < nFaces; ++f)
  {
    for (int j = 0; j < 3; ++j)
    {
      const std::int64_t root = corners.Find(3 * f + j);
      if (classPoint[root] < 0)
      {
        classPoint[root] = surface.NumberOfPoints();
        surface.SourcePoint.push_back(faces.Vertex(f, j));
        surface.Points.push_back(points[faces.Vertex(f, j)]);
      }
      surface.Triangles[f][j] = classPoint[root];
    }
  }
}

/// Every undirected edge of the surface must have exactly two faces. If not, two sheets
/// still share an edge: one kept tetrahedron there is removed (SeedRemovedByPinch).
/// Returns how many were removed (0: the surface is a 2-manifold).
std::int64_t RemovePinchTetrahedra(
  const SeedSurface& surface, const BoundaryFaces& faces, std::vector<unsigned char>& status)
{
  std::unordered_map<unsigned long long, int> edgeUse;
  edgeUse.reserve(static_cast<std::size_t>(3 * faces.Count()));
  for (const std::array<int, 3>& tri : surface.Triangles)
  {
    for (int j = 0; j < 3; ++j)
    {
      ++edgeUse[EdgeKey(tri[j], tri[(j + 1) % 3])];
    }
  }
  std::int64_t removed = 0;
  for (std::int64_t f = 0; f < faces.Count(); ++f)
  {
    const std::array<int, 3>& tri = surface.Triangles[f];
    for (int j = 0; j < 3; ++j)
    {
      if (edgeUse[EdgeKey(tri[j], tri[(j + 1) % 3])] != 2 && status[faces.Slot[f] / 4] == SeedKept)
      {
        status[faces.Slot[f] / 4] = SeedRemovedByPinch;
        ++removed;
        // One removal per edge is enough; mark the edge as handled.
        edgeUse[EdgeKey(tri[j], tri[(j + 1) % 3])] = 2;
      }
    }
  }
  return removed;
}

/// The pinch counts of the report, on the original vertex numbering; returns the number
/// of output copies of each input point.
std::unordered_map<std::int64_t, std::int64_t> CountPinches(
  const SeedSurface& surface, const BoundaryFaces& faces, SeedBoundaryReport& report)
{
  std::unordered_map<unsigned long long, int> originalEdgeUse;
  for (std::int64_t f = 0; f < faces.Count(); ++f)
  {
    for (int j = 0; j < 3; ++j)
    {
      ++originalEdgeUse[EdgeKey(faces.Vertex(f, j), faces.Vertex(f, (j + 1) % 3))];
    }
  }
  report.PinchedEdges = 0;
  for (const auto& e : originalEdgeUse)
  {
    report.PinchedEdges += e.second > 2 ? 1 : 0;
  }
  std::unordered_map<std::int64_t, std::int64_t> copies;
  for (std::int64_t source : surface.SourcePoint)
  {
    ++copies[source];
  }
  report.PinchedVertices = 0;
  report.VertexCopiesAdded = 0;
  for (const auto& c : copies)
  {
    if (c.second > 1)
    {
      ++report.PinchedVertices;
      report.VertexCopiesAdded += c.second - 1;
    }
  }
  return copies;
}

/// Moves the copies of a split vertex into their own fans, by 2% of the fan's mean edge
/// length toward its ring centroid, so that the sheets are no longer geometrically glued.
void SeparateSplitCopies(const std::vector<Vec3>& points,
  std::unordered_map<std::int64_t, std::int64_t>& copies, SeedSurface& surface)
{
  const std::size_t nPoints = surface.Points.size();
  std::vector<Vec3> ring(nPoints, Vec3{ 0, 0, 0 });
  std::vector<double> length(nPoints, 0.0);
  std::vector<int> count(nPoints, 0);
  for (const std::array<int, 3>& tri : surface.Triangles)
  {
    for (int j = 0; j < 3; ++j)
    {
      const std::int64_t p = tri[j];
      if (copies[surface.SourcePoint[p]] < 2)
      {
        continue;
      }
      for (int o = 1; o < 3; ++o)
      {
        const Vec3& q = points[surface.SourcePoint[tri[(j + o) % 3]]];
        for (int i = 0; i < 3; ++i)
        {
          ring[p][i] += q[i];
        }
        length[p] += Norm(q - points[surface.SourcePoint[p]]);
        ++count[p];
      }
    }
  }
  for (std::size_t p = 0; p < nPoints; ++p)
  {
    if (count[p] == 0)
    {
      continue;
    }
    Vec3 dir;
    for (int i = 0; i < 3; ++i)
    {
      dir[i] = ring[p][i] / count[p] - surface.Points[p][i];
    }
    const double norm = std::sqrt(Dot(dir, dir));
    if (norm > 0)
    {
      const double shift = 0.02 * length[p] / count[p];
      for (int i = 0; i < 3; ++i)
      {
        surface.Points[p][i] += shift * dir[i] / norm;
      }
    }
  }
}

std::int64_t CountComponents(const SeedSurface& surface)
{
  UnionFind parts(static_cast<std::int64_t>(surface.Points.size()));
  for (const std::array<int, 3>& tri : surface.Triangles)
  {
    parts.Union(tri[0], tri[1]);
    parts.Union(tri[0], tri[2]);
  }
  std::int64_t components = 0;
  for (std::size_t p = 0; p < surface.Points.size(); ++p)
  {
    components += parts.Find(static_cast<std::int64_t>(p)) == static_cast<std::int64_t>(p) ? 1 : 0;
  }
  return components;
}
} // namespace

double SeedTetSignedVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  return Dot(b - a, Cross(c - a, d - a)) / 6.0;
}

double SeedTetCircumradius(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  // Centre relative to a: (|u|^2 (v x w) + |v|^2 (w x u) + |w|^2 (u x v)) / (2 u.(v x w)).
  const Vec3 u = b - a, v = c - a, w = d - a;
  const Vec3 vw = Cross(v, w), wu = Cross(w, u), uv = Cross(u, v);
  const double det = 2.0 * Dot(u, vw);
  const double scale = std::max({ Dot(u, u), Dot(v, v), Dot(w, w) });
  if (std::abs(det) <= 1e-12 * scale * std::sqrt(scale))
  {
    return std::numeric_limits<double>::infinity();
  }
  const double uu = Dot(u, u), vv = Dot(v, v), ww = Dot(w, w);
  Vec3 centre;
  for (int i = 0; i < 3; ++i)
  {
    centre[i] = (uu * vw[i] + vv * wu[i] + ww * uv[i]) / det;
  }
  return std::sqrt(Dot(centre, centre));
}

std::string SeedBoundaryReport::Summary() const
{
  std::ostringstream os;
  const char* sep = "";
  if (this->DegenerateRemoved > 0)
  {
    os << sep << "removed " << this->DegenerateRemoved << " flat tetrahedra at the boundary";
    sep = "; ";
  }
  if (this->PinchedEdges > 0 || this->PinchedVertices > 0)
  {
    os << sep << "resolved " << this->PinchedEdges << " pinched edge(s) and "
       << this->PinchedVertices << " pinched vertex(es) by splitting vertices ("
       << this->VertexCopiesAdded << " point copies added, moved 2% of an edge apart)";
    sep = "; ";
  }
  if (this->PinchTetsRemoved > 0)
  {
    os << sep << "removed " << this->PinchTetsRemoved
       << " tetrahedra where two sheets shared an edge (Removed = 4)";
    sep = "; ";
  }
  if (this->Components > 1)
  {
    os << sep << "the surface has " << this->Components << " separate closed components";
  }
  return os.str();
}

SeedSurface ExtractSeedBoundary(const std::vector<Vec3>& points, const std::vector<SeedTet>& inTets,
  std::vector<unsigned char>& status, double degenerateVolume, SeedBoundaryReport& report)
{
  report = SeedBoundaryReport();
  SeedSurface surface;
  const std::int64_t nTets = static_cast<std::int64_t>(inTets.size());
  if (status.size() != inTets.size())
  {
    status.assign(inTets.size(), SeedKept);
  }
  std::vector<char> flat;
  const std::vector<SeedTet> tets = OrientPositively(points, inTets, degenerateVolume, flat);
  const std::vector<std::int64_t> neighbour = FaceNeighbours(tets);

  // A tetrahedron can be removed for a pinch only a bounded number of times in total.
  for (std::int64_t attempt = 0; attempt <= nTets; ++attempt)
  {
    report.DegenerateRemoved += PeelFlatTetrahedra(flat, neighbour, status);
    const BoundaryFaces faces =
      CollectBoundaryFaces(tets, neighbour, status, report.KeptTetrahedra);
    if (faces.Count() == 0)
    {
      return surface;
    }
    BuildFanSurface(faces, PairFacesAcrossEdges(faces, tets, neighbour, status), points, surface);
    const std::int64_t removedNow = RemovePinchTetrahedra(surface, faces, status);
    if (removedNow > 0)
    {
      report.PinchTetsRemoved += removedNow;
      continue; // extract again without them
    }
    std::unordered_map<std::int64_t, std::int64_t> copies = CountPinches(surface, faces, report);
    if (report.VertexCopiesAdded > 0)
    {
      SeparateSplitCopies(points, copies, surface);
    }
    report.Components = CountComponents(surface);
    return surface;
  }
  // Unreachable in practice: every attempt removes at least one tetrahedron.
  surface = SeedSurface();
  return surface;
}

int SubdivideSeedSurface(SeedSurface& surface, double target, std::int64_t maxTriangles)
{
  int steps = 0;
  if (!(target > 0.0) || !surface.BuildTopology(nullptr))
  {
    return 0;
  }
  while (surface.MeanEdgeLength() > std::sqrt(2.0) * target &&
    static_cast<std::int64_t>(surface.Triangles.size()) * 4 <= maxTriangles)
  {
    const bool built = surface.SubdivideUniformly(nullptr);
    surface.SourcePoint.resize(surface.Points.size(), -1);
    ++steps;
    if (!built)
    {
      break; // not a manifold (the boundary extraction makes one): no mean edge length
    }
  }
  return steps;
}
} // namespace dsurf
