// SPDX-License-Identifier: BSD-3-Clause
// The one triangle-surface type of the module: the seed builds it (dsSeedSurface.h), the
// solver deforms it and the refinement subdivides it. Plain C++, no pipeline types. Points
// move during a solve; connectivity changes only in refinement and subdivision, after which
// BuildTopology() is called again.
#ifndef dsTriangleMesh_h
#define dsTriangleMesh_h

#include "DeformableSurfaceFiltersModule.h" // for export macro

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace dsurf
{
using Vec3 = std::array<double, 3>;

inline Vec3 operator+(const Vec3& a, const Vec3& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}
inline Vec3 operator-(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
inline Vec3 operator*(double s, const Vec3& a)
{
  return { s * a[0], s * a[1], s * a[2] };
}
inline double Dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
inline double Norm(const Vec3& a)
{
  return std::sqrt(Dot(a, a));
}

/// Key of the undirected edge (a, b) of point ids below 2^32, for hash maps of edges (the
/// refinement and the seed's pinch counts on input point ids).
inline unsigned long long EdgeKey(long long a, long long b)
{
  if (a > b)
  {
    const long long t = a;
    a = b;
    b = t;
  }
  return (static_cast<unsigned long long>(a) << 32) | static_cast<unsigned int>(b);
}

/// The 1 -> 4 split of triangle v whose edge (v[k], v[k+1]) has midpoint m[k]: three corner
/// children and the middle one, all with the parent's orientation. Used by the red splits of
/// the refinement and by TriangleMesh::SubdivideUniformly.
template <class Triangle, class Id>
inline void SplitInFour(const Triangle& v, const Id m[3], Triangle children[4])
{
  children[0] = { v[0], m[0], m[2] };
  children[1] = { m[0], v[1], m[1] };
  children[2] = { m[2], m[1], v[2] };
  children[3] = { m[0], m[1], m[2] };
}

/// Unnormalised area-weighted normal of a fan of `count` triangles: the sum of their
/// (b - a) x (c - a), corners(i) giving the corner ids {a, b, c} of the i-th one in
/// `points`. Used by TriangleMesh::AreaWeightedNormal and the solver's local copy.
template <class Corners>
inline Vec3 AreaWeightedNormal(const Vec3* points, int count, const Corners& corners)
{
  Vec3 n{ 0, 0, 0 };
  for (int i = 0; i < count; ++i)
  {
    const auto& tri = corners(i);
    n = n + Cross(points[tri[1]] - points[tri[0]], points[tri[2]] - points[tri[0]]);
  }
  return n;
}

/// Vertex labels of red-green refinement (docs/METHOD.md §6.4). Initial and red vertices are N;
/// a green split labels its new midpoint M, the ends of the split edge C, the opposite corner D.
enum VertexLabel : unsigned char
{
  LabelN = 0,
  LabelC = 1,
  LabelM = 2,
  LabelD = 3
};

/// Finite-difference weight that a vertex labelled `self` gives a neighbour labelled
/// `neighbor` (docs/METHOD.md §6.4 table; row = self, column = neighbour).
inline double UmbrellaWeight(unsigned char self, unsigned char neighbor)
{
  static const double table[4][4] = {
    { 1, 1, 1, 1 }, // N
    { 2, 2, 2, 1 }, // C
    { 1, 2, 0, 1 }, // M
    { 1, 1, 0, 1 }, // D
  };
  return table[self & 3][neighbor & 3];
}

struct DEFORMABLESURFACEFILTERS_EXPORT TriangleMesh
{
  // --- state (set by the caller / refinement) ---
  std::vector<Vec3> Points;
  std::vector<std::array<int, 3>> Triangles; ///< consistently oriented (outward for closed input)
  std::vector<unsigned char> Labels;         ///< VertexLabel per point (N when empty)
  /// Per triangle, the label of each corner within that triangle (docs/METHOD.md §6.4): in a
  /// green half its role in that green pair (C, M, D), N in other triangles. A vertex
  /// can play different roles in different greens; the weights follow each green's own.
  /// Empty (or stale in size): Labels apply everywhere. Kept in corner order by whoever
  /// reorders a triangle's corners.
  std::vector<std::array<unsigned char, 3>> CornerLabels;
  std::vector<int> Levels; ///< refinement level that created each point
  /// Per point, its depth in the refinement hierarchy: 0 for the start's, else 1 + the deeper
  /// end's of the edge it halves: its level of detail (a late split of a coarse triangle makes
  /// points of a late level but a low depth). Set by refinement (dsRedGreen.h); empty or stale
  /// in size: unknown, Levels stands in.
  std::vector<int> Depths;
  /// Per point, the index (0, 1, ...) of the object it belongs to when one run solves several
  /// (docs/METHOD.md §9.9); empty: one object. Points appended by subdivision or refinement get
  /// theirs from ExtendObjects.
  std::vector<int> Objects;
  /// The caller's label of each object (the filter's ObjectId array), empty when none was given.
  std::vector<long long> ObjectIds;

  // --- topology, derived by BuildTopology() ---
  /// One-ring of vertex v: Neighbors[NeighborOffsets[v] .. NeighborOffsets[v+1]), sorted ascending.
  std::vector<int> NeighborOffsets, Neighbors;
  /// Triangles incident to v: VertexTriangles[VertexTriangleOffsets[v] .. [v+1]).
  std::vector<int> VertexTriangleOffsets, VertexTriangles;
  /// Unique edges (a < b), the edges of each triangle (edge k joins corners k and k+1),
  /// and the one or two triangles of each edge (-1 when the edge is on an open boundary).
  std::vector<std::array<int, 2>> Edges;
  std::vector<std::array<int, 3>> TriangleEdges;
  std::vector<std::array<int, 2>> EdgeTriangles;
  /// 1 for vertices on an open boundary (they stay fixed in the solver).
  std::vector<unsigned char> BoundaryVertex;

  int NumberOfPoints() const { return static_cast<int>(this->Points.size()); }
  /// 1 + the largest entry of Objects (1 when it is empty).
  int NumberOfObjects() const;
  /// Gives every point beyond the end of Objects the object of a neighbour (a point appended by
  /// a split lies on an edge of its own object); nothing when Objects is empty. Needs the
  /// topology.
  void ExtendObjects();
  int NumberOfTriangles() const { return static_cast<int>(this->Triangles.size()); }

  /// Derive the topology from Points/Triangles; fills Labels/Levels with N/0 when their
  /// size does not match. Returns false with a message when an edge has three or more
  /// triangles (non-manifold), a triangle is degenerate (repeated vertex) or an index
  /// is out of range. Two triangles traversing a shared edge in the same direction
  /// (inconsistent orientation) are reported by IsConsistentlyOriented(), not here.
  bool BuildTopology(std::string* error);

  /// Edge id of (a, b) in either order, -1 when absent. Needs BuildTopology().
  int FindEdge(int a, int b) const;

  // --- invariants (need BuildTopology()) ---
  bool IsClosed() const;               ///< every edge has two triangles
  bool IsConsistentlyOriented() const; ///< neighbours traverse shared edges oppositely
  /// Flip triangles so that neighbours traverse shared edges oppositely; each connected
  /// piece keeps the orientation most of its triangles had. Rebuilds the topology and
  /// returns the number of triangles flipped (a non-orientable piece stays as it is
  /// where the walk meets itself).
  int OrientConsistently();
  /// Turns every closed piece whose signed volume is negative inside out (its triangles
  /// reversed), so normals point out of every closed piece. Rebuilds the topology and returns
  /// the number of triangles flipped. Needs a consistent orientation per piece.
  int OrientPiecesOutward();
  int CountNonManifoldVertices() const; ///< vertices whose triangles form more than one fan
  int EulerCharacteristic() const
  {
    return this->NumberOfPoints() - static_cast<int>(this->Edges.size()) +
      this->NumberOfTriangles();
  }
  /// Closed volume by the divergence theorem (positive when oriented outward).
  double SignedVolume() const;
  /// Mean length of the unique edges (0 without edges). Needs BuildTopology().
  double MeanEdgeLength() const;
  /// Unnormalised area-weighted normal of vertex v (sum of incident face cross products).
  Vec3 AreaWeightedNormal(int v) const;
  /// Smallest interior angle of triangle t, in degrees.
  double MinAngleDegrees(int t) const;

  /// Splits every triangle 1 -> 4 (SplitInFour) at the midpoints of its edges, so the shape
  /// is kept exactly; a closed, manifold, oriented mesh stays so, with the same Euler
  /// characteristic. The midpoint of edge e becomes point NumberOfPoints() + e (edges in
  /// the order BuildTopology() numbers them: first use along the triangles), triangle t's
  /// children become triangles 4t .. 4t+3. Every point is then labelled N, level 0 (a fresh
  /// level-0 mesh). Needs the topology of the current triangles (built here when there is
  /// none) and rebuilds it after the split; false with BuildTopology()'s message on failure.
  bool SubdivideUniformly(std::string* error);

  /// Splits at its midpoint every edge longer than both `minLength` and twice the shortest
  /// edge of a triangle it borders, conformingly (a triangle is bisected at its longest split
  /// edge, its halves again at theirs), and repeats on the result (at most 16 rounds, none that
  /// would take the mesh past `maxPoints` points): the long edges of elongated triangles come
  /// down to about minLength. The shape is kept exactly and
  /// the mesh stays closed, manifold and oriented; every point is then labelled N, level 0.
  /// Returns the number of edges split (0: the mesh is untouched); -1 with BuildTopology()'s
  /// message on failure.
  int SplitElongatedEdges(double minLength, long long maxPoints, std::string* error);

private:
  /// The steps of BuildTopology(); the first two return why the mesh is invalid, or "".
  std::string BuildVertexTriangles(); ///< VertexTriangleOffsets / VertexTriangles
  std::string BuildEdges();           ///< Edges, TriangleEdges, EdgeTriangles
  void BuildRings();                  ///< NeighborOffsets / Neighbors, BoundaryVertex
  /// Edge id of (a, b) as a triangle before `before` has it (-1 when none does); needs
  /// VertexTriangles and those triangles' TriangleEdges.
  int EdgeBefore(int a, int b, int before) const;
};
} // namespace dsurf

#endif
