// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkDelaunaySeedSurface
 * @brief   Start surface for the deformable surface: the outer boundary of a Delaunay
 *          tetrahedrisation of picked points, after removing tetrahedra.
 *
 * The user picks points on the object's boundary (on slices, from a CSV through
 * TableToPoints, a polyline, the points of any mesh); they are joined by a Delaunay
 * tetrahedrisation (vtkDelaunay3D, Alpha 0, so the tetrahedron numbering depends only on the
 * input); tetrahedra are removed to model non-convex shapes, and the boundary of the remaining
 * tetrahedra is the start surface (Lürig, Kobbelt & Ertl 2000, section 7).
 *
 * A tetrahedron is removed when
 * - its ID is in the RemovedTetrahedra list (IDs as shown by output 1, `TetraId`);
 * - Alpha > 0 and its circumsphere radius exceeds Alpha (computed here on the full
 *   tetrahedrisation, so IDs stay stable when Alpha changes);
 * - UseIntensityRange is on, an image is connected to port 1, and the image value at the
 *   tetrahedron's centroid (trilinear; the active scalars, or the only point array, of one
 *   component: otherwise the rule is skipped with a warning) lies outside
 *   IntensityRange, or the centroid lies outside the image. A seed of a dark cavity or a
 *   bright bone thus follows the object.
 *
 * Input port 0: any vtkPointSet. Input port 1 (optional): vtkImageData for IntensityRange.
 *
 * Output 0: the boundary of the kept tetrahedra, a closed, 2-manifold, outward-oriented
 * triangle surface holding only the points it uses, with point array `SeedPointId` (index of the
 * input point; -1 for points added by subdivision). Pinches (an edge with four or more boundary
 * faces, a vertex where two sheets meet) are resolved by splitting the vertex into one copy per
 * fan, the copies moved 2% of an edge length into their fans; only where that is not enough is
 * a tetrahedron removed. A warning says what was done. Flat tetrahedra exposed at the boundary are
 * dropped. TargetEdgeLength > 0 subdivides the surface (1-to-4 midpoint) until the mean edge length
 * is within a factor sqrt(2) of it, so the solver starts with enough vertices.
 *
 * Output 1: every tetrahedron of the Delaunay complex as a vtkUnstructuredGrid with cell arrays
 * `TetraId` (the stable ID to put in RemovedTetrahedra), `Removed` (0 kept, 1 by ID, 2 by Alpha,
 * 3 by intensity, 4 by pinch resolution, 5 flat at the boundary) and `Circumradius` (to choose
 * Alpha), plus `CentroidValue` when an image is used. Threshold or colour by `Removed`.
 *
 * One click: with one to three finite points (too few for a tetrahedron) the surface is a
 * small closed sphere of radius SeedRadius around each point (an icosahedron subdivided
 * twice: 162 vertices, 320 triangles), each point's vertices carrying its SeedPointId, and the
 * tetrahedra output is empty. Pick one point inside an object and run Deformable Surface with
 * its region force (RegionWeight) to grow it to the object's boundary.
 *
 * Several objects (docs/METHOD.md §9.9): when the input has a point array `ObjectId`, the
 * points of each ObjectId value are seeded on their own, as above (one to three points: a sphere
 * around each; four or more: their Delaunay hull with its own removals), in ascending ObjectId,
 * and every cell of both outputs carries its group's value in a cell array `ObjectId`, which
 * Deformable Surface reads to solve the objects together. TetraIds run on from one group to the
 * next (group by group, in ascending ObjectId). A group that gives no seed (four coplanar points)
 * is an error and empties both outputs. Without the array everything is one group, as before.
 *
 * Bad input (no finite point, four or more points all coplanar, every tetrahedron removed, a
 * NaN parameter) gives an error or warning and an empty surface; NaN/inf points, and points with
 * a coordinate beyond 1e100 (vtkDelaunay3D would overflow), are dropped with a warning; a
 * surface that still overflows (a SeedRadius near the largest double) is an error; points closer
 * than Tolerance x the bounding-box diagonal are merged, with a warning when four or more points
 * merge into fewer than four (a seed sphere around each cluster then).
 *
 * Distributed input (pvbatch/pvserver under MPI): the points of every process are gathered on
 * process 0 (through Controller, by default the global controller), which alone tetrahedrises
 * them and produces both outputs; the other processes output empty data, so the seed is neither
 * partial nor duplicated when it is rendered or saved. Points flagged as ghost duplicates
 * (vtkGhostType) are dropped first; exact duplicates along piece seams are merged by
 * vtkDelaunay3D. SeedPointId then indexes the concatenation of all processes' inputs in process
 * order. The optional image is requested whole (whole extent, piece 0 of 1) on every process,
 * because a centroid may fall anywhere in it. With no controller, or one process, nothing of
 * this happens. A script calling the filter on one process only of an MPI job must set
 * the Controller to nullptr, or the gather waits for the others forever.
 *
 * Caveats: the whole point set is tetrahedrised on one process (no distributed Delaunay).
 * Points with near-cospherical neighbours (e.g. regular grids) produce flat tetrahedra whose
 * IDs are still stable, but they may disappear from the boundary.
 */
#ifndef vtkDelaunaySeedSurface_h
#define vtkDelaunaySeedSurface_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <vector> // for the ID list

class vtkDataArray;
class vtkImageData;
class vtkPolyData;
class vtkMultiProcessController;
class vtkUnstructuredGrid;

class DEFORMABLESURFACEFILTERS_EXPORT vtkDelaunaySeedSurface : public vtkPolyDataAlgorithm
{
public:
  static vtkDelaunaySeedSurface* New();
  vtkTypeMacro(vtkDelaunaySeedSurface, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The optional image (input port 1) used by IntensityRange.
  void SetImageConnection(vtkAlgorithmOutput* output);
  void SetImageData(vtkImageData* image);
  ///@}

  ///@{
  /// IDs (`TetraId` of output 1) of tetrahedra the user deletes.
  void AddRemovedTetrahedron(vtkIdType id);
  void RemoveAllRemovedTetrahedra();
  vtkIdType GetNumberOfRemovedTetrahedra() const;
  vtkIdType GetRemovedTetrahedron(vtkIdType i) const;
  ///@}

  ///@{
  /// Remove tetrahedra whose circumsphere radius exceeds Alpha (world units); 0 (default) keeps
  /// all.
  vtkSetClampMacro(Alpha, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Alpha, double);
  ///@}

  ///@{
  /// Keep only tetrahedra whose centroid's image value lies in IntensityRange (needs port 1).
  /// Defaults: UseIntensityRange off, IntensityRange [0, 1].
  vtkSetMacro(UseIntensityRange, bool);
  vtkGetMacro(UseIntensityRange, bool);
  vtkBooleanMacro(UseIntensityRange, bool);
  vtkSetVector2Macro(IntensityRange, double);
  vtkGetVector2Macro(IntensityRange, double);
  ///@}

  ///@{
  /// Subdivide the surface to about this mean edge length (world units); 0 (default) leaves it
  /// as is.
  vtkSetClampMacro(TargetEdgeLength, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(TargetEdgeLength, double);
  ///@}

  ///@{
  /**
   * Radius, in world units, of the sphere made around each point when only one to three
   * points are given. Default 5 (mm in most medical scans).
   */
  vtkSetClampMacro(SeedRadius, double, 1e-12, VTK_DOUBLE_MAX);
  vtkGetMacro(SeedRadius, double);
  ///@}

  ///@{
  /// Points closer than Tolerance x (bounding-box diagonal) are merged by vtkDelaunay3D.
  /// Default 0.001.
  vtkSetClampMacro(Tolerance, double, 0.0, 1.0);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /// Processes whose points are gathered (default: the global controller). nullptr or one
  /// process: serial behaviour.
  void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  /// Output 1: all tetrahedra with `TetraId`, `Removed`, `Circumradius`.
  vtkUnstructuredGrid* GetTetrahedra();

protected:
  vtkDelaunaySeedSurface();
  ~vtkDelaunaySeedSurface() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// The seed of one object from its finite points (their input ids in inputId), with the
  /// removed tetrahedra `removedIds` (its own TetraIds); false (after an error or a warning)
  /// when it gives no surface.
  bool SeedObject(vtkPolyData* points, const std::vector<vtkIdType>& inputId, vtkImageData* image,
    const std::vector<vtkIdType>& removedIds, vtkPolyData* surface, vtkUnstructuredGrid* tets);
  /// One seed per ObjectId group, appended, cells labelled (see the class comment).
  void SeedObjects(vtkPolyData* points, const std::vector<vtkIdType>& inputId,
    vtkDataArray* objectIds, vtkImageData* image, vtkPolyData* surface, vtkUnstructuredGrid* tets);

  std::vector<vtkIdType> RemovedTetrahedra;
  // The defaults live here (the core, dsSeedSurface.h, takes each value as an argument); the
  // XML's default_values must equal them (Testing/Python/vtkpython_xml_defaults.py).
  double Alpha = 0.0;
  bool UseIntensityRange = false;
  double IntensityRange[2] = { 0.0, 1.0 };
  double TargetEdgeLength = 0.0;
  double SeedRadius = 5.0;
  double Tolerance = 0.001;
  vtkMultiProcessController* Controller = nullptr;

private:
  vtkDelaunaySeedSurface(const vtkDelaunaySeedSurface&) = delete;
  void operator=(const vtkDelaunaySeedSurface&) = delete;
};

#endif
