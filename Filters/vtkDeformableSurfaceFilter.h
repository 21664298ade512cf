/**
 * @class   vtkDeformableSurfaceFilter
 * @brief   Deforms an initial triangle surface onto the boundaries of a volume.
 *
 * The deformable surface of Lürig, Kobbelt & Ertl (2000): a triangle mesh starting
 * near an object of a 3-D image moves until it rests on the object's boundary,
 * minimising membrane (Tau) and thin-plate (1 - Tau) energies plus the external
 * potential P = -(EdgeWeight |grad(G_sigma * f)| + ImageWeight f).
 *
 * Inputs: port 0 a vtkImageData (the point array chosen with SetInputArrayToProcess,
 * ParaView: Scalars; default the active scalars); port 1 the initial surface, any
 * vtkPolyData with polygons and/or triangle strips, closed or open, any genus,
 * several disjoint pieces at once (SetInitialSurfaceConnection()).
 *
 * How:
 * - The surface is triangulated and coincident points are merged (ParaView's Box
 *   has each face separate, Sphere has a seam), then the topology is built. Vertices
 *   on an open boundary stay fixed. An edge with three or more triangles is an error.
 *   The input is never modified.
 * - The external force is the same code as vtkImageScaleSpaceGradient (normalised
 *   potential, world coordinates: spacing, origin and direction honoured), sampled
 *   trilinearly at every vertex. It is applied in edge lengths (docs/METHOD.md §6b): F = h sigma
 *   (-grad P), h the mean edge length at the start of the level, so Tau and Gamma
 *   keep their meaning at any scale. Vertices outside the volume feel no external
 *   force (warned once).
 * - Each sweep corrects every vertex once, in place (Gauss-Seidel):
 *   c = Gamma (Tau U + (1 - Tau) alpha (-U^2 / alpha) + F'), where U, U^2, alpha are
 *   the umbrella operators and F' is F projected onto the umbrella direction when
 *   F . U > 0, else onto the area-weighted vertex normal (the paper's rule against
 *   self-intersection). Sweeps stop when the mean |c| falls below
 *   ConvergenceTolerance times the mean edge length times sigma / sqrt(sigma^2 + voxel^2),
 *   or after MaxSweepsPerLevel.
 * - Multithreaded (vtkSMPTools, STDThread backend, NumberOfThreads) by a distance-2
 *   colouring of the vertex graph: the result is bit-identical for any thread count.
 *
 * Beyond the paper, for real scans (an object among neighbours, a seed near it): the first
 * sigma follows the start (Sigma), a region force pushes the surface through the object's
 * intensity range (RegionWeight, IntensityRange), folds left by the forces are smoothed
 * open (dsUntangle.h), and a start of more than 100 000 triangles much finer than the first
 * sigma begins on a coarse copy (vertex clustering, kept only when the topology is unchanged;
 * a warning says so).
 *
 * Output 0: the surface (triangles; the input's orientation, except that inward-facing closed
 * pieces are turned outward when the region force is on; the merged input's points in their
 * order, refined, unless the start was coarsened) with point arrays Normals, Displacement (|c| of
 * the last sweep), ExternalForce (|F|, region force included), ErrorIndicator (|internal part of c|
 * of the last sweep), RefinementLevel, VertexLabel and field data Sweeps, Levels,
 * InitialSubdivisions, FinalMeanCorrection, SelfIntersections (intersecting triangle pairs, found
 * with a bounding-volume hierarchy), Sigma (the last level's), InitialSigma, Converged (the last
 * level), StopReason (why the levels ended: "sigma floor", "no detail", "MaxLevels", "MaxSweeps"
 * or "aborted"), WarmStart and, with the region force, IntensityRange (the range it used).
 * Output 1: a vtkTable, one row per sweep: Sweep, Level, Sigma, Vertices, Triangles,
 * MeanCorrection, MaxCorrection (ParaView plots it in a Line Chart View).
 *
 * Start surface: with SubdivideInitialSurface (default on) a coarse start is first
 * split 1 -> 4 at edge midpoints to the mean edge length nearest 4 sigma_0 (within a factor
 * sqrt 2; the target never below two voxels; before that, the long edges of elongated
 * triangles are halved, TriangleMesh::SplitElongatedEdges), so a
 * Box of 12 triangles around the whole volume is pulled in evenly (field data
 * InitialSubdivisions).
 *
 * Hierarchy (docs/METHOD.md §6, dsMultilevel.h): after a level converges, the error estimator
 * (|internal part of the correction| per vertex) marks every triangle whose corner average, as
 * the distance in voxels at which the image force balances it, exceeds RefinementThreshold (all
 * triangles with UniformRefinement; adaptively, never a triangle whose edges are all shorter
 * than a voxel, nor, with the region force, than the level's sigma, or than 2 sigma once
 * sigma <= sigma_0 / 8: the region force faded to an eighth, docs/METHOD.md §9.3); the marked
 * triangles are red-green refined (no T-vertices, vertex labels N/C/M/D choose the umbrella
 * weights), new vertices are placed by the butterfly scheme, sigma is halved
 * (HierarchicalSigma) and the force field rebuilt.
 * Sigma never goes below 2/3 of a voxel, and goes straight there when half would be less than
 * 1.26 times that (a third of an octave: NextHierarchicalSigma); the level solved there is the
 * last (finer meshes would follow detail the image does not show), so the number of levels
 * follows the resolution:
 * halving from extent / 6 takes 6 levels at 128^3, 8 at 512^3. MaxLevels is a cap. Refinement
 * stops where nothing is marked or before a step would exceed MaxVertices (a warning; the
 * red-green closure can add some more); the levels still halve sigma on the same mesh, so the
 * surface always ends on the fine-scale boundary. With HierarchicalSigma off the run ends when
 * nothing is marked. Field data StopReason (and a debug line) say why the levels ended.
 *
 * Distributed input (pvbatch/pvserver under MPI): the solve is global (every vertex sees the
 * whole force field and its neighbours), so process 0 does it alone. Each process asks for
 * its own piece of the initial surface; the pieces (ghost cells dropped) are gathered on
 * process 0 (through Controller, by default the global controller), where the seam points
 * held by two pieces are merged with the other coincident points. Process 0 outputs the
 * surface and the convergence table; the other processes output an empty surface and an
 * empty table, so nothing is duplicated downstream. The image is requested whole (whole
 * extent, piece 0 of 1) on every process, as the serial algorithm needs: for a large
 * volume this holds one full copy per process (the other processes do not use theirs).
 * With no controller, or one process, the surface is requested whole and nothing is
 * gathered. A script calling the filter on one process only of an MPI job must set the
 * Controller to nullptr, or the gather waits for the others forever. The result equals the
 * serial result on the same gathered surface; the vertex order follows the pieces, so
 * against a serial run on the undivided surface it agrees up to the convergence tolerance.
 *
 * The image in pieces (docs/METHOD.md §9.8): with the default potential (EdgeWeight > 0,
 * ImageWeight 0, the global maximum normalisation) -- whatever sigma_0 and the region force's
 * range, which are made from the pieces -- each process instead requests its piece of the
 * image with the ghost levels the largest sigma_0 its parameters allow needs (extent / 6 when
 * sigma_0 comes from the start, which the request cannot know yet), the gathered surface is sent
 * to every process, and every process runs the same solve (the forces sampled by the owner of
 * each vertex's voxel cell and summed per colour); process 0 outputs the surface (equal to the
 * serial result bit for bit) with field data PieceVoxels (the voxels each process held) and
 * ImageVoxels. Each process holds its piece and a bounded number of ghost layers: one for a
 * level with the recursive Gaussian (sigma from 3 voxels, its state passed from piece to
 * piece), 13 at most for the sampled one, twice the block size for coarse levels (54 at 512^3
 * with every default, which allows for sigma_0 up to extent / 6). A reader that cannot split its file (NIfTI,
 * MetaImage: the whole image on process 0, nothing on the others) leaves the solve to process 0
 * alone. Otherwise an empty or invalid piece on any process is an error on all of them. The sweeps then run on one thread per process; Abort on one process
 * stops all of them after the same sweep (agreed once per batch of sweeps).
 *
 * Caveats: with another potential the whole image is requested (above). Abort stops after the
 * current sweep and outputs the (valid) surface reached so far. A weak boundary next to a strong
 * one needs HierarchicalSigma off, whose default sigma is one voxel (mean spacing).
 */
#ifndef vtkDeformableSurfaceFilter_h
#define vtkDeformableSurfaceFilter_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // for the warm start's copy

#include <vector> // for the time-step snapshots

class vtkImageData;
class vtkMultiProcessController;
class vtkTable;
class vtkDataArray;
namespace dsurf
{
struct ImageVolume;
struct MultilevelParameters;
class MultilevelSolver;
struct TriangleMesh;
}

class DEFORMABLESURFACEFILTERS_EXPORT vtkDeformableSurfaceFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkDeformableSurfaceFilter* New();
  vtkTypeMacro(vtkDeformableSurfaceFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The initial surface (port 1); the image is port 0 (SetInputConnection(0, ...)).
   */
  void SetInitialSurfaceConnection(vtkAlgorithmOutput* output);
  void SetInitialSurfaceData(vtkDataObject* surface);

  ///@{
  /**
   * Tau: membrane (1) versus thin-plate (0) share of the internal energy. Default 0.1.
   */
  vtkSetClampMacro(Tau, double, 0.0, 1.0);
  vtkGetMacro(Tau, double);
  ///@}

  ///@{
  /**
   * Gamma: damping of each correction. Default 0.07. Values above 0.5 make the
   * iteration diverge; they are clamped with a warning.
   */
  virtual void SetGamma(double gamma);
  vtkGetMacro(Gamma, double);
  ///@}

  ///@{
  /**
   * Weights of the edge term |grad(G_sigma * f)| and the image term f of the external
   * potential, each normalised to [0, 1]. Defaults: EdgeWeight 1, ImageWeight 0.
   */
  vtkSetClampMacro(EdgeWeight, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(EdgeWeight, double);
  vtkSetClampMacro(ImageWeight, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ImageWeight, double);
  ///@}

  ///@{
  /**
   * The first Gaussian sigma. Sigma > 0: that, in world units. Else SigmaFraction > 0: that
   * fraction of the mean extent of the image (the paper's 1/6 = 0.1667). Both 0 (the
   * defaults: Sigma 0, SigmaFraction 0): one voxel (mean spacing) with HierarchicalSigma off;
   * else chosen from the start surface (dsInitialSigma.h). A start
   * spanning the image (a box around the whole volume) begins at the paper's extent / 6; any other
   * start is taken to lie near its object, and sigma_0 is the 90th percentile of its distance to
   * the nearest edge along the vertex and face normals, between one voxel and extent / 6 (field
   * data InitialSigma).
   */
  vtkSetClampMacro(Sigma, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Sigma, double);
  vtkSetClampMacro(SigmaFraction, double, 0.0, 1.0);
  vtkGetMacro(SigmaFraction, double);
  ///@}

  enum EdgeNormalizationModes
  {
    GLOBAL_MAXIMUM = 0,
    LOCAL = 1
  };
  ///@{
  /**
   * How the edge strength g = |grad(G_sigma * f)| is normalised in the potential.
   * GLOBAL_MAXIMUM (default): g / max g, the strongest edge of the volume sets the scale.
   * LOCAL: g / (G_2sigma * g + 0.05 max g), each edge against the edge strength around it, so
   * a weak boundary far from a strong one is as strong as the strong one. (On the whole-head
   * MRI the region force, not the normalisation, is what keeps the skin from muting the brain;
   * docs/METHOD.md says what was measured.)
   */
  vtkSetClampMacro(EdgeNormalization, int, GLOBAL_MAXIMUM, LOCAL);
  vtkGetMacro(EdgeNormalization, int);
  ///@}

  ///@{
  /**
   * The region ("balloon") force, beyond the paper (dsRegion.h): along the vertex normal,
   * outward where the image under the vertex lies in IntensityRange, inward where it does not
   * (speed clamp(min(I - lo, hi - I) / (0.1 (hi - lo)), -1, 1), in edge lengths, times
   * RegionWeight, shrinking with sigma level by level), added to the edge force before the
   * paper's projection rule. RegionWeight 0.3 (default) suits a seed near its object (the
   * whole-head MRI of the README), ~1 a one-click seed sphere growing to a large object given
   * its IntensityRange; 0 turns it off. IntensityRange [lo, hi]
   * with lo < hi is used as given. Otherwise (default [0, 0]) it is estimated from the image
   * inside and just outside the start surface (EstimateIntensityRange), and the force is off
   * for a start spanning the whole image (nothing outside it to compare with) or an open one
   * (no inside), so a box around the volume solves the paper's problem unchanged. The range used
   * is in the field data IntensityRange. A range matching no voxel turns the force off with a
   * warning. Defaults: RegionWeight 0.3, IntensityRange [0, 0].
   */
  vtkSetClampMacro(RegionWeight, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RegionWeight, double);
  vtkSetVector2Macro(IntensityRange, double);
  vtkGetVector2Macro(IntensityRange, double);
  ///@}

  ///@{
  /**
   * Stop a level after this many sweeps (a cap; levels normally stop on
   * ConvergenceTolerance first). Default 2000.
   */
  vtkSetClampMacro(MaxSweepsPerLevel, int, 1, 1000000);
  vtkGetMacro(MaxSweepsPerLevel, int);
  ///@}

  ///@{
  /**
   * A level has converged when the mean |c| of a sweep is below this fraction of the
   * mean edge length, times sigma / sqrt(sigma^2 + voxel^2) (the width of an edge in the
   * potential, dsurf::PotentialEdgeWidth). Default 1e-3.
   */
  vtkSetClampMacro(ConvergenceTolerance, double, 0.0, 1.0);
  vtkGetMacro(ConvergenceTolerance, double);
  ///@}

  ///@{
  /**
   * Cap on the refinement steps after the first level (default 10, the most; 0 = a single level
   * on the initial mesh). The levels end before it at sigma's floor (2/3 voxel) or, with
   * constant sigma, when nothing is left to refine (field data StopReason).
   */
  vtkSetClampMacro(MaxLevels, int, 0, 10);
  vtkGetMacro(MaxLevels, int);
  ///@}
  ///@{
  /**
   * A triangle is refined when the mean error estimator (the internal force) of its corners,
   * as the distance at which the image force balances it, exceeds RefinementThreshold voxels
   * (mean spacing): absolute, so a level refines only where the surface still rests away from
   * the image's edge. Default 0.07. Smaller refines more.
   */
  vtkSetClampMacro(RefinementThreshold, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RefinementThreshold, double);
  ///@}
  ///@{
  /**
   * Refine every triangle at every level instead of the marked ones. Default off.
   */
  vtkSetMacro(UniformRefinement, bool);
  vtkGetMacro(UniformRefinement, bool);
  vtkBooleanMacro(UniformRefinement, bool);
  ///@}

  ///@{
  /**
   * Before the first level, subdivide the initial surface uniformly (midpoints: its
   * shape is kept) until its mean edge length is at most 4 x the first sigma (but not
   * below two voxels), so a
   * coarse start such as a Box of 12 triangles around the whole volume is sampled
   * finely enough for the force to pull it in evenly. Default on. The field data
   * InitialSubdivisions says how many times it was subdivided.
   */
  vtkSetMacro(SubdivideInitialSurface, bool);
  vtkGetMacro(SubdivideInitialSurface, bool);
  vtkBooleanMacro(SubdivideInitialSurface, bool);
  ///@}
  ///@{
  /**
   * Halve sigma (and the kernel support) at every refinement. Default on. Off keeps
   * sigma constant: for a weak boundary near a strong one; without Sigma or SigmaFraction that
   * sigma is the paper's small one, one voxel (mean spacing).
   */
  vtkSetMacro(HierarchicalSigma, bool);
  vtkGetMacro(HierarchicalSigma, bool);
  vtkBooleanMacro(HierarchicalSigma, bool);
  ///@}
  ///@{
  /**
   * Place new vertices by the butterfly scheme (default on) or at edge midpoints.
   */
  vtkSetMacro(ButterflyProlongation, bool);
  vtkGetMacro(ButterflyProlongation, bool);
  vtkBooleanMacro(ButterflyProlongation, bool);
  ///@}
  ///@{
  /**
   * Refinement stops (with a warning) before the mesh would exceed this many vertices.
   * Default 2 000 000.
   */
  vtkSetClampMacro(MaxVertices, vtkIdType, 4, VTK_ID_MAX);
  vtkGetMacro(MaxVertices, vtkIdType);
  ///@}
  ///@{
  /**
   * Check the topology invariants (closed stays closed, manifold, Euler characteristic,
   * orientation, no T-vertex) after every refinement; a failure is an error. Default
   * off (always on in Debug builds).
   */
  vtkSetMacro(CheckTopology, bool);
  vtkGetMacro(CheckTopology, bool);
  vtkBooleanMacro(CheckTopology, bool);
  ///@}

  ///@{
  /**
   * Threads for the solver and the force computation; 0 (default) = all cores.
   * The result does not depend on it.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Diagnostic switch, default on: apply the paper's self-intersection rule
   * (project the external force onto the umbrella direction or the normal).
   * Off applies the raw force, which folds surfaces; for tests and comparisons only.
   */
  vtkSetMacro(ProjectExternalForce, bool);
  vtkGetMacro(ProjectExternalForce, bool);
  vtkBooleanMacro(ProjectExternalForce, bool);
  ///@}

  ///@{
  /**
   * Stop the whole run after this many sweeps (default 0: no limit), exactly there, mid-level
   * if need be, with a warning: a budget for huge starts, and "the surface after n sweeps".
   */
  vtkSetClampMacro(MaxSweeps, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaxSweeps, int);
  ///@}

  ///@{
  /**
   * Convergence as time steps (default off): the output reports time steps 0, S, 2S, ...
   * (S = SweepsPerTimeStep, default 20; the time value is the number of sweeps, at most 1000
   * steps up to the schedule's cap), and the surface at time t is the one after t sweeps (the
   * last surface from the end of the solve on; time 0 is the start surface). The first request
   * solves the whole schedule once and keeps a snapshot every S sweeps (points and triangles,
   * ~24 bytes a vertex and 32 a triangle: 25 snapshots of 14 000 vertices ~ 20 MB; at most
   * 1000 snapshots and 512 MB, later steps show the final surface); every other step, forward
   * or back, comes from that cache until a parameter or an input changes. Serial only: a
   * distributed run, or an aborted one, is not cached (every step solves again). Snapshots
   * carry the geometry and the field data Sweeps; the final step carries every array. The
   * inputs are asked for no particular time. Defaults: AnimateSweeps off, SweepsPerTimeStep 20.
   */
  vtkSetMacro(AnimateSweeps, bool);
  vtkGetMacro(AnimateSweeps, bool);
  vtkBooleanMacro(AnimateSweeps, bool);
  vtkSetClampMacro(SweepsPerTimeStep, int, 1, 1000000);
  vtkGetMacro(SweepsPerTimeStep, int);
  ///@}

  ///@{
  /**
   * Warm start, the paper's interactive tuning (default off): when on, an update after a
   * change of the filter's own parameters (Tau, Gamma, the weights, Sigma, the region force,
   * the hierarchy, the Scalars array...) starts from the last surface computed while it was on
   * instead of the initial surface; a change of either input (a new image or a new start
   * surface) starts over. Serial only: a distributed run always starts from the initial
   * surface. Memory: one copy of the last result (points and triangles). A warm-started surface
   * depends on the session's history: a saved state reloaded computes it from the start.
   */
  vtkSetMacro(ContinueFromLastResult, bool);
  vtkGetMacro(ContinueFromLastResult, bool);
  vtkBooleanMacro(ContinueFromLastResult, bool);
  ///@}

  ///@{
  /**
   * Processes whose surface pieces are gathered (default: the global controller). nullptr
   * or one process: serial behaviour.
   */
  void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  /**
   * The convergence table (output port 1).
   */
  vtkTable* GetConvergenceTable();

protected:
  vtkDeformableSurfaceFilter();
  ~vtkDeformableSurfaceFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // The solver's parameters: their defaults are dsurf::MultilevelParameters' (the constructor
  // copies them through ExchangeParameters), each under the same name there.
  double Tau{};
  double Gamma{};
  double EdgeWeight{};
  double ImageWeight{};
  double Sigma{};
  double SigmaFraction{};
  int EdgeNormalization{};
  double RegionWeight{};
  double IntensityRange[2]{};
  int MaxSweepsPerLevel{};
  double ConvergenceTolerance{};
  int MaxLevels{};
  double RefinementThreshold{};
  bool UniformRefinement{};
  bool SubdivideInitialSurface{};
  bool HierarchicalSigma{};
  bool ButterflyProlongation{};
  vtkIdType MaxVertices{};
  bool CheckTopology{};
  int NumberOfThreads{};
  bool ProjectExternalForce{};
  int MaxSweeps{};
  // This filter's own.
  vtkMultiProcessController* Controller = nullptr;
  bool ContinueFromLastResult = false;
  bool AnimateSweeps = false;
  int SweepsPerTimeStep = 20;

  // AnimateSweeps' cache: a snapshot every SweepsPerTimeStep sweeps, the final output, and
  // what they were computed from (inputs and this filter's parameters).
  std::vector<vtkSmartPointer<vtkPolyData>> Snapshots;
  vtkSmartPointer<vtkPolyData> AnimationResult;
  vtkSmartPointer<vtkTable> AnimationTable;
  vtkMTimeType AnimationKey[3] = { 0, 0, 0 };
  const void* AnimationInputs[2] = { nullptr, nullptr };
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// The surface at time t (sweeps) from the cache into `output`.
  void ServeTimeStep(double t, vtkPolyData* output);
  /// With AnimateSweeps, time t from the cache when it holds these inputs and parameters
  /// (key: their modification times); false: not cached, solve.
  bool ServeFromCache(vtkImageData* image, vtkPolyData* surface, const vtkMTimeType key[3],
    double t, vtkPolyData* output, vtkTable* table);

private:
  /// The one mapping between this filter's solver properties and the core's parameters of
  /// the same names: into `core` (toCore) or from it (the constructor takes the defaults).
  void ExchangeParameters(dsurf::MultilevelParameters& core, bool toCore);
  /// The image array read in place in its own type (dsVTKImage.h); false (an error said why) for
  /// a bad or constant one.
  bool ReadImage(vtkImageData* image, vtkDataArray* array, dsurf::ImageVolume& volume);
  /// The start surface as the core's mesh, consistently oriented; false (an error said why).
  bool StartMesh(vtkPolyData* start, dsurf::TriangleMesh& mesh);
  /// An error naming the first parameter that is NaN or infinite (the clamps let NaN through).
  bool ParametersAreFinite();
  /// Run the solver with this filter's parameters, filling the convergence table and the
  /// time steps' snapshots; false (an error said why) when it fails.
  bool Solve(const dsurf::ImageVolume& volume, dsurf::TriangleMesh& mesh,
    dsurf::MultilevelSolver& solver, vtkTable* table);
  /// The solver's warnings and debug lines.
  void Report(const dsurf::MultilevelSolver& solver);
  /// Distributed, with the default potential (see the class comment): the image is requested
  /// in pieces and solved by every process.
  bool ImageInPieces();
  /// Whether the image requested in pieces came whole to process 0 and empty to the others (a
  /// reader that cannot split its file): then process 0 solves alone. Collective.
  bool ImageOnProcessZeroOnly(vtkImageData* image, const int wholeExtent[6]);
  /// That solve (docs/METHOD.md §9.8): the local input checks agreed by all processes first,
  /// then the core on this process's piece; process 0 delivers the surface.
  void SolveOnPieces(vtkImageData* image, vtkDataArray* array, vtkPolyData* surface,
    const int wholeExtent[6], vtkPolyData* output, vtkTable* table);
  bool OnPieces = false; ///< SolveOnPieces is running: one solver thread
  /// The warm start's copy and the time steps' cache of this result (complete: not aborted,
  /// serial).
  void KeepResult(vtkImageData* image, vtkPolyData* surface, const vtkMTimeType key[3],
    bool complete, vtkPolyData* output, vtkTable* table);

  // The warm start's state: the last output and the inputs it came from.
  vtkSmartPointer<vtkPolyData> LastResult;
  vtkMTimeType LastImageTime = 0, LastSurfaceTime = 0;
  const void* LastImage = nullptr;
  const void* LastSurface = nullptr;

private:
  vtkDeformableSurfaceFilter(const vtkDeformableSurfaceFilter&) = delete;
  void operator=(const vtkDeformableSurfaceFilter&) = delete;
};

#endif
