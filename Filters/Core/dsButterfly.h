// SPDX-License-Identifier: BSD-3-Clause
// Butterfly prolongation (docs/METHOD.md §6.5): where red-green refinement puts a new
// edge midpoint. Plain C++, no pipeline types.
//
// Rules, chosen per edge (a, b) of the mesh *before* refinement:
// - Regular: both ends interior with valence 6 -> the 8-point butterfly of Dyn, Levin
//   and Gregory (1990), w = 1/16:
//     p = 1/2 (a + b) + 2w (b1 + b2) - w (c1 + c2 + c3 + c4)
//   b1, b2 the corners opposite the edge, c1..c4 the corners opposite the four outer
//   edges of those two triangles. On a regular grid it reproduces cubic polynomials.
// - Extraordinary: one end interior with valence k != 6, the other valence 6 ->
//   the modified butterfly of Zorin, Schröder and Sweldens (1996) around the
//   extraordinary end e with ring q_0 = the other end, q_1..q_{k-1} in cyclic order:
//     p = 3/4 e + sum_j s_j q_j,
//     k = 3: s = (5/12, -1/12, -1/12); k = 4: s = (3/8, 0, -1/8, 0);
//     k >= 5: s_j = (1/4 + cos(2 pi j / k) + 1/2 cos(4 pi j / k)) / k.
// - BothExtraordinary: both ends interior with valence != 6 -> the average of the two
//   Zorin stencils (Zorin et al.'s own rule).
// - Boundary: an edge on an open boundary -> the 4-point curve scheme
//   9/16 (a + b) - 1/16 (a' + b') along the boundary (a', b' the next boundary
//   vertices), so the boundary curve is refined by itself.
// - Midpoint (the fallback): 1/2 (a + b) when the stencil is incomplete or irregular:
//   an interior edge with an end on the boundary, a boundary end with a branching
//   boundary, a ring that is not one cycle (or, read at the edge's level, not complete: a
//   corner of a refined patch's border has no vertices of that level on its coarse side),
//   or a stencil triangle flagged irregular.
// Adaptive meshes (red-green refinement, dsRedGreen.h): the stencil is read on the mesh at the
// edge's own level, given the hierarchy (ButterflyHierarchy): a green pair counts as its
// parent triangle and a finer region as the coarse triangles it refines, so the rules above
// apply where a green or a finer neighbour touches the stencil instead of falling back to
// the midpoint (each ring neighbour that is the midpoint of a coarser edge of the vertex
// stands for that edge's far end; a green's midpoint is left out of its other corners' rings).
// Every rule is an affine combination (weights sum to 1), so a plane stays planar.
#ifndef dsButterfly_h
#define dsButterfly_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTriangleMesh.h"

#include <array>
#include <vector>

namespace dsurf
{
enum class ButterflyRule : unsigned char
{
  Regular = 0,
  Extraordinary = 1,
  BothExtraordinary = 2,
  Boundary = 3,
  Midpoint = 4
};

/// The refinement hierarchy of a mesh, for reading stencils at an edge's level: per point, the
/// edge it is the midpoint of ({-1, -1} for a point of the start) and its depth (0 for a point
/// of the start, else 1 + the deeper end's depth: the level of detail, which a late split of a
/// coarse triangle keeps low however many steps came before).
struct ButterflyHierarchy
{
  const std::vector<std::array<int, 2>>* ParentEdges = nullptr;
  const std::vector<int>* Depths = nullptr;
};

/// New point on edge `edge` of `mesh` (BuildTopology() done). irregularTriangles, when
/// given, flags triangles that must not be part of a stencil; a stencil touching one falls
/// back to the midpoint. rule, when given, receives the rule that was applied. hierarchy,
/// when given (a parent edge and a depth per point), reads the stencil at the edge's level
/// (see above).
DEFORMABLESURFACEFILTERS_EXPORT Vec3 ButterflyEdgePoint(const TriangleMesh& mesh, int edge,
  const std::vector<char>* irregularTriangles = nullptr, ButterflyRule* rule = nullptr,
  const ButterflyHierarchy& hierarchy = ButterflyHierarchy());

/// The Zorin weights s_0..s_{k-1} for an extraordinary vertex of valence k (k >= 3).
DEFORMABLESURFACEFILTERS_EXPORT std::vector<double> ZorinWeights(int k);
} // namespace dsurf

#endif
