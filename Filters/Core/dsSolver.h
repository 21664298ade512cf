// SPDX-License-Identifier: BSD-3-Clause
// The single-level deformable-surface solver (docs/METHOD.md §3-5): umbrella operators with
// the label weights of docs/METHOD.md §6.4 (per edge, from the labels its triangles give its
// ends: TriangleMesh::CornerLabels), one fixed-point step per vertex, Gauss-Seidel
// in place, and the self-intersection rule for the external force (dsSelfIntersectionRule.h).
// Plain C++, no pipeline types; the hierarchy (refinement, sigma halving) drives it from
// outside. The parallel sweeps run as steps of a StepScheduler (dsStepScheduler.h).
//
// Parallel Gauss-Seidel: the vertex graph is coloured at distance 2 (two vertices
// of one colour share no edge and no U^2 stencil), colours are swept in sequence and
// the vertices of one colour in parallel. A vertex's update reads only points of
// earlier colours or not yet updated ones, never one being written concurrently, so
// the result does not depend on the number of threads (bit-identical).
//
// For the parallel sweep the solver keeps its own copy of the mesh in breadth-first
// order (positions, neighbour lists, triangle fans): each thread owns one contiguous
// share of every colour, i.e. one compact region of the surface, so the points it
// reads were mostly written by itself and stay in its cache. Results are written back
// to the mesh (its own point order) and the per-vertex outputs (indexed by the mesh's
// ids) at the end of a call, not per vertex: scattered writes from two threads to
// shared cache lines would cost more than the arithmetic.
#ifndef dsSolver_h
#define dsSolver_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsScaleSpace.h"
#include "dsTriangleMesh.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace dsurf
{
struct ContactBounds; // dsContact.h

struct DEFORMABLESURFACEFILTERS_EXPORT SolverParameters
{
  double Tau = 0.1; ///< membrane (1) vs thin plate (0), docs/METHOD.md §2
  /// Damping of the correction, docs/METHOD.md §4. Above 0.5 the iteration diverges: the filter
  /// clamps values outside 0 < Gamma <= 0.5, with a warning.
  double Gamma = 0.07;
  /// docs/METHOD.md §5 rule (project F onto the umbrella or the normal). false is a test-only
  /// switch that applies the raw force, to show what the rule prevents.
  bool ProjectExternalForce = true;
  /// docs/METHOD.md §6.4 label weights on (default). false weighs every
  /// neighbour 1 whatever the labels: a test-only switch showing what the table prevents
  /// (vertices drifting on red-green borders).
  bool UseLabelWeights = true;
  /// 0 = the machine's hardware concurrency. The result does not depend on it (a distance-2
  /// colouring of the vertex graph).
  int NumberOfThreads = 0;
};

struct DEFORMABLESURFACEFILTERS_EXPORT SweepStatistics
{
  double MeanCorrection = 0; ///< mean |c| over the vertices moved in the sweep
  double MaxCorrection = 0;  ///< max |c|
  int MovedVertices = 0;     ///< vertices corrected (not on an open boundary, not isolated)
  int OutsideVertices = 0;   ///< vertices that sampled no force because they lie outside the volume
};

/// The external force of one vertex of the colour being swept, between its computation and its
/// use (Solver::SetForceExchange).
struct DEFORMABLESURFACEFILTERS_EXPORT VertexForce
{
  Vec3 Position{ 0, 0, 0 }; ///< where the force was sampled (world coordinates)
  /// F before the docs/METHOD.md §5 rule: the edge force (forceScale applied) plus the region
  /// force.
  Vec3 Force{ 0, 0, 0 };
  int Outside = 0; ///< 1: no edge force was sampled, the vertex lies outside the field's volume
};

/// Called once per colour of every sweep with the forces of that colour's vertices (in the
/// solver's order, the same for equal meshes), after they were sampled and before any is
/// applied; it may replace Force and Outside. A distributed solve passes this to combine the
/// forces that each process sampled in its piece of the volume (vtkDeformableSurfaceFilter).
using ForceExchange = std::function<void(VertexForce* forces, int count)>;

class DEFORMABLESURFACEFILTERS_EXPORT Solver
{
public:
  void SetParameters(const SolverParameters& parameters) { this->Parameters = parameters; }
  const SolverParameters& GetParameters() const { return this->Parameters; }

  /// The mesh to deform in place. It must have BuildTopology() done. Rebuilds the
  /// colouring and the weights (from Labels / CornerLabels): call again after the
  /// connectivity or the labels changed (refinement).
  void SetMesh(TriangleMesh* mesh);
  TriangleMesh* GetMesh() const { return this->Mesh; }

  /// External force F(x) = forceScale * field->SampleForce(x); nullptr = no external force.
  /// The field is not copied and must outlive the sweeps.
  void SetForceField(const ForceField* field, double forceScale)
  {
    // Sampled through a pointer set here, in the caller's code, so the solver library
    // itself does not depend on the force implementation (refinement-only users link
    // without it).
    this->Field = field;
    this->ForceScale = forceScale;
    this->Sampler = field ? &Solver::SampleField : nullptr;
  }

  /// The region force (dsRegion.h): scale * RegionSpeed(I(x), low, high) * n at every vertex,
  /// I sampled trilinearly in `image` (read in place, in its own type), n the unit
  /// area-weighted normal (outward for an outward-oriented surface). It is added to the edge
  /// force before the projection rule. scale 0 or no image data: none. outwardOnly: the
  /// negative speeds are dropped (grow inside the range, leave the rest to the edge force).
  void SetRegionForce(
    const ImageView& image, double low, double high, double scale, bool outwardOnly = false)
  {
    RegionModel model;
    model.Low = low;
    model.High = high;
    model.OutwardOnly = outwardOnly;
    this->SetRegionForce(image, std::vector<RegionModel>{ model }, scale);
  }
  /// The region force of several objects (docs/METHOD.md §9.9): each vertex reads the model of
  /// its object (the mesh's Objects; model 0 when it has none); a model that is not On gives its
  /// object no region force.
  struct RegionModel
  {
    double Low = 0, High = 0;
    bool OutwardOnly = false;
    bool On = true;
    double Scale = 1.0; ///< times the force's scale: the object's own fade
    /// The edge force's pull against the normal weakens by the region speed where that is
    /// positive (a click's first levels; WithoutInwardEdgePull, docs/METHOD.md §9.3).
    bool DropInwardEdgePull = false;
    /// Above 0 (the voxel's size): the speed's zero lies at the local midpoint of the image
    /// inside and outside the vertex (MidpointSpeed, dsRegion.h; a click's last level).
    double MidpointVoxel = 0;
  };
  void SetRegionForce(const ImageView& image, std::vector<RegionModel> models, double scale)
  {
    this->RegionImage = image;
    this->RegionImage.Data = scale != 0.0 && !models.empty() ? image.Data : nullptr;
    this->RegionModels = std::move(models);
    this->RegionScale = scale;
  }

  /// Where each vertex may go in the next sweeps (mesh order; ContactLimiter, dsContact.h), or
  /// nullptr for anywhere. Not copied: it must outlive the sweeps.
  void SetContactBounds(const ContactBounds* bounds) { this->Bounds = bounds; }

  /// The hook between sampling and applying the external forces of each colour (see
  /// ForceExchange); empty (the default) = none. With a hook a colour is swept in three
  /// phases: (a) the forces of all its vertices are sampled, (b) the hook is called once, on
  /// one of the solver's threads while the others wait, (c) every vertex is corrected with
  /// its force. A vertex's force depends only on its own position and its fan normal, which no
  /// vertex of its colour moves (the distance-2 colouring), so a hook that changes nothing
  /// gives results bit-identical to a sweep without one, for any number of threads. The hook
  /// is called even when the solver has no force field of its own (its vertices then carry
  /// zero forces, Outside 0).
  void SetForceExchange(ForceExchange exchange) { this->Exchange = std::move(exchange); }

  /// One Gauss-Seidel sweep: every vertex not on an open boundary is corrected once,
  /// in place: c = gamma (tau c1 + (1 - tau) alpha c2 + F_projected), p <- p + c.
  SweepStatistics Sweep();

  /// Up to maxSweeps sweeps in one parallel region (starting threads once instead of
  /// per sweep), exactly the same results as as many Sweep() calls. After each sweep,
  /// afterSweep(statistics of that sweep) is called on one of the solver's threads
  /// while the others wait; it returns false to stop. The mesh's points and the
  /// per-vertex outputs are written when Sweeps returns (the callback sees the
  /// points of before the call) and must not be changed by the callback.
  /// Returns the number of sweeps done.
  int Sweeps(int maxSweeps, const std::function<bool(const SweepStatistics&)>& afterSweep);

  /// Per vertex, from the last sweep (0 for fixed vertices):
  /// |gamma (tau c1 + (1 - tau) alpha c2)|, the internal part of the correction (docs/METHOD.md
  /// §6.2), in the same units as Displacement().
  const std::vector<double>& ErrorIndicator() const { return this->ErrorIndicatorValues; }
  /// |c|, the length the vertex moved.
  const std::vector<double>& Displacement() const { return this->DisplacementValues; }
  /// |F| before the docs/METHOD.md §5 projection (forceScale applied).
  const std::vector<double>& ExternalForceMagnitude() const { return this->ForceValues; }

  int NumberOfColors() const { return static_cast<int>(this->Colors.Offsets.size()) - 1; }
  /// Vertices of colour k: ColorVertices()[ColorOffsets()[k] .. ColorOffsets()[k+1]).
  const std::vector<int>& ColorOffsets() const { return this->Colors.Offsets; }
  const std::vector<int>& ColorVertices() const { return this->Colors.Vertices; }

  /// The umbrella operator of vertex v with the docs/METHOD.md §6.4 weights (uniform when the
  /// weights of v sum to zero): U(v) = sum w_i q_i / W - v. Exposed for tests.
  Vec3 Umbrella(int v) const;

private:
  class SweepJob; // the parallel sweeps as StepScheduler steps (dsSolver.cxx)
  /// Builds the colouring if the mesh changed; false when nothing can move (no topology
  /// or no labels yet).
  bool ReadyToSweep();
  int SerialSweeps(int maxSweeps, const std::function<bool(const SweepStatistics&)>& afterSweep);
  int ParallelSweeps(
    int numThreads, int maxSweeps, const std::function<bool(const SweepStatistics&)>& afterSweep);
  /// Copies the mesh's points of local vertices [first, last) into the local copy.
  void RefreshLocal(int first, int last);
  void BuildColoring();
  /// Writes local points and results [first, last) back to the mesh and the outputs.
  void CopyOut(int first, int last);
  /// Partial statistics of the last sweep over one chunk of LocalColors.Vertices.
  struct ChunkSums
  {
    double Sum = 0, Max = 0;
    int Outside = 0;
  };
  void ChunkStatistics(int chunk, ChunkSums& out) const;
  SweepStatistics CombineStatistics(const std::vector<ChunkSums>& chunks) const;
  /// Builds the breadth-first copy of the topology used by the sweeps.
  void BuildLocalLayout();
  void OrderBreadthFirst();   ///< Original and Local
  void CopyTopologyToLocal(); ///< neighbour lists and fans in local ids
  void BuildLocalColors();    ///< LocalColors from Colors
  /// Corrects the vertices [first, last) of LocalColors.Vertices (of one colour) in place, in
  /// the local copy; records the per-vertex values. The external forces of a batch of them are
  /// sampled before any of the batch is corrected (see UpdateRange in dsSolver.cxx).
  void UpdateRange(int first, int last);
  /// Phase (a) of a colour with a force exchange: v's force into `out`.
  void SampleVertexForce(int v, VertexForce& out) const;
  /// Phase (c), and the second half of UpdateRange: correct the vertex v =
  /// LocalColors.Vertices[k] with the external force `force` (applied through the §5 rule when
  /// `external`); `normal` is v's fan normal when already known, else nullptr.
  void CorrectVertex(int k, bool external, const Vec3& force, int outside, const Vec3* normal);
  /// Phases (a) and (c) on the vertices [first, last) of LocalColors.Vertices, of the colour
  /// whose vertices start at `colorBegin` there (ColorForces[k - colorBegin] is vertex k's).
  void SampleRange(int colorBegin, int first, int last);
  void CorrectRange(int colorBegin, int first, int last);
  /// Phase (b): the hook on the colour's forces.
  void ExchangeColor(int color);
  /// The internal part of the correction of local vertex v, tau c1 + (1 - tau) alpha c2
  /// (docs/METHOD.md §3-4), and its umbrella vector U(v) in `umbrella`, from the umbrellas
  /// kept up to date in LocalUmbrellas.
  Vec3 InternalCorrection(int v, Vec3& umbrella) const;
  /// U of the local vertices [first, last) from LocalPoints (at the start of every sweep).
  void ComputeUmbrellas(int first, int last);
  /// LocalBackWeights and LocalAlpha from the local topology and the weights the sweeps use
  /// (label weights or all neighbours alike); LocalUmbrellas sized.
  void BuildRingCoefficients();
  /// The external force F at local vertex v before the docs/METHOD.md §5 rule: the edge force
  /// (outside = 1 when v lies outside the force field's volume) plus the region force; the
  /// region force's fan normal is returned in `normal` (haveNormal) for the rule to reuse.
  Vec3 ExternalForce(int v, int& outside, Vec3& normal, bool& haveNormal) const;
  /// The region speed `speed` at point p (image value `intensity`) with the range's end moved to
  /// the local midpoint along the unit normal n (RegionModel::MidpointVoxel, MidpointSpeed).
  double LocalMidpointSpeed(
    const Vec3& p, const Vec3& n, const RegionModel& model, double intensity, double speed) const;
  /// An edge field or a region force is set (else the external force is zero).
  bool HasExternalForce() const { return (this->Field && this->Sampler) || this->RegionImage.Data; }

  SolverParameters Parameters;
  TriangleMesh* Mesh = nullptr;
  static bool SampleField(const ForceField* field, const double x[3], double f[3])
  {
    return field->SampleForce(x, f);
  }

  const ForceField* Field = nullptr;
  bool (*Sampler)(const ForceField*, const double*, double*) = nullptr;
  double ForceScale = 1.0;
  ForceExchange Exchange;
  std::vector<VertexForce> ColorForces; ///< phase (a) to (c) of one colour, with an exchange
  ImageView RegionImage;                ///< Data nullptr: no region force
  std::vector<RegionModel> RegionModels;
  double RegionScale = 0;
  /// Per local vertex, its object's index into RegionModels (refreshed by every call).
  std::vector<int> LocalObjects;
  const ContactBounds* Bounds = nullptr;
  /// Area-weighted (unnormalised) normal of local vertex v, from its triangle fan.
  Vec3 FanNormal(int v) const;
  bool UniformWeights = true; ///< every label N: the weight lookup can be skipped
  /// The sweeps weigh every neighbour alike: all labels N, or the label weights switched off.
  bool AllNeighboursAlike() const
  {
    return this->UniformWeights || !this->Parameters.UseLabelWeights;
  }
  /// Otherwise the normalised weight of every neighbour slot of the mesh (aligned with
  /// TriangleMesh::Neighbors), from the labels per triangle (docs/METHOD.md §6.4), as the index
  /// of its value in WeightValues: the weights take few distinct values, and an index is half
  /// the bytes of a double for the sweep, which reads the weights of a whole 2-ring per vertex.
  std::vector<std::uint32_t> WeightIds;
  std::vector<double> WeightValues;
  /// Vertices of colour k: Vertices[Offsets[k] .. Offsets[k+1]) (CSR), ascending ids.
  struct ColorClasses
  {
    std::vector<int> Offsets{ 0 }, Vertices;
  };
  ColorClasses Colors;    ///< in mesh ids
  int ColoredPoints = -1; ///< point count the colouring was built for
  std::vector<double> ErrorIndicatorValues, DisplacementValues, ForceValues; ///< mesh order

  // Local (breadth-first) layout: Original[local] = mesh id, Local[mesh id] = local id.
  std::vector<int> Original, Local;
  std::vector<int> LocalNeighborOffsets, LocalNeighbors;
  std::vector<int> LocalFanOffsets;          ///< triangles around each local vertex
  std::vector<std::array<int, 3>> LocalFan;  ///< their corners (local ids, mesh order)
  std::vector<std::uint32_t> LocalWeightIds; ///< WeightIds in the local layout (same slot order)
  std::vector<Vec3> LocalPoints;             ///< refreshed from the mesh by every call
  /// U of every local vertex: computed at the start of a sweep, then moved with the points (a
  /// vertex moved by c moves its own U by -c and each neighbour q's by w_qv c), so that a
  /// vertex's U^2 reads its ring's umbrellas instead of recomputing them from the 2-ring.
  std::vector<Vec3> LocalUmbrellas;
  /// Per local neighbour slot (aligned with LocalNeighbors): the normalised weight the
  /// neighbour gives the slot's vertex (w_qv).
  std::vector<double> LocalBackWeights;
  /// Per local vertex: alpha = 1 + sum_i w_i w_(q_i)v, U^2's coefficient of the vertex itself
  /// (fixed for a mesh, its labels and UseLabelWeights).
  std::vector<double> LocalAlpha;
  /// The weights LocalBackWeights and LocalAlpha were built with: 1 every neighbour weighs
  /// the same, 0 the label weights, -1 not built for this mesh.
  int RingCoefficientsMode = -1;
  struct VertexResult
  {
    double ErrorIndicator = 0, Displacement = 0, Force = 0;
    int Outside = 0;
  };
  /// Per vertex that moves, in the order of LocalColors.Vertices: a colour's results are
  /// written side by side (not one cache line per vertex, a colour's vertices being spread
  /// over the surface) and summed by the statistics in that order. Copied to the mesh order
  /// after a call.
  std::vector<VertexResult> LocalResults;
  ColorClasses LocalColors;   ///< the same classes in local ids
  std::vector<int> ColorSlot; ///< per local vertex: its index in LocalColors.Vertices, or -1
};
} // namespace dsurf

#endif
