// SPDX-License-Identifier: BSD-3-Clause
// The adaptive multilevel schedule of the deformable surface (docs/METHOD.md §6): plain C++,
// no pipeline types; vtkDeformableSurfaceFilter converts data and calls Run().
//
// Per level l = 0, 1, ...:
//   1. external force field at sigma_l (scale space of the volume, potential normalised
//      to [0, 1]; on a decimated grid at coarse sigma and over the surface's neighbourhood
//      after the first level, dsFieldGrid.h); F = ForceWeight * h_l * sigma_l * (-grad P) with h_l
//      the mean edge length of the level's mesh (docs/METHOD.md §6b: force in edge lengths,
//      scale-normalised);
//   2. Gauss-Seidel sweeps until the mean correction of a sweep is below
//      ConvergenceTolerance * h_l * sigma_l / w_l (w_l = PotentialEdgeWidth: the tolerance
//      stops every level at the same share of the edge's width in the potential), or
//      MaxSweepsPerLevel sweeps;
//   3. unless l is the last level: error estimator e(v) = |internal part of the last
//      correction| (docs/METHOD.md §6.2); a triangle is marked when the mean e of its corners,
//      as the distance d = e / gamma * sigma_l / h_l at which the image force balances it (F
//      grows as ~h d / sigma away from an edge), exceeds RefinementThreshold voxels (mean
//      spacing) (every triangle when UniformRefinement). The threshold is absolute: a level
//      refines only where the surface still rests that far from the image's edge, so the
//      triangles follow the detail and the resolution, not a fixed share of every level (as a
//      threshold relative to the level's mean would). The default 0.07 voxel was measured on the
//      phantoms: a binary sphere of radius 32 voxels in 128^3 ends with ~2 500 triangles at mean
//      |d| 0.06 voxel, the cube of half-side 16 with ~6 300 (its edges and corners), a noisy ball
//      of radius 128 in 512^3 with ~11 000 at 0.034 (0.05: 23 000 triangles for 0.031). Adaptively,
//      a triangle whose edges are all shorter than a voxel (mean spacing) is never marked: the
//      image has no finer detail; with the region force on, nor one whose edges are all shorter
//      than sigma_l (the image at sigma_l shows nothing finer), or than 2 sigma_l once the force
//      has faded to an eighth (UnsplitEdgeLength): the region force carries the surface far, so
//      its edges follow the travel rather than sigma (a clicked seed grown to the brain has edges
//      ~sigma_0), and at a coarse sigma the absolute estimator marks nearly every triangle
//      (docs/METHOD.md §9.3);
//   4. red-green refinement (dsRedGreen.h), new points by butterfly prolongation
//      (dsButterfly.h; at edge midpoints with ButterflyProlongation off);
//   5. sigma_{l+1} = sigma_l / 2 when HierarchicalSigma (the kernel support follows
//      sigma: it is 4 sigma in the recursive Gaussian), else sigma stays; never below its floor
//      (SigmaFloorVoxels), and the floor itself when the half would lie less than a third of an
//      octave above it (NextHierarchicalSigma).
// A level with nothing to refine (nothing marked, the marked triangles all below a voxel,
// or the next step over MaxVertices: a warning, once) still goes on to the next, smaller
// sigma with the same mesh, so the surface always ends at the fine scale rather than on
// the blurred edge of a coarse sigma. The run ends (GetStopReason) after the level solved at
// sigma's floor (2/3 of a voxel, SigmaFloorVoxels; hierarchical sigma only), when a level
// would change neither the mesh nor sigma (constant sigma, nothing marked), at the cap of
// MaxLevels levels past the first, after MaxSweeps sweeps, or when a callback asks to abort
// (the surface is valid at every moment).
//
// Beyond the paper (docs/METHOD.md §9): sigma_0 can follow the start (dsInitialSigma.h); a
// region force (dsRegion.h), RegionWeight * h * min(1, sigma_l / sigma_0) * speed * normal,
// joins the edge force; folds are smoothed open on the delivered surface and after levels
// whose mesh resolves their sigma (dsUntangle.h); a start far finer than sigma_0 begins on a
// coarse copy (CoarsenStart); a click whose range came from the classes around it takes front
// levels at sigma's floor while the object lies beyond part of it (FrontTriangles).
//
// The class's sources: dsMultilevel.cxx (the levels, their sweeps and fields, when a level
// rests), dsMultilevelStart.cxx (sigma_0 and the start's preparation), dsMultilevelRegion.cxx
// (the region ranges, models and front) and dsMultilevelRefine.cxx (refinement between levels);
// the state they share across a run is in dsMultilevelRunState.h.
#ifndef dsMultilevel_h
#define dsMultilevel_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsContact.h"
#include "dsFieldGrid.h"
#include "dsInitialSigma.h"
#include "dsPieceField.h"
#include "dsRedGreen.h"
#include "dsScaleSpace.h"
#include "dsSolver.h"
#include "dsTriangleMesh.h"
#include "dsUntangle.h"

#include <functional>
#include <string>
#include <vector>

namespace dsurf
{
/// SubdivideInitialSurface: the start is split until its mean edge length is at most this
/// many first sigmas (see MultilevelParameters::SubdivideInitialSurface).
constexpr double InitialEdgeSigmaRatio = 4.0;
/// Sigma of the constant mode (HierarchicalSigma off) when neither Sigma nor SigmaFraction is
/// given, in voxels (mean spacing): the paper's small sigma for a weak boundary next to a strong
/// one (docs/METHOD.md §6.6); its basin of attraction is ~2 voxels.
constexpr double ConstantSigmaVoxels = 1.0;
/// Sigma's floor with the hierarchical sigma, in voxels (mean spacing): sigma halves level by
/// level, never below this, and the level solved there is the schedule's last (a click's front
/// levels and midpoint level stay there, docs/METHOD.md §9.3). With the force's chain rule
/// (dsScaleSpace.h) an edge at 2/3 voxel is 0.70 voxel wide in the potential; a level at half a
/// voxel (0.59 wide) changed the noise-free phantoms by <= 0.01 voxel and moved the noisy
/// sphere's worst vertex 0.03-0.05 voxel further out (docs/METHOD.md §6 item 1).
constexpr double SigmaFloorVoxels = 2.0 / 3.0;
/// A start of more triangles than this, with a mean edge below sigma_0 / 2, begins the
/// hierarchy on a coarse copy (MultilevelSolver::CoarsenStart).
constexpr int CoarsenAboveTriangles = 100000;

/// The parameters of the schedule. Each is named as the vtkDeformableSurfaceFilter property
/// (and ParaView XML property) it comes from, its comment here is the one description of it in
/// the code and its default initialiser the one home of that property's default: the filter
/// holds this struct and its properties read and write these fields
/// (vtkDeformableSurfaceFilter_PARAMETERS, CONTRIBUTING.md, "Adding a parameter").
struct DEFORMABLESURFACEFILTERS_EXPORT MultilevelParameters
{
  SolverParameters Solver; ///< tau, gamma, projection, label weights, threads
  /// w_edge and w_image: the weights of the edge term |grad(G_sigma * f)| and of the image term
  /// f of the potential, each normalised to [0, 1].
  double EdgeWeight = 1.0;
  double ImageWeight = 0.0;
  double ForceWeight = 1.0; ///< multiplies h * sigma * (-grad P)
  /// sigma_0: Sigma (physical units) when > 0; else SigmaFraction * the mean extent of the
  /// volume when > 0 (the paper's 1/6); else (0, the default) with HierarchicalSigma off the
  /// paper's small constant sigma, ConstantSigmaVoxels voxels (mean spacing); else chosen from
  /// the start (dsInitialSigma.h): the paper's extent / 6 for a start spanning the volume, the
  /// start's (90th-percentile) distance to its nearest edges along the vertex and face normals
  /// for any other, between one voxel and extent / 6 (the filter's field data InitialSigma).
  double Sigma = 0.0;
  double SigmaFraction = 0.0;
  /// How the edge strength is normalised in the potential (dsScaleSpace.h).
  dsurf::EdgeNormalization EdgeNormalization = dsurf::EdgeNormalization::GlobalMaximum;
  /// The region force (dsRegion.h): RegionWeight * h * speed * normal; 0 = off. The default
  /// suits a seed near its object (the whole-head MRI of the README); a click given its range
  /// pulls with at least GivenRangeClickWeight (1, dsRegion.h: a one-click seed sphere growing
  /// to a large object; ObjectRegion::Weight). Its range is IntensityRange when
  /// IntensityRange[0] < IntensityRange[1], else estimated from the image inside and just
  /// outside the start surface (EstimateIntensityRange); without a given range it is off for a
  /// start spanning the image or an open one, so a box around the volume solves the paper's
  /// problem unchanged. A range matching no voxel turns it off with a warning; the range used is
  /// the filter's field data IntensityRange.
  double RegionWeight = 0.3;
  double IntensityRange[2] = { 0.0, 0.0 };
  /// Several objects (docs/METHOD.md §9.9): a range per object, as triples ObjectId, low, high
  /// (the object's id in the start's ObjectId array); an object listed with low < high uses its
  /// range, any other IntensityRange (given or estimated from its own start).
  std::vector<double> ObjectIntensityRanges;
  bool HierarchicalSigma = true; ///< halve sigma per refinement; off = constant sigma_0
  int MaxLevels = 10; ///< cap on the refinement steps (levels 0..MaxLevels at most; see above)
  int MaxSweepsPerLevel = 2000; ///< cap per level (the phantom tests need <= ~130)
  /// Sweeps per parallel region (Solver::Sweeps): progress, abort and the sweep callback
  /// come after each batch, so the callback sees the mesh as of the end of its batch; 1
  /// hands over every sweep's mesh (slower on several threads: threads start per sweep).
  /// Meshes over 50 000 vertices get smaller batches (16 x 50 000 / vertices, at least 1),
  /// so an abort is answered quickly; results do not depend on the batch size.
  int SweepBatch = 16;
  /// Stop the whole run after this many sweeps (0: no limit), exactly there, mid-level if
  /// need be (a warning says so); the surface is valid at every sweep.
  int MaxSweeps = 0;
  /// Stop a level when mean |c| < this * mean edge length * sigma / PotentialEdgeWidth(sigma).
  double ConvergenceTolerance = 1e-3;
  double RefinementThreshold = 0.07; ///< |internal force| in voxels (see above)
  bool UniformRefinement = false;    ///< refine every triangle at every level, not the marked ones
  /// New vertices by the butterfly scheme (Prolongation::Butterfly), else at edge midpoints
  /// (Prolongation::Linear); RefineLevel maps it to the refiner's enum.
  bool ButterflyProlongation = true;
  /// Before level 0, subdivide the start surface uniformly (1 -> 4, midpoints, so its
  /// shape is kept exactly) to the mean edge length nearest InitialEdgeSigmaRatio * sigma_0
  /// (while it exceeds that by more than sqrt 2): a vertex samples the force only where it stands,
  /// so a coarse start (a Box of 12 triangles around a whole volume) needs edges comparable to the
  /// first sigma to be pulled in evenly; the target never below two voxels (mean spacing), which
  /// resolve nothing more. The subdivided surface counts as level 0.
  bool SubdivideInitialSurface = true;
  /// Refinement stops (with a warning) before the mesh would exceed this many vertices (the
  /// red-green closure can add some more).
  long long MaxVertices = 2000000;
  /// Check the topology invariants (closed stays closed, manifold, Euler characteristic,
  /// orientation, no T-vertex) after every refinement (always on in Debug builds); a broken
  /// invariant stops the run with an error.
  bool CheckTopology = false;
};

/// The width of an edge in the potential at scale sigma, sqrt(sigma^2 + voxel^2): the central
/// differences of |grad| and of the potential, and the trilinear reading of the force, widen a
/// sharp edge by about a voxel (docs/METHOD.md §6.1; measured on the binary sphere of radius 32:
/// the force's slope across the boundary gives widths 1.14 and 1.65 voxels at sigma 0.5 and
/// 1.33, i.e. 1.02 and 0.97 voxel added in quadrature). Measured with -grad P as central
/// differences of P; the force's chain rule (dsScaleSpace.h) keeps the edge narrower (0.70 and
/// 1.34 voxels at sigma 2/3 and 1.33), so this width is a conservative one: the levels stop nearer
/// their rest than the same share of the narrower width.
DEFORMABLESURFACEFILTERS_EXPORT double PotentialEdgeWidth(double sigma, double voxel);

/// The next level's sigma with the hierarchical sigma: sigma / 2, or `floor` (sigma's floor,
/// SigmaFloorVoxels in world units) when sigma / 2 lies below 2^(1/3) * floor (a third of an
/// octave); never below the floor, and sigma itself once it is there. This saves a level that
/// would sit barely above the floor's, with its field and its sweeps of the finest mesh (the
/// Colin27 click's sigma went 1.59, 0.80, 0.67 mm; now 1.59, 0.67). Half an octave was too much:
/// the level it merged held a refinement a capsule phantom needed (docs/METHOD.md §6.6).
DEFORMABLESURFACEFILTERS_EXPORT double NextHierarchicalSigma(double sigma, double floor);

/// The region force's fade at level sigma: min(1, sigma / sigma_0) (dsRegion.h; the force
/// shrinks with sigma once below sigma_0).
DEFORMABLESURFACEFILTERS_EXPORT double RegionFade(double sigma, double firstSigma);

/// Whether a front's sizes at its front levels so far (triangles, oldest first) grew at each of
/// the last FrontGrowthLevels levels to more than FrontGrowthFactor times the size before them.
DEFORMABLESURFACEFILTERS_EXPORT bool FrontGrows(const std::vector<long long>& sizes);

/// A click's competitors (EstimateIntensityRange) are looked for within this many sigma_0 of
/// it: sigma_0 from a click is its distance to the nearest edges (dsInitialSigma.h), so the
/// neighbourhood holds the object's class and the classes around it.
constexpr double CompetitorReachSigmas = 4.0;

/// A point whose region speed is at least this is in the object (MultilevelSolver::FrontTriangles).
constexpr double FrontSpeed = 0.5;
/// The front is looked for this many voxels beyond each triangle (FrontTriangles).
constexpr double FrontLookVoxels = 1.0;
/// Looking beyond a triangle samples this many depths from 0 to FrontLookVoxels: the object
/// must go on from the surface out, and a gap of a voxel blurs to a dip about a voxel wide.
constexpr int FrontLookSteps = 5;
/// At most this many samples along a triangle's side when looking beyond it (a side longer than
/// this many voxels is sampled more sparsely than a voxel).
constexpr int FrontGridMax = 16;
/// Front levels at most, beyond MaxLevels: the horned phantom's four horns, 2-4 voxels wide and
/// 25-40 long, are followed to within 1.5 voxels of their ends in 53 (the two-voxel horn's tip
/// moves about 0.2 voxel a level).
constexpr int MaxFrontLevels = 64;
/// A front level sweeps at most this many times (a horn's took 60-80 sweeps each); noise can
/// keep one vertex stepping back and forth for ever.
constexpr int FrontLevelSweeps = 200;
/// A level rests when its vertices step back and forth in place (docs/METHOD.md §9.7): every
/// StallWindowSweeps sweeps, the vertices' mean net displacement over the window is below
/// StallNetShare of their mean corrections summed over it and below StallSigmaShare of sigma,
/// and (a closed start) no object's enclosed volume changed by more than StallVolumeShare of it.
/// A surface that travels or settles keeps most of what it moves; one held where a force
/// changes sign at noise (the region force at its range's end) cancels most of it, and slow
/// drift under that noise that still gains ground (a click growing) changes its volume. An open
/// start's first level only, without the volume.
constexpr int StallWindowSweeps = 32;
constexpr double StallNetShare = 0.3;
constexpr double StallSigmaShare = 0.1;
constexpr double StallVolumeShare = 0.001;
/// Front levels follow a front of at most this share of its object's triangles.
constexpr double FrontShare = 0.1;
/// Front levels stop following an object whose front grew at each of its last FrontGrowthLevels
/// front levels to more than FrontGrowthFactor times what it was before them (FrontGrows). A thin
/// part left behind keeps a front of about its tip, which shrinks as the tip is reached (the
/// horned phantom: 38 triangles, then 23-32, 10-20 and 4-8; a click along a capsule 37, then
/// 12-16); a network of thin parts branches at every level (a click in Colin27's lateral
/// ventricle: 70, 87, 146, 220, ..., 103 605 at the seventeenth, 660 000 vertices and half a
/// litre of CSF and grey matter, the levels running on for tens of minutes).
constexpr int FrontGrowthLevels = 3;
constexpr double FrontGrowthFactor = 2.0;
/// Front levels split the triangles around the front down to this many voxels: a horn two
/// voxels wide needs edges below a voxel around it (with a voxel, the committed horned
/// phantom's narrowest horn stayed unentered: reference -> surface 2.6 voxels; 0.88 with half).
constexpr double FrontEdgeVoxels = 0.5;
/// A front level ends when no vertex moves more than this many voxels in a sweep.
constexpr double FrontRestVoxels = 0.01;

/// The region force's fade (RegionFade) at or below which adaptive refinement leaves coarser
/// triangles unsplit (UnsplitEdgeLength): three halvings after sigma_0, where the force pushes
/// with an eighth of its strength.
constexpr double RegionFadedShare = 1.0 / 8.0;
/// Below RegionFadedShare, triangles whose edges are all shorter than this many sigma_l are
/// not split (above it: one sigma_l).
constexpr double FadedEdgeSigmaRatio = 2.0;

/// Adaptive refinement leaves a triangle unsplit when its edges are all shorter than this
/// (docs/METHOD.md §9.3): the voxel (mean spacing), below which the image shows no detail;
/// with the region force on (region), sigma, and once the force has faded to RegionFadedShare
/// (sigma <= sigma_0 / 8) FadedEdgeSigmaRatio * sigma. The region force carries a surface far
/// and its edges follow the travel, not sigma; while it is strong a mesh coarser than sigma
/// lets it bulge through narrow gaps (a click in KmeansTest leaked with 2 sigma on every
/// level), so there the bound is sigma. Once it has faded the edge force holds the surface,
/// and splitting it to sigma mostly multiplies vertices: the Colin27 click 31 364 -> 18 223
/// vertices, 0.75 -> 0.80 mm, the solve about half as long (docs/RESULTS.md, BENCHMARKS.md).
/// Measured choices (docs/METHOD.md §9.3): the paper's proportion, 4 sigma, lost the detail of
/// a ridged ball (max 0.96 -> 2.33 voxels; 2 sigma: 1.28); from sigma_0 / 4 on, the KmeansTest
/// click changed.
DEFORMABLESURFACEFILTERS_EXPORT double UnsplitEdgeLength(
  double voxel, double sigma, double firstSigma, bool region);

/// The region force of one object: its range and how it is used.
struct DEFORMABLESURFACEFILTERS_EXPORT ObjectRegion
{
  bool On = false;
  double Low = 0, High = 0;
  bool OutwardOnly = false; ///< an estimate without contrast: grow only
  /// A click's range from its competitors (RangeEstimate::Classes): after sigma's floor, front
  /// levels follow the parts the object still lies beyond (FrontTriangles).
  bool FollowsFront = false;
  /// The RegionWeight it pulls with: MultilevelParameters::RegionWeight, at least
  /// GivenRangeClickWeight for a click given its range (dsRegion.h).
  double Weight = 0;
};

/// Why the levels ended (MultilevelSolver::GetStopReason; the StopReason field of the filter).
enum class StopReason
{
  None,       ///< no run yet, or it failed
  SigmaFloor, ///< the level at sigma's floor (2/3 voxel, hierarchical sigma) was solved
  NoDetail,   ///< nothing left to refine and sigma cannot shrink (constant sigma)
  MaxLevels,  ///< the cap on levels was reached first
  MaxSweeps,  ///< the sweep budget of the whole run was used up
  Aborted     ///< the progress or the sweep callback asked to stop
};
/// "sigma floor", "no detail", "MaxLevels", "MaxSweeps", "aborted" or "none".
DEFORMABLESURFACEFILTERS_EXPORT const char* StopReasonName(StopReason reason);

/// One row per sweep, for the convergence table.
struct DEFORMABLESURFACEFILTERS_EXPORT SweepRecord
{
  int Sweep = 0; ///< 1-based, over the whole run
  int Level = 0;
  double Sigma = 0;
  int Vertices = 0;
  int Triangles = 0;
  double MeanCorrection = 0;
  double MaxCorrection = 0;
};

/// Per level, for reports and tests.
struct DEFORMABLESURFACEFILTERS_EXPORT LevelRecord
{
  int Level = 0;
  double Sigma = 0;
  int Sweeps = 0;
  bool Converged = false; ///< mean |c| fell below the tolerance before the cap, or it stalled
  bool Stalled = false;   ///< its vertices stepped back and forth in place (StallWindowSweeps)
  /// Solved with the surface kept off itself (SolveLevelKeptApart): its sweeps, or an earlier
  /// level's, made the surface cross itself.
  bool KeptApart = false;
  bool Front = false; ///< a front level (after sigma's floor, following a thin part)
  int Vertices = 0;
  int Triangles = 0;
  double MeanEdgeLength = 0;
  double Tolerance = 0;        ///< the mean correction below which the level has converged (step 2)
  int MarkedTriangles = 0;     ///< marked for the next refinement (0 on the last level)
  RefinementCounts Refinement; ///< of the refinement that followed this level
  UntangleResult Folds; ///< intersecting triangle pairs after the sweeps, and after smoothing
  /// Force samples of a field in bricks that fell in a brick not computed yet, or beyond the
  /// field's box but inside the image (no force there; the bricks and a following box follow the
  /// surface between batches of sweeps, and a batch goes on only while the sum of its sweeps'
  /// largest corrections is below half the bricks' reach; a vertex is sampled before its own
  /// move, so no sample falls beyond the bricks). This process's samples: a piece of a distributed
  /// image also counts the vertices beyond its part, which other pieces sample.
  long long FieldMisses = 0;
  /// The boxes the level's force field covered: 1, or on a first level whose box follows the
  /// surface one more each time the surface came near its side (MultilevelSolver::FollowSurface).
  int FieldBoxes = 1;
  /// The voxels of the level's (last) field box: the image's region its field was made for.
  long long FieldVoxels = 0;
  /// A front level (after sigma's floor, where the object still lies beyond the surface): it ends
  /// when the largest correction of a sweep is below this (world units); 0 on the other levels.
  double FrontRest = 0;
};

class DEFORMABLESURFACEFILTERS_EXPORT MultilevelSolver
{
public:
  /// Progress in [0, 1]; return false to abort (the surface stays valid).
  using ProgressCallback = std::function<bool(double)>;
  /// Called once per sweep, after the sweep's batch (see SweepBatch); return false to stop.
  using SweepCallback = std::function<bool(const SweepRecord&, const TriangleMesh&)>;

  void SetParameters(const MultilevelParameters& p) { this->Parameters = p; }
  const MultilevelParameters& GetParameters() const { return this->Parameters; }
  /// Makes `coarse` (Points/Triangles) from `fine` with edges of about `edge` (world units);
  /// false when it cannot. Used for a start far finer than sigma_0 (CoarsenStart).
  using CoarsenCallback =
    std::function<bool(const TriangleMesh& fine, double edge, TriangleMesh& coarse)>;
  void SetProgressCallback(ProgressCallback cb) { this->Progress = std::move(cb); }
  void SetSweepCallback(SweepCallback cb) { this->OnSweep = std::move(cb); }
  void SetCoarsenCallback(CoarsenCallback cb) { this->Coarsen = std::move(cb); }

  /// A distributed solve (docs/METHOD.md §9.8): this process holds `piece` of the image, and
  /// Run's image has the whole image's geometry (piece.Whole) and non-null data; its values
  /// are read only through the piece (piece.Image). Every process runs the same
  /// schedule on the same mesh (so every process ends with the same surface); each level's
  /// field is computed per piece (ComputePieceForce), the forces are exchanged per colour
  /// (OwnerForceExchange), the region force's voxel count is summed, and sigma_0 from the
  /// start and the estimated intensity range are made from the pieces
  /// (ChoosePieceInitialSigma, EstimatePieceIntensityRange): every default is distributed. An
  /// empty or invalid piece on any process fails the run on all of them. The progress
  /// callback's answer is agreed by all processes (one maximum per batch of sweeps): when one
  /// asks to stop, all stop after the same sweep. The sweep callback must not stop one alone.
  void SetDistribution(const ImagePiece& piece, const PieceReductions& reduce)
  {
    this->Distributed = true;
    this->Piece = piece;
    this->Reduce = reduce;
  }
  /// The ghost voxels along axis a that a distributed solve of `whole` with parameters p needs
  /// around each piece, for any level's sigma up to sigma_0 as p gives it (or extent / 6, the
  /// largest sigma_0 a start can give): twice the block size of the coarsest level, the sampled
  /// Gaussian's radius and one (at most 13 voxels), one layer for the recursive Gaussian; and
  /// those of the probe of sigma_0 from the start (InitialSigmaProbeGhostVoxels).
  static int DistributedGhostVoxels(
    const MultilevelParameters& p, const ImageGeometry& whole, int a);

  /// Deform `mesh` (any closed or open manifold triangle mesh, Points/Triangles set)
  /// toward the boundaries of the volume `image` (read in place, in its own type).
  /// Returns false with a message on bad input, a broken invariant or a surface that collapsed
  /// (docs/METHOD.md §9.3); the mesh is then left as it was at the last valid state (a
  /// collapsed one as it collapsed).
  bool Run(const ImageView& image, TriangleMesh& mesh, std::string* error);
  /// The same for a float volume, one value per voxel of `geometry`, x fastest.
  bool Run(
    const float* scalars, const ImageGeometry& geometry, TriangleMesh& mesh, std::string* error)
  {
    return this->Run(ImageView::Of(scalars, geometry), mesh, error);
  }

  /// The region model of every object as Run makes it (sigma_0 of the start, each range given or
  /// estimated; docs/METHOD.md §9.3, §9.9), without solving: GetObjectRegions() then holds
  /// them (none On when the region force is off). `mesh` (Points/Triangles, Objects) is
  /// turned outward as Run turns it. False with a message on bad input. Serial; a start Run
  /// would coarsen (§9.5) gives here the range of the start itself.
  bool EstimateRegions(const ImageView& image, TriangleMesh& mesh, std::string* error);

  const std::vector<SweepRecord>& GetSweeps() const { return this->Sweeps; }
  const std::vector<LevelRecord>& GetLevels() const { return this->Levels; }
  const std::vector<std::string>& GetWarnings() const { return this->Warnings; }
  bool GetAborted() const { return this->Aborted; }
  /// Why the last run's levels ended.
  StopReason GetStopReason() const { return this->Stop; }
  /// Uniform subdivisions applied to the start surface before level 0.
  int GetInitialSubdivisions() const { return this->InitialSubdivisions; }
  /// Per vertex of the final mesh, from the last sweep.
  const std::vector<double>& GetErrorIndicator() const { return this->ErrorIndicator; }
  const std::vector<double>& GetDisplacement() const { return this->Displacement; }
  const std::vector<double>& GetExternalForce() const { return this->ExternalForce; }
  /// Most vertices that lay outside the volume (no external force) in one sweep.
  int GetMaxOutsideVertices() const { return this->MaxOutsideVertices; }
  /// Vertices outside the volume in the last sweep (where the surface came to rest).
  int GetFinalOutsideVertices() const { return this->FinalOutsideVertices; }
  double GetFinalMeanCorrection() const
  {
    return this->Sweeps.empty() ? 0.0 : this->Sweeps.back().MeanCorrection;
  }
  /// Sigma of the last level solved.
  double GetFinalSigma() const { return this->Levels.empty() ? 0.0 : this->Levels.back().Sigma; }
  bool GetLastLevelConverged() const
  {
    return !this->Levels.empty() && this->Levels.back().Converged;
  }
  int GetTotalSweeps() const { return static_cast<int>(this->Sweeps.size()); }
  /// How sigma_0 was chosen (Rays 0 when it was given or the start spans the volume).
  const InitialSigmaChoice& GetInitialSigmaChoice() const { return this->SigmaChoice; }
  /// The intensity range the region force used (estimated or given); both 0 when it was off.
  /// With several objects, the first one's whose force was on.
  const double* GetIntensityRange() const { return this->UsedRange; }
  /// The RegionWeight the region force pulled with (ObjectRegion::Weight; with several objects,
  /// the first one's whose force was on); RegionWeight when it was off.
  double GetRegionWeight() const;
  /// The region model of each object (mesh.Objects; one when the start has none).
  const std::vector<ObjectRegion>& GetObjectRegions() const { return this->ObjectRegions; }
  /// Triangle pairs of different objects that intersect on the delivered surface (0 with one
  /// object; dsContact.h keeps it 0, and starts that cross are refused).
  int GetCrossingPairs() const { return this->Crossings; }

  /// The marking rule of step 3, exposed for tests: one mark per triangle.
  static std::vector<char> MarkTriangles(
    const TriangleMesh& mesh, const std::vector<double>& estimator, double threshold, bool uniform);

private:
  MultilevelParameters Parameters;
  ProgressCallback Progress;
  SweepCallback OnSweep;
  CoarsenCallback Coarsen;
  std::vector<SweepRecord> Sweeps;
  std::vector<LevelRecord> Levels;
  std::vector<std::string> Warnings;
  std::vector<double> ErrorIndicator, Displacement, ExternalForce;
  int MaxOutsideVertices = 0;
  int FinalOutsideVertices = 0;
  int InitialSubdivisions = 0;
  bool Aborted = false;
  StopReason Stop = StopReason::None;
  int PlannedLevels = 0; ///< levels to sigma's floor within MaxLevels (progress)
  InitialSigmaChoice SigmaChoice;
  double UsedRange[2] = { 0, 0 };
  std::vector<ObjectRegion> ObjectRegions; ///< per object (one unless the start has several)
  /// Several objects: no step brings two objects' triangles within the clearance (dsContact.h).
  ContactLimiter Contact;
  bool SelfContact = false; ///< the parts of one object are kept apart too
  ContactBounds Bounds;     ///< the limiter's, for the solver
  int Crossings = 0;
  double ProgressReached = 0.0; ///< the largest progress reported so far in this run
  bool Distributed = false;     ///< SetDistribution was called
  ImagePiece Piece;
  PieceReductions Reduce;
  /// Whether the run goes on after this process's progress callback answered `here`
  /// (distributed: every process's answer combined, see SetDistribution).
  bool GoOn(bool here) const;
  struct RunState;
  // Run's steps, in order.
  void ClearResults();
  /// Input checks, sigma_0, PrepareStart, and the solver and force-field settings.
  bool Start(const ImageView& image, TriangleMesh& mesh, RunState& state, std::string* error);
  /// Levels 0..MaxLevels: set up, SolveLevel, EndSweeps, RefineLevel, the next sigma.
  bool RunLevels(const ImageView& image, TriangleMesh& mesh, RunState& state, std::string* error);
  /// SolveLevel, solved again with the surface kept off itself (SelfContact) when its sweeps
  /// made it cross itself; a front level is undone instead (SolveFrontLevel). Returns
  /// SolveLevel's stop.
  bool SolveLevelKeptApart(
    const ImageView& image, TriangleMesh& mesh, RunState& state, LevelRecord& rec);
  /// A front level: SolveLevel, its moves undone (and no front level after it) when they made
  /// the surface cross itself or an object collapse; returns SolveLevel's stop, but for such a
  /// collapse.
  bool SolveFrontLevel(
    const ImageView& image, TriangleMesh& mesh, RunState& state, LevelRecord& rec);
  /// The schedule's last level (before any front levels): sigma at its floor with the
  /// hierarchical sigma, or level MaxLevels.
  bool ScheduleEndsAt(const RunState& state, int level) const;
  /// With the hierarchical sigma: the level's sigma is at its floor (SigmaFloorVoxels).
  bool AtSigmaFloor(const RunState& state) const;
  /// Whether an object's range is a click's competition range (ObjectRegion::FollowsFront):
  /// after the schedule and its front levels, one more level rests it at the local midpoint.
  bool MidpointLevelWanted(const RunState& state) const;
  /// Warns (once a run) that front levels stopped following an object whose front grew
  /// (FrontGrows on its FrontHistory).
  void WarnOfGrowingFront(const TriangleMesh& mesh, RunState& state);
  /// After a level kept apart: its remaining folds smoothed open (SmoothFolds) on any mesh.
  void SmoothKeptApart(TriangleMesh& mesh, LevelRecord& rec);
  /// Each object's region model for a level at sigma: its range, its fade (its own sigma_0's
  /// when each object has one), front levels at full strength for the objects they follow, and
  /// whether the edge force's inward pull is dropped (a click's first levels; docs/METHOD.md §9.3).
  std::vector<Solver::RegionModel> LevelRegionModels(const RunState& state, double sigma) const;
  /// The level's force field (rebuilt when sigma changed), edge and region force scales, and
  /// rec's sigma, sizes and mean edge length.
  bool SetUpLevel(const ImageView& image, TriangleMesh& mesh, RunState& state, LevelRecord& rec,
    std::string* error);
  /// After the sweeps: folds smoothed open (on the last level, and on one whose mesh resolves
  /// its sigma), the per-vertex arrays of the level kept.
  void EndSweeps(const Solver& solver, TriangleMesh& mesh, LevelRecord& rec, bool lastLevel);
  /// Untangle (rec.Folds), with a warning for what remains.
  void SmoothFolds(TriangleMesh& mesh, LevelRecord& rec);
  /// Step 3's marks without the triangles whose edges are all shorter than `unsplit`
  /// (UnsplitEdgeLength; adaptive refinement only).
  /// With `front` (per vertex: a corner of a FrontTriangles triangle; a front level) instead only
  /// the triangles with a front corner and an edge longer than FrontEdgeVoxels.
  std::vector<char> MarkForRefinement(const TriangleMesh& mesh, const LevelRecord& rec,
    double voxel, double unsplit, const std::vector<char>& front) const;
  /// Per triangle: 1 where, from some point of a grid on it about a voxel apart, the image
  /// out along its normal to FrontLookVoxels lies well inside the object's range (region speed,
  /// dsRegion.h, at least FrontSpeed at each of FrontLookSteps depths): the region force would
  /// push the surface on, which has not reached the object's edge there. Collective when
  /// distributed.
  std::vector<char> FrontTriangles(const ImageView& image, const TriangleMesh& mesh) const;
  /// FrontTriangles' samples: per triangle with `divisions` (per side of its grid, 0: none), from
  /// `first[t]` on, 1 where the sample point (FrontSamplePoints) lies in the object (InObjectAt),
  /// else 0; distributed, summed over the processes. Collective when distributed.
  std::vector<double> FrontSamples(const ImageView& image, const TriangleMesh& mesh,
    const std::vector<int>& divisions, const std::vector<long long>& first) const;
  /// Whether the image at x is in `region`'s object (region speed at least FrontSpeed);
  /// distributed, false unless this process owns x's cell.
  bool InObjectAt(const ImageView& image, const Vec3& x, const ObjectRegion& region) const;
  /// Per vertex: 1 on a corner of a front triangle (`triangles`, FrontTriangles) of an object
  /// whose front holds at most FrontShare of its triangles and has not grown at each of its last
  /// front levels (FrontGrows); empty when there is none.
  /// `followed` (per object): whether its front is followed.
  /// `history` (per object): its front's triangles at each front level so far, appended to;
  /// an object whose front grows (FrontGrows) is not followed.
  std::vector<char> FrontOf(const TriangleMesh& mesh, const std::vector<char>& triangles,
    std::vector<char>& followed, std::vector<std::vector<long long>>& history) const;
  /// Steps 3-4: mark, check MaxVertices, record the level, refine (refined: whether it did)
  /// and check the invariants.
  bool RefineLevel(
    TriangleMesh& mesh, RunState& state, LevelRecord& rec, bool& refined, std::string* error);
  /// Step 4 on the marks (recorded in the last level's record); with several objects undone
  /// (refined false) when it would make two of them cross.
  bool Refine(TriangleMesh& mesh, RunState& state, const std::vector<char>& marks,
    Prolongation prolongation, bool& refined, std::string* error);
  /// With MaxLevels >= 1, a start of more than CoarsenAboveTriangles triangles whose mean edge
  /// is below sigma_0 / 2
  /// is replaced by the Coarsen callback's copy with edges of about sigma_0, when that copy
  /// keeps the start's topology (closed or not, Euler characteristic, orientation).
  bool CoarsenStart(TriangleMesh& mesh, RunState& state, std::string* error);
  /// sigma_0 of the run: FirstSigma of the start, or with several objects the largest of each
  /// object's FirstSigma (kept in StartSigmas).
  bool ObjectSigmas(
    const ImageView& image, const TriangleMesh& mesh, double& sigma, std::string* error);
  std::vector<double> StartSigmas; ///< per object, its own sigma_0 (several objects only)
  /// sigma_0 by the rule of Sigma / SigmaFraction / the start.
  bool FirstSigma(
    const ImageView& image, const TriangleMesh& mesh, double& sigma, std::string* error);
  /// Closed pieces turned outward and the region force's range (with RegionWeight > 0; region =
  /// whether it is on): the part of PrepareStart that EstimateRegions shares.
  bool PrepareRegions(const ImageView& image, TriangleMesh& mesh, RedGreenRefiner& refiner,
    double sigma, bool& region, std::string* error);
  /// Before level 0: closed pieces turned outward and the region force's range (with
  /// RegionWeight > 0; region = whether it is on), then the start subdivided to ~4 sigma_0.
  bool PrepareStart(const ImageView& image, TriangleMesh& mesh, RedGreenRefiner& refiner,
    double sigma, bool& region, std::string* error);
  /// The sweeps of one level (rec: its level, sigma and mean edge length): batches, the
  /// convergence test, the records, progress and abort, MaxSweeps. True = stop the run.
  /// A field in bricks (dsFieldBricks.h) gets the bricks the surface comes within reach of
  /// before each batch, and a batch ends early once its vertices may have moved half that reach
  /// (the sum of its sweeps' largest corrections).
  /// A first level on the image's own grid also makes its field again over a larger box when the
  /// surface nears its box's side (FollowSurface), and its batches end as with bricks.
  bool SolveLevel(const ImageView& image, TriangleMesh& mesh, RunState& state, LevelRecord& rec);
  /// The field at state.FieldParameters over `box` (in bricks around `mesh` when FieldInBricks;
  /// distributed, this piece's part) into state.Field. Collective when distributed: false on
  /// every process when it failed on one.
  bool MakeField(const ImageView& image, const TriangleMesh& mesh, RunState& state,
    const VoxelBox& box, std::string* error);
  /// On a first level whose field follows the surface (RunState::FieldFollows): the field made
  /// again over the surface's neighbourhood grown by FieldGrowthShare of its extent once the
  /// surface comes within a sigma of needing more than the box holds. False (the run ends with
  /// RunState::FieldError) when that failed. Collective when distributed (every process holds
  /// the same mesh, so all decide alike).
  bool FollowSurface(
    const ImageView& image, const TriangleMesh& mesh, RunState& state, LevelRecord& rec);
  /// The region force's range of every object (given or estimated, ObjectRange); false = no
  /// region force for any.
  bool RegionRange(const ImageView& image, const TriangleMesh& mesh, double firstSigma);
  /// One object's range (given or estimated from `mesh`, its start); false = no region force
  /// for it (a warning says why, naming the object `which`, except for a start spanning the
  /// image or an open start without a given range).
  bool ObjectRange(const ImageView& image, const TriangleMesh& mesh, double firstSigma,
    const std::string& which, const double given[2], ObjectRegion& model);
  /// The range given for object `object` of `mesh` (ObjectIntensityRanges, else IntensityRange).
  void GivenRange(const TriangleMesh& mesh, int object, double range[2]) const;
  /// Several objects, or one kept off itself: the contact bounds for the next sweeps (Bounds),
  /// from the last sweep's longest step `lastStep` (0 at a level's first); returns how many
  /// sweeps they are for.
  int LimitSteps(const TriangleMesh& mesh, double lastStep);
  /// False (with a message) when the start surfaces of different objects cross.
  bool CheckStartsApart(const TriangleMesh& mesh, std::string* error);
  double Voxel = 0;     ///< the image's mean spacing (the contact's clearance and budget)
  std::string Collapse; ///< why an object's surface collapsed (the run then fails); empty: none
};
} // namespace dsurf

#endif
