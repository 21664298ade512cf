// SPDX-License-Identifier: BSD-3-Clause
// Red-green adaptive refinement of the deformable surface (docs/METHOD.md §6.3-6.5): plain C++,
// no pipeline types.
//
// How: the refiner remembers which current triangles are green halves, their parent
// triangle and split edge, and, for every edge ever split, its midpoint vertex. A
// refinement step works on the "base" mesh, which is the current mesh with every
// green pair merged back into its parent (so greens are never refined: a marked
// green, or a green that needs another split, has its cut undone and its parent is
// red-refined instead). Marked base triangles are red-split 1 -> 4; then a closure
// runs to a fixed point: a base triangle with two or three split edges, or with a
// split edge whose half is split again (two levels finer on the other side), is
// red-split too. Every base triangle left with exactly one split edge is emitted as a
// green pair 1 -> 2. No T-vertices remain; points are never removed or reordered
// (new ones are appended), so per-point state of the caller stays valid.
//
// Labels (docs/METHOD.md §6.4) are recomputed from the greens after every step
// (ComputeLabels): all N, then for each green its midpoint M, the ends of its split edge C,
// its opposite corner D.
// An undone green's M is an ordinary N vertex of the red split, and its C / D revert
// to N unless another green still uses them. A vertex often plays several roles (wherever a
// red-green border turns; most often C of one green and D of another: docs/METHOD.md §6.4),
// so the weights do not come from one label per vertex: every green half carries its
// corners' roles in that green (ComputeCornerLabels, mesh.CornerLabels; N in other
// triangles), and the solver weighs each edge by the greens it lies in. The vertex label
// (M over C over D) is the row of its other edges and what the output's VertexLabel shows.
//
// New points are placed by the butterfly scheme (dsButterfly.h) evaluated on the mesh
// before the step, each stencil read at its edge's level (greens as their parents, finer
// regions as the triangles they refine: ButterflyHierarchy from the parent edges); points
// on edges that do not exist in that mesh (inner edges of triangles split twice in one step)
// take the midpoint. Prolongation::Linear puts every new point at the edge midpoint.
#ifndef dsRedGreen_h
#define dsRedGreen_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsButterfly.h"
#include "dsTriangleMesh.h"

#include <array>
#include <string>
#include <unordered_map>
#include <vector>

namespace dsurf
{
enum class Prolongation
{
  Butterfly,
  Linear
};

struct DEFORMABLESURFACEFILTERS_EXPORT RefinementCounts
{
  bool Ok = false; ///< false: nothing changed, see Error
  std::string Error;
  int RedSplits = 0;        ///< base triangles split 1 -> 4 (marked ones and the closure)
  int ClosureRedSplits = 0; ///< of those, splits forced by the closure, not by a mark
  int Greens = 0;           ///< green pairs present after the step
  int UndoneGreens = 0;     ///< green pairs of before that were merged and red-split
  int NewVertices = 0;
  int ButterflyVertices = 0; ///< new vertices placed by a butterfly / Zorin / boundary rule
  int FallbackVertices = 0;  ///< new vertices placed at the midpoint as a fallback
};

class DEFORMABLESURFACEFILTERS_EXPORT RedGreenRefiner
{
public:
  /// Attach to a level-0 mesh: forget any hierarchy, label every vertex N, level and depth 0,
  /// and build the topology. Returns false with a message when the mesh is not a
  /// manifold triangle mesh.
  bool Initialize(TriangleMesh& mesh, std::string* error);

  /// One red-green step. markedTriangles has one entry per current triangle (non-zero =
  /// refine). The mesh must be the one passed to Initialize() / the last Refine() with
  /// only its points moved. Modifies it in place (points appended, triangles rebuilt,
  /// Labels and Levels set, BuildTopology() called).
  RefinementCounts Refine(TriangleMesh& mesh, const std::vector<char>& markedTriangles,
    Prolongation mode = Prolongation::Butterfly);

  /// Number of refinement steps done since Initialize().
  int GetLevel() const { return this->Level; }
  /// Whether current triangle t is one half of a green pair.
  bool IsGreen(int t) const
  {
    return t >= 0 && t < static_cast<int>(this->TriangleGreen.size()) &&
      this->TriangleGreen[t] >= 0;
  }
  int NumberOfGreens() const { return static_cast<int>(this->Greens.size()); }
  /// The green pair current triangle t belongs to: parent corners (mesh orientation),
  /// the corner starting the split edge, and the midpoint M. false when t is not green.
  bool GetGreen(int t, std::array<int, 3>& parent, int& splitCorner, int& midpoint) const
  {
    if (!this->IsGreen(t))
    {
      return false;
    }
    const Green& g = this->Greens[this->TriangleGreen[t]];
    parent = g.Parent;
    splitCorner = g.SplitCorner;
    midpoint = g.Midpoint;
    return true;
  }
  /// Per current triangle: 1 for green halves (the flags used for butterfly stencils).
  std::vector<char> GreenFlags() const;

  /// Edges of `mesh` that have a midpoint vertex: a triangle using such an edge
  /// would have a T-vertex. 0 after every Refine().
  int CountTVertices(const TriangleMesh& mesh) const;

  /// The vertex labels of docs/METHOD.md §6.4 implied by the current greens: what Refine()
  /// writes to mesh.Labels (see the class comment for the priority M > C > D > N).
  std::vector<unsigned char> ComputeLabels(int numberOfPoints) const;

  /// Per triangle of `mesh` (the current one), the label of each corner within that
  /// triangle: in a green half the corner's role in that green, else N. What
  /// Refine() writes to mesh.CornerLabels; the solver's weights follow it, so a vertex that
  /// is C of one green and D of another still gives the second green's M weight 0.
  std::vector<std::array<unsigned char, 3>> ComputeCornerLabels(const TriangleMesh& mesh) const;

private:
  class Step; // the working state and phases of one Refine() (dsRedGreen.cxx)
  /// Empty when Refine() may run on this mesh with these marks, else the reason.
  std::string CheckRefineInput(
    const TriangleMesh& mesh, const std::vector<char>& markedTriangles) const;

  struct Green
  {
    std::array<int, 3> Parent; ///< corners of the parent, in the mesh orientation
    int SplitCorner;           ///< the split edge joins Parent[SplitCorner] and the next corner
    int Midpoint;              ///< M vertex
  };
  std::vector<Green> Greens;
  std::vector<int> TriangleGreen; ///< per current triangle: index into Greens, -1 if not green
  std::unordered_map<unsigned long long, int> Midpoints; ///< edge key -> midpoint vertex
  std::vector<std::array<int, 2>> ParentEdge; ///< per point: the edge it is the midpoint of, or -1
  int Level = 0;
  int ExpectedPoints = -1, ExpectedTriangles = -1;
};

/// The topology invariants every refinement must keep (docs/METHOD.md §6.3): manifold
/// edges and vertices, consistent orientation, the given Euler characteristic, and,
/// when mustBeClosed, every edge with two triangles (on a closed surface this also means
/// no T-vertex). Runs BuildTopology() on a copy when the mesh's topology is stale.
/// Returns false with a message naming the first broken invariant.
DEFORMABLESURFACEFILTERS_EXPORT bool CheckTopologyInvariants(
  const TriangleMesh& mesh, int expectedEuler, bool mustBeClosed, std::string* message);
} // namespace dsurf

#endif
