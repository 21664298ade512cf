// SPDX-License-Identifier: BSD-3-Clause
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
 * of the last sweep), RefinementLevel, VertexLabel and field data Sweeps, Levels (a click's
 * midpoint level included), InitialSubdivisions, FinalMeanCorrection, SelfIntersections
 * (intersecting triangle pairs, found with a bounding-volume hierarchy), Sigma (the last level's),
 * InitialSigma, Converged (the last level), StopReason (why the levels ended: "sigma floor", "no
 * detail", "MaxLevels", "MaxSweeps" or "aborted"), WarmStart, FrontLevels (levels past sigma's
 * floor that followed a thin part of a click's object), KeptApartLevels (levels solved with the
 * surface kept off itself, after one made it cross itself) and, with the region force,
 * IntensityRange (the range it used) and RegionWeight (the weight it pulled with; with several
 * objects, the first's). Several objects (docs/METHOD.md §9.9): a start with a cell array
 * ObjectId is one object per value, solved together, each with its own sigma_0, start
 * subdivision and region range, never crossing another (each step limited to keep 0.1 voxel between
 * objects); the output then has ObjectId per point and per cell and field data ObjectIds,
 * ObjectVolumes, ObjectVertices, ObjectIntensityRanges (0 0 where the object's region force was
 * off), ObjectRegionWeights (0 where off) and CrossingPairs. Output 1: a vtkTable, one row per
 * sweep: Sweep, Level, Sigma, Vertices, Triangles, MeanCorrection, MaxCorrection (ParaView plots it
 * in a Line Chart View).
 *
 * Start surface: with SubdivideInitialSurface on, a coarse start is first
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
 * schedule's last (finer meshes would follow detail the image does not show; a click's front
 * levels and its midpoint level stay at that sigma), so the number of levels
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
 * with every default, which allows for sigma_0 up to extent / 6). A reader that cannot split its
 * file (NIfTI, MetaImage: the whole image on process 0, nothing on the others) leaves the solve to
 * process 0 alone. Otherwise an empty or invalid piece on any process is an error on all of them.
 * The sweeps then run on one thread per process; Abort on one process stops all of them after the
 * same sweep (agreed once per batch of sweeps).
 *
 * Caveats: with another potential the whole image is requested (above). Abort stops after the
 * current sweep and outputs the (valid) surface reached so far. A weak boundary next to a strong
 * one needs HierarchicalSigma off, whose default sigma is one voxel (mean spacing).
 */
#ifndef vtkDeformableSurfaceFilter_h
#define vtkDeformableSurfaceFilter_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for the parameters and the kept results

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
class SweepAnimation;
struct RegionPreviewMode;
class WarmStart;
}

// The parameters, one line each (CONTRIBUTING.md, "Adding a parameter"): the property's name
// (Set<Name> and Get<Name> in C++, Python and the ParaView XML), its type here, the field that
// holds it, whose initialiser is its one default (Parameters: dsurf::MultilevelParameters,
// dsMultilevel.h and dsSolver.h; Animation and Warm: this filter's own, dsVTKAnimation.h and
// dsVTKWarmStart.h), and its range. From this list come the methods below, PrintSelf and the check
// that refuses a NaN or infinite number at the update (the clamps let NaN through).
//   NUMBER: clamped to [min, max], as vtkSetClampMacro (Get<Name>MinValue/MaxValue too);
//   CUSTOM: a number whose Set<Name> is written by hand (its own rule);
//   FLAG:   on or off, as vtkSetMacro and vtkBooleanMacro (<Name>On/Off too);
//   PAIR:   two numbers, as vtkSetVector2Macro and vtkGetVector2Macro.
// clang-format off
#define vtkDeformableSurfaceFilter_PARAMETERS(NUMBER, CUSTOM, FLAG, PAIR)                          \
  NUMBER(Tau, double, Parameters->Solver.Tau, 0.0, 1.0)                                            \
  CUSTOM(Gamma, double, Parameters->Solver.Gamma)                                                  \
  NUMBER(EdgeWeight, double, Parameters->EdgeWeight, 0.0, VTK_DOUBLE_MAX)                          \
  NUMBER(ImageWeight, double, Parameters->ImageWeight, 0.0, VTK_DOUBLE_MAX)                        \
  NUMBER(Sigma, double, Parameters->Sigma, 0.0, VTK_DOUBLE_MAX)                                    \
  NUMBER(SigmaFraction, double, Parameters->SigmaFraction, 0.0, 1.0)                               \
  NUMBER(EdgeNormalization, int, Parameters->EdgeNormalization, GLOBAL_MAXIMUM, LOCAL)             \
  NUMBER(RegionWeight, double, Parameters->RegionWeight, 0.0, VTK_DOUBLE_MAX)                      \
  PAIR(IntensityRange, double, Parameters->IntensityRange)                                         \
  NUMBER(MaxSweepsPerLevel, int, Parameters->MaxSweepsPerLevel, 1, 1000000)                        \
  NUMBER(ConvergenceTolerance, double, Parameters->ConvergenceTolerance, 0.0, 1.0)                 \
  NUMBER(MaxLevels, int, Parameters->MaxLevels, 0, 10)                                             \
  NUMBER(RefinementThreshold, double, Parameters->RefinementThreshold, 0.0, VTK_DOUBLE_MAX)        \
  FLAG(UniformRefinement, Parameters->UniformRefinement)                                           \
  FLAG(SubdivideInitialSurface, Parameters->SubdivideInitialSurface)                               \
  FLAG(HierarchicalSigma, Parameters->HierarchicalSigma)                                           \
  FLAG(ButterflyProlongation, Parameters->ButterflyProlongation)                                   \
  NUMBER(MaxVertices, vtkIdType, Parameters->MaxVertices, 4, VTK_ID_MAX)                           \
  FLAG(CheckTopology, Parameters->CheckTopology)                                                   \
  NUMBER(NumberOfThreads, int, Parameters->Solver.NumberOfThreads, 0, 1024)                        \
  NUMBER(MaxSweeps, int, Parameters->MaxSweeps, 0, VTK_INT_MAX)                                    \
  FLAG(AnimateSweeps, Animation->AnimateSweeps)                                                    \
  NUMBER(SweepsPerTimeStep, int, Animation->SweepsPerTimeStep, 1, 1000000)                         \
  FLAG(ContinueFromLastResult, Warm->ContinueFromLastResult)                                       \
  FLAG(PreviewRegion, Preview->PreviewRegion)

// The methods each kind of line declares (defined in vtkDeformableSurfaceFilter.cxx).
#define vtkDeformableSurfaceFilter_NUMBER(name, type, field, min, max)                            \
  virtual void Set##name(type value);                                                              \
  virtual type Get##name();                                                                        \
  virtual type Get##name##MinValue();                                                              \
  virtual type Get##name##MaxValue();
#define vtkDeformableSurfaceFilter_CUSTOM(name, type, field)                                       \
  virtual void Set##name(type value);                                                              \
  virtual type Get##name();
#define vtkDeformableSurfaceFilter_FLAG(name, field)                                               \
  virtual void Set##name(bool value);                                                              \
  virtual bool Get##name();                                                                        \
  virtual void name##On();                                                                         \
  virtual void name##Off();
#define vtkDeformableSurfaceFilter_PAIR(name, type, field)                                         \
  virtual void Set##name(type first, type second);                                                 \
  void Set##name(const type values[2]);                                                            \
  virtual type* Get##name() VTK_SIZEHINT(2);                                                       \
  virtual void Get##name(type& first, type& second);                                               \
  virtual void Get##name(type values[2]);
// clang-format on

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

  enum EdgeNormalizationModes
  {
    GLOBAL_MAXIMUM = 0,
    LOCAL = 1
  };

  /**
   * The parameters' Set<Name> and Get<Name> (vtkDeformableSurfaceFilter_PARAMETERS above). What
   * each one does is said once, at the field that holds it: dsurf::MultilevelParameters
   * (Core/dsMultilevel.h; Tau, Gamma, NumberOfThreads in SolverParameters, Core/dsSolver.h),
   * dsVTKAnimation.h (AnimateSweeps, SweepsPerTimeStep), dsVTKWarmStart.h
   * (ContinueFromLastResult) and dsVTKRegionPreview.h (PreviewRegion); for users, with its default
   * and range, in its Documentation in xml/DeformableSurface.xml (the ParaView help).
   * EdgeNormalization takes the values of EdgeNormalizationModes (dsurf::EdgeNormalization,
   * Core/dsScaleSpace.h).
   */
  vtkDeformableSurfaceFilter_PARAMETERS(vtkDeformableSurfaceFilter_NUMBER,
    vtkDeformableSurfaceFilter_CUSTOM, vtkDeformableSurfaceFilter_FLAG,
    vtkDeformableSurfaceFilter_PAIR);

  ///@{
  /**
   * Several objects: the region force's range of the object whose ObjectId is `objectId`
   * (dsurf::MultilevelParameters::ObjectIntensityRanges; ParaView's ObjectIntensityRanges, a
   * table of ObjectId, low, high). An object not listed uses IntensityRange.
   */
  void AddObjectIntensityRange(double objectId, double low, double high);
  void RemoveAllObjectIntensityRanges();
  ///@}

  ///@{
  /**
   * Processes whose surface pieces are gathered (by default the global controller). nullptr
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
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The solver's parameters, held here once (the properties above read and write them).
  std::unique_ptr<dsurf::MultilevelParameters> Parameters;
  /// AnimateSweeps' time steps and their cache.
  std::unique_ptr<dsurf::SweepAnimation> Animation;
  /// ContinueFromLastResult's copy of the last result.
  std::unique_ptr<dsurf::WarmStart> Warm;
  std::unique_ptr<dsurf::RegionPreviewMode> Preview; ///< PreviewRegion (dsVTKRegionPreview.h)
  vtkMultiProcessController* Controller = nullptr;

private:
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
  /// The solved mesh into output 0 (points, arrays, field data; `warm`: it started from the last
  /// result).
  void Deliver(const dsurf::TriangleMesh& mesh, const dsurf::MultilevelSolver& solver, bool warm,
    vtkPolyData* output);
  /// Distributed, with the default potential (see the class comment): the image is requested
  /// in pieces and solved by every process.
  bool ImageInPieces();
  /// That solve (docs/METHOD.md §9.8, dsVTKPieces.h): the local input checks agreed by all
  /// processes first, then the core on this process's piece; process 0 delivers the surface.
  void SolveOnPieces(vtkImageData* image, vtkDataArray* array, vtkPolyData* surface,
    const int wholeExtent[6], vtkPolyData* output, vtkTable* table);
  bool OnPieces = false; ///< SolveOnPieces is running: one solver thread

  vtkDeformableSurfaceFilter(const vtkDeformableSurfaceFilter&) = delete;
  void operator=(const vtkDeformableSurfaceFilter&) = delete;
};

#endif
