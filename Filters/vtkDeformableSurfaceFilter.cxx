#include "vtkDeformableSurfaceFilter.h"

#include "dsMultilevel.h"
#include "dsScaleSpace.h"
#include "dsSelfIntersectionCount.h"
#include "dsSolver.h"
#include "dsTriangleMesh.h"
#include "dsVTKImage.h"
#include "dsVTKPieces.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCleanPolyData.h"
#include "vtkDSPolyDataGather.h"
#include "vtkDataArrayRange.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkQuadricClustering.h"
#include "vtkSmartPointer.h"
#include "vtkStaticPointLocator.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkDeformableSurfaceFilter);
vtkCxxSetObjectMacro(vtkDeformableSurfaceFilter, Controller, vtkMultiProcessController);

namespace
{
constexpr double MaxStableGamma = 0.5;

/// The columns of the convergence table (output 1), one row per sweep.
struct ConvergenceColumns
{
  vtkNew<vtkIntArray> Sweep, Level, Vertices, Triangles;
  vtkNew<vtkDoubleArray> Sigma, MeanCorrection, MaxCorrection;

  ConvergenceColumns()
  {
    this->Sweep->SetName("Sweep");
    this->Level->SetName("Level");
    this->Sigma->SetName("Sigma");
    this->Vertices->SetName("Vertices");
    this->Triangles->SetName("Triangles");
    this->MeanCorrection->SetName("MeanCorrection");
    this->MaxCorrection->SetName("MaxCorrection");
  }
  void AddTo(vtkTable* table)
  {
    for (vtkAbstractArray* a :
      std::initializer_list<vtkAbstractArray*>{ this->Sweep, this->Level, this->Sigma,
        this->Vertices, this->Triangles, this->MeanCorrection, this->MaxCorrection })
    {
      table->AddColumn(a);
    }
  }
};

/// Coordinates beyond this are refused like NaN: no image is that large, vtkCleanPolyData's
/// point locator spends seconds per point on them, and the solver's squares overflow.
constexpr double MaxCoordinate = 1e100;

/// Whether every point that a polygon or strip uses has finite coordinates within MaxCoordinate
/// (unused points, which the merging drops, may be anything).
bool UsedPointsInRange(vtkPolyData* input)
{
  vtkNew<vtkIdList> ids;
  for (vtkCellArray* cells : { input->GetPolys(), input->GetStrips() })
  {
    for (vtkIdType c = 0; cells && c < cells->GetNumberOfCells(); ++c)
    {
      cells->GetCellAtId(c, ids);
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        double x[3];
        input->GetPoint(ids->GetId(k), x);
        if (!(std::abs(x[0]) <= MaxCoordinate && std::abs(x[1]) <= MaxCoordinate &&
              std::abs(x[2]) <= MaxCoordinate)) // true for NaN too
        {
          return false;
        }
      }
    }
  }
  return true;
}

/// Drops the points no triangle uses (those of polygons that the merging made degenerate, whose
/// points vtkCleanPolyData keeps): they are no part of the surface. The others keep their order.
void DropUnusedPoints(dsurf::TriangleMesh& mesh)
{
  std::vector<int> newId(mesh.Points.size(), -1);
  for (const auto& t : mesh.Triangles)
  {
    for (int v : t)
    {
      newId[v] = 0;
    }
  }
  int kept = 0;
  for (std::size_t v = 0; v < newId.size(); ++v)
  {
    if (newId[v] == 0)
    {
      mesh.Points[kept] = mesh.Points[v];
      newId[v] = kept++;
    }
  }
  mesh.Points.resize(kept);
  for (auto& t : mesh.Triangles)
  {
    for (int& v : t)
    {
      v = newId[v];
    }
  }
}

/// Triangulate and merge coincident points (copies; the input is untouched), then
/// fill the core mesh. False with a message on bad input.
/// True when two distinct points of `poly` lie within `tolerance` of each other.
bool HasNearDuplicatePoints(vtkPolyData* poly, double tolerance)
{
  if (poly->GetNumberOfPoints() < 2)
  {
    return false;
  }
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i)
  {
    double x[3];
    poly->GetPoint(i, x);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    {
      return false; // the locator's bins need finite bounds; BuildMesh refuses these points
    }
  }
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(poly);
  locator->BuildLocator();
  std::vector<vtkIdType> mergeMap(poly->GetNumberOfPoints());
  locator->MergePoints(tolerance, mergeMap.data());
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i)
  {
    if (mergeMap[i] != i)
    {
      return true;
    }
  }
  return false;
}

bool BuildMesh(vtkPolyData* input, dsurf::TriangleMesh& mesh, std::string& error)
{
  if (!UsedPointsInRange(input))
  {
    error = "the initial surface has a non-finite point coordinate (NaN, infinite or beyond 1e100)";
    return false;
  }
  vtkNew<vtkPolyData> copy;
  copy->ShallowCopy(input);
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(copy);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->Update();
  // Points closer than 1e-6 of the diagonal are merged (a writer's round-off splits a
  // vertex). vtkCleanPolyData with a tolerance takes ~35 s for 640 k points (a
  // marching-cubes start); exact merging (vtkMergePoints) is linear and gives the same
  // points in the same order when no two distinct points are that close, which a static
  // locator checks in about a second. Only then is the tolerance merge run.
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(triangulate->GetOutputPort());
  clean->PointMergingOn();
  clean->ToleranceIsAbsoluteOff();
  clean->SetTolerance(0.0);
  clean->ConvertLinesToPointsOff();
  clean->ConvertPolysToLinesOff();
  clean->ConvertStripsToPolysOff();
  clean->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  clean->Update();
  constexpr double relativeTolerance = 1e-6;
  if (HasNearDuplicatePoints(
        clean->GetOutput(), relativeTolerance * triangulate->GetOutput()->GetLength()))
  {
    clean->SetTolerance(relativeTolerance);
    clean->Update();
  }
  vtkPolyData* tri = clean->GetOutput();
  if (!tri || tri->GetNumberOfPolys() == 0)
  {
    error = "the initial surface has no polygons or triangle strips";
    return false;
  }
  const vtkIdType nPts = tri->GetNumberOfPoints();
  mesh = dsurf::TriangleMesh();
  mesh.Points.resize(nPts);
  for (vtkIdType i = 0; i < nPts; ++i)
  {
    tri->GetPoint(i, mesh.Points[i].data());
  }
  mesh.Triangles.reserve(tri->GetNumberOfPolys());
  auto it = vtk::TakeSmartPointer(tri->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    if (n == 3)
    {
      mesh.Triangles.push_back(
        { static_cast<int>(ids[0]), static_cast<int>(ids[1]), static_cast<int>(ids[2]) });
    }
  }
  // The cleaning drops a triangle that names a point twice but keeps its points.
  DropUnusedPoints(mesh);
  std::string topologyError;
  if (!mesh.BuildTopology(&topologyError))
  {
    error = "the initial surface is not a manifold triangle mesh: " + topologyError;
    return false;
  }
  return true;
}

vtkSmartPointer<vtkDoubleArray> PointArray(const char* name, const std::vector<double>& values)
{
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), a->GetPointer(0));
  return a;
}

/// The deformed mesh as vtkPolyData with the solver's per-vertex arrays.
/// The mesh's points and triangles into `output` (nothing else).
void SetGeometry(const dsurf::TriangleMesh& mesh, vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.NumberOfPoints());
  for (int i = 0; i < mesh.NumberOfPoints(); ++i)
  {
    points->SetPoint(i, mesh.Points[i].data());
  }
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(mesh.NumberOfTriangles(), 3 * mesh.NumberOfTriangles());
  for (const auto& t : mesh.Triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    polys->InsertNextCell(3, ids);
  }
  output->SetPoints(points);
  output->SetPolys(polys);
}

/// The core's coarse copy of a start far finer than sigma_0 (MultilevelSolver::CoarsenStart):
/// vertex clustering on a grid of `edge` (Lindstrom 2000, vtkQuadricClustering), linear in
/// the triangles (~1 s for 1.3 M; decimation by edge collapse took ~60 s). It can merge thin
/// parts: the core keeps the copy only when the topology is unchanged.
bool CoarsenMesh(const dsurf::TriangleMesh& fine, double edge, dsurf::TriangleMesh& coarse)
{
  vtkNew<vtkPolyData> poly;
  SetGeometry(fine, poly);
  double bounds[6];
  poly->GetBounds(bounds);
  // The clustering keeps a dense grid (~90 bytes a cell): at most MaxClusterDivisions cells
  // along the longest side (~190 MB), with edges longer than sigma_0 where that is finer.
  constexpr double MaxClusterDivisions = 128.0;
  const double longest =
    std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  const double step = std::max(edge, (longest + edge) / MaxClusterDivisions);
  vtkNew<vtkQuadricClustering> cluster;
  cluster->SetInputData(poly);
  cluster->AutoAdjustNumberOfDivisionsOff();
  cluster->SetDivisionOrigin(
    bounds[0] - 0.5 * step, bounds[2] - 0.5 * step, bounds[4] - 0.5 * step);
  cluster->SetDivisionSpacing(step, step, step);
  cluster->Update();
  std::string error;
  return BuildMesh(cluster->GetOutput(), coarse, error);
}

void FillOutput(
  const dsurf::TriangleMesh& mesh, const dsurf::MultilevelSolver& solver, vtkPolyData* output)
{
  const int nPts = mesh.NumberOfPoints();
  SetGeometry(mesh, output);

  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(nPts);
  vtkNew<vtkIntArray> levels;
  levels->SetName("RefinementLevel");
  levels->SetNumberOfTuples(nPts);
  vtkNew<vtkUnsignedCharArray> labels;
  labels->SetName("VertexLabel");
  labels->SetNumberOfTuples(nPts);
  for (int i = 0; i < nPts; ++i)
  {
    dsurf::Vec3 n = mesh.AreaWeightedNormal(i);
    const double len = dsurf::Norm(n);
    if (len > 0)
    {
      n = dsurf::operator*(1.0 / len, n);
    }
    normals->SetTuple3(i, n[0], n[1], n[2]);
    levels->SetValue(i, mesh.Levels[i]);
    labels->SetValue(i, mesh.Labels[i]);
  }
  vtkPointData* pd = output->GetPointData();
  pd->SetNormals(normals);
  const auto sized = [nPts](const std::vector<double>& v)
  { return static_cast<int>(v.size()) == nPts ? v : std::vector<double>(nPts, 0.0); };
  pd->AddArray(PointArray("Displacement", sized(solver.GetDisplacement())));
  pd->AddArray(PointArray("ExternalForce", sized(solver.GetExternalForce())));
  pd->AddArray(PointArray("ErrorIndicator", sized(solver.GetErrorIndicator())));
  pd->AddArray(levels);
  pd->AddArray(labels);
}

/// This process's share of the initial surface to send for gathering: its points, polygons
/// and strips (all that BuildMesh uses), without the ghost cells another process owns.
vtkSmartPointer<vtkPolyData> OwnedSurfacePiece(vtkPolyData* surface)
{
  auto piece = vtkSmartPointer<vtkPolyData>::New();
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    return piece;
  }
  vtkSmartPointer<vtkPolyData> owned = surface;
  if (surface->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName()))
  {
    owned = vtkSmartPointer<vtkPolyData>::New();
    owned->DeepCopy(surface); // RemoveGhostCells works in place; the input stays as it is
    owned->RemoveGhostCells();
  }
  piece->SetPoints(owned->GetPoints());
  piece->SetPolys(owned->GetPolys());
  piece->SetStrips(owned->GetStrips());
  return piece;
}

/// AnimateSweeps keeps at most this many snapshots (the time steps reported) and this much
/// memory in them; later steps show the final surface.
constexpr std::size_t MaxSnapshots = 1001;
constexpr double MaxSnapshotBytes = 512.0 * 1024 * 1024;

/// Memory of one snapshot: double points, 64-bit connectivity and offsets.
double SnapshotBytes(const dsurf::TriangleMesh& mesh)
{
  return 24.0 * mesh.NumberOfPoints() + 32.0 * mesh.NumberOfTriangles();
}

/// The mesh's points and triangles as vtkPolyData with field data Sweeps (a time step).
vtkSmartPointer<vtkPolyData> MeshSnapshot(const dsurf::TriangleMesh& mesh, int sweeps)
{
  auto snapshot = vtkSmartPointer<vtkPolyData>::New();
  SetGeometry(mesh, snapshot);
  vtkNew<vtkIntArray> count;
  count->SetName("Sweeps");
  count->InsertNextValue(sweeps);
  snapshot->GetFieldData()->AddArray(count);
  return snapshot;
}

template <typename ArrayT, typename T>
void AddFieldValue(vtkFieldData* fd, const char* name, T value)
{
  vtkNew<ArrayT> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
/// The field data of output 0 (the list the class comment, the XML help and the README give).
void AddFieldData(const dsurf::MultilevelSolver& solver, const dsurf::TriangleMesh& mesh,
  bool region, bool warm, vtkFieldData* fd)
{
  AddFieldValue<vtkIntArray>(fd, "Sweeps", solver.GetTotalSweeps());
  AddFieldValue<vtkIntArray>(fd, "Levels", static_cast<int>(solver.GetLevels().size()));
  AddFieldValue<vtkIntArray>(fd, "InitialSubdivisions", solver.GetInitialSubdivisions());
  AddFieldValue<vtkDoubleArray>(fd, "FinalMeanCorrection", solver.GetFinalMeanCorrection());
  AddFieldValue<vtkIntArray>(fd, "SelfIntersections", dsurf::CountSelfIntersections(mesh));
  AddFieldValue<vtkDoubleArray>(fd, "Sigma", solver.GetFinalSigma());
  AddFieldValue<vtkDoubleArray>(
    fd, "InitialSigma", solver.GetLevels().empty() ? 0.0 : solver.GetLevels().front().Sigma);
  if (region)
  {
    vtkNew<vtkDoubleArray> usedRange;
    usedRange->SetName("IntensityRange");
    usedRange->SetNumberOfComponents(2);
    usedRange->InsertNextTuple(solver.GetIntensityRange());
    fd->AddArray(usedRange);
  }
  AddFieldValue<vtkIntArray>(fd, "Converged", solver.GetLastLevelConverged() ? 1 : 0);
  AddFieldValue<vtkStringArray>(fd, "StopReason", dsurf::StopReasonName(solver.GetStopReason()));
  AddFieldValue<vtkIntArray>(fd, "WarmStart", warm ? 1 : 0);
}
/// One property and its core parameter: copied into the core (toCore) or from it.
template <typename Mine, typename Core>
void Exchange(Mine& mine, Core& core, bool toCore)
{
  if (toCore)
  {
    core = static_cast<Core>(mine);
  }
  else
  {
    mine = static_cast<Mine>(core);
  }
}
} // namespace

//------------------------------------------------------------------------------
vtkDeformableSurfaceFilter::vtkDeformableSurfaceFilter()
{
  dsurf::MultilevelParameters defaults;
  this->ExchangeParameters(defaults, false);
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkDeformableSurfaceFilter::~vtkDeformableSurfaceFilter()
{
  this->SetController(nullptr);
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::SetInitialSurfaceConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

void vtkDeformableSurfaceFilter::SetInitialSurfaceData(vtkDataObject* surface)
{
  this->SetInputData(1, surface);
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::SetGamma(double gamma)
{
  double clamped = gamma;
  if (!(gamma > 0.0) || gamma > MaxStableGamma)
  {
    clamped = (gamma > MaxStableGamma) ? MaxStableGamma : 1e-6;
    vtkWarningMacro("Gamma " << gamma << " is outside the stable range (0, " << MaxStableGamma
                             << "]; using " << clamped << ".");
  }
  if (this->Gamma != clamped)
  {
    this->Gamma = clamped;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkTable* vtkDeformableSurfaceFilter::GetConvergenceTable()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkDeformableSurfaceFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  }
  else
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  }
  return 1;
}

int vtkDeformableSurfaceFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

//------------------------------------------------------------------------------
// AnimateSweeps: time steps 0, S, 2S, ... (the time value is the number of sweeps) up to the
// schedule's cap, at most 1000 of them.
int vtkDeformableSurfaceFilter::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!this->AnimateSweeps)
  {
    return 1; // the inputs' time steps, if any, pass through as for any filter
  }
  const long long S = this->SweepsPerTimeStep;
  long long bound = static_cast<long long>(this->MaxLevels + 1) * this->MaxSweepsPerLevel;
  if (this->MaxSweeps > 0)
  {
    bound = std::min<long long>(bound, this->MaxSweeps);
  }
  const long long steps =
    std::min<long long>(static_cast<long long>(MaxSnapshots) - 1, (bound + S - 1) / S);
  std::vector<double> times(static_cast<std::size_t>(steps + 1));
  for (long long k = 0; k <= steps; ++k)
  {
    times[static_cast<std::size_t>(k)] = static_cast<double>(k * S);
  }
  outInfo->Set(
    vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
  const double range[2] = { 0.0, times.back() };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

void vtkDeformableSurfaceFilter::ServeTimeStep(double t, vtkPolyData* output)
{
  const double k = t < 0 ? -1.0 : std::floor(t / this->SweepsPerTimeStep + 1e-9);
  const bool snapshot = k >= 0 && k < static_cast<double>(this->Snapshots.size());
  output->ShallowCopy(
    snapshot ? this->Snapshots[static_cast<std::size_t>(k)].Get() : this->AnimationResult.Get());
  if (t >= 0)
  {
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  }
}

bool vtkDeformableSurfaceFilter::ServeFromCache(vtkImageData* image, vtkPolyData* surface,
  const vtkMTimeType key[3], double t, vtkPolyData* output, vtkTable* table)
{
  if (!this->AnimateSweeps || !this->AnimationResult || this->AnimationInputs[0] != image ||
    this->AnimationInputs[1] != surface || !std::equal(key, key + 3, this->AnimationKey))
  {
    return false;
  }
  vtkDebugMacro(<< "Time " << t << " from the cache.");
  this->ServeTimeStep(t, output);
  table->ShallowCopy(this->AnimationTable);
  return true;
}

//------------------------------------------------------------------------------
// The Gaussian reaches across the whole volume: ask for all of it, also when the pipeline runs
// distributed, unless the image goes in pieces (ImageInPieces). The surface is asked whole in
// serial, one piece per process when distributed (gathered in RequestData).
int vtkDeformableSurfaceFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* imageInfo = inputVector[0]->GetInformationObject(0);
  if (imageInfo && this->ImageInPieces() &&
    imageInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    // This process's piece and the ghost layers the levels' sigma need (docs/METHOD.md §9.8).
    // The start is not known yet: the ghosts allow for any sigma_0 up to its largest, extent
    // / 6, and for its probe (MultilevelSolver::DistributedGhostVoxels): a bounded number.
    const int* whole = imageInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
    dsurf::ImageGeometry geometry;
    for (int a = 0; a < 3; ++a)
    {
      geometry.Dimensions[a] = whole[2 * a + 1] - whole[2 * a] + 1;
      geometry.Spacing[a] = imageInfo->Has(vtkDataObject::SPACING())
        ? imageInfo->Get(vtkDataObject::SPACING())[a]
        : 1.0;
    }
    dsurf::MultilevelParameters mp;
    this->ExchangeParameters(mp, true);
    int ghost = 0;
    for (int a = 0; a < 3; ++a)
    {
      ghost = std::max(ghost, dsurf::MultilevelSolver::DistributedGhostVoxels(mp, geometry, a));
    }
    imageInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(),
      this->Controller->GetLocalProcessId());
    imageInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(),
      this->Controller->GetNumberOfProcesses());
    imageInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), ghost);
    imageInfo = nullptr; // no whole-image request below
  }
  if (imageInfo)
  {
    imageInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
    imageInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
    imageInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    if (imageInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    {
      imageInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
        imageInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
      imageInfo->Set(vtkStreamingDemandDrivenPipeline::EXACT_EXTENT(), 1);
    }
  }
  if (this->AnimateSweeps)
  {
    // The output's time is a number of sweeps, not the inputs' time.
    for (int port = 0; port < 2; ++port)
    {
      if (vtkInformation* info = inputVector[port]->GetInformationObject(0))
      {
        info->Remove(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
      }
    }
  }
  if (vtkInformation* surfaceInfo = inputVector[1]->GetInformationObject(0))
  {
    const bool distributed = vtkDSPolyDataGather::IsDistributed(this->Controller);
    surfaceInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(),
      distributed ? this->Controller->GetLocalProcessId() : 0);
    surfaceInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(),
      distributed ? this->Controller->GetNumberOfProcesses() : 1);
    surfaceInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::ExchangeParameters(dsurf::MultilevelParameters& core, bool toCore)
{
  Exchange(this->Tau, core.Solver.Tau, toCore);
  Exchange(this->Gamma, core.Solver.Gamma, toCore);
  Exchange(this->ProjectExternalForce, core.Solver.ProjectExternalForce, toCore);
  Exchange(this->NumberOfThreads, core.Solver.NumberOfThreads, toCore);
  Exchange(this->EdgeWeight, core.EdgeWeight, toCore);
  Exchange(this->ImageWeight, core.ImageWeight, toCore);
  Exchange(this->Sigma, core.Sigma, toCore);
  Exchange(this->SigmaFraction, core.SigmaFraction, toCore);
  Exchange(this->EdgeNormalization, core.EdgeNormalization, toCore);
  Exchange(this->RegionWeight, core.RegionWeight, toCore);
  Exchange(this->IntensityRange[0], core.IntensityRange[0], toCore);
  Exchange(this->IntensityRange[1], core.IntensityRange[1], toCore);
  Exchange(this->HierarchicalSigma, core.HierarchicalSigma, toCore);
  Exchange(this->MaxLevels, core.MaxLevels, toCore);
  Exchange(this->MaxSweepsPerLevel, core.MaxSweepsPerLevel, toCore);
  Exchange(this->ConvergenceTolerance, core.ConvergenceTolerance, toCore);
  Exchange(this->RefinementThreshold, core.RefinementThreshold, toCore);
  Exchange(this->UniformRefinement, core.UniformRefinement, toCore);
  Exchange(this->SubdivideInitialSurface, core.SubdivideInitialSurface, toCore);
  Exchange(this->ButterflyProlongation, core.ButterflyProlongation, toCore);
  Exchange(this->MaxVertices, core.MaxVertices, toCore);
  Exchange(this->CheckTopology, core.CheckTopology, toCore);
  Exchange(this->MaxSweeps, core.MaxSweeps, toCore);
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::Report(const dsurf::MultilevelSolver& solver)
{
  for (const std::string& w : solver.GetWarnings())
  {
    vtkWarningMacro(<< w);
  }
  // Vertices that only pass outside on the way (a start box at the image bounds bulges
  // out for a few sweeps) are harmless; the ones that end outside never met the image.
  if (solver.GetFinalOutsideVertices() > 0)
  {
    vtkWarningMacro(<< solver.GetFinalOutsideVertices()
                    << " vertices ended outside the image, where they feel no external force: "
                       "the initial surface may reach beyond the volume.");
  }
  const dsurf::InitialSigmaChoice& choice = solver.GetInitialSigmaChoice();
  vtkDebugMacro(
    << "sigma_0 " << (solver.GetLevels().empty() ? 0.0 : solver.GetLevels().front().Sigma)
    << (choice.SpansVolume ? ": the start spans the volume (extent / 6)" : "")
    << (choice.Rays > 0 ? ": the 90th-percentile distance " + std::to_string(choice.StartDistance) +
             " from the start to its nearest edges (" + std::to_string(choice.RaysWithEdge) +
             " of " + std::to_string(choice.Rays) + " rays met one)"
                        : std::string()));
  vtkDebugMacro(<< "The levels ended after level "
                << (solver.GetLevels().empty() ? -1 : solver.GetLevels().back().Level) << ": "
                << dsurf::StopReasonName(solver.GetStopReason()) << ".");
  vtkDebugMacro(<< "At most " << solver.GetMaxOutsideVertices()
                << " vertices lay outside the image during a sweep.");
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::KeepResult(vtkImageData* image, vtkPolyData* surface,
  const vtkMTimeType key[3], bool complete, vtkPolyData* output, vtkTable* table)
{
  if (this->ContinueFromLastResult && complete)
  {
    // A copy of the final surface: downstream filters must not be able to change where the
    // next run starts (and with AnimateSweeps the output becomes a time step).
    vtkNew<vtkPolyData> shape;
    shape->SetPoints(output->GetPoints());
    shape->SetPolys(output->GetPolys());
    this->LastResult = vtkSmartPointer<vtkPolyData>::New();
    this->LastResult->DeepCopy(shape);
    this->LastImage = image;
    this->LastImageTime = image->GetMTime();
    this->LastSurface = surface;
    this->LastSurfaceTime = surface->GetMTime();
  }
  if (this->AnimateSweeps)
  {
    this->AnimationResult = vtkSmartPointer<vtkPolyData>::New();
    this->AnimationResult->DeepCopy(output);
    this->AnimationTable = vtkSmartPointer<vtkTable>::New();
    this->AnimationTable->DeepCopy(table);
    std::copy(key, key + 3, this->AnimationKey);
    this->AnimationInputs[0] = complete ? image : nullptr; // an incomplete run is never a hit
    this->AnimationInputs[1] = complete ? surface : nullptr;
  }
}

//------------------------------------------------------------------------------
bool vtkDeformableSurfaceFilter::ReadImage(
  vtkImageData* image, vtkDataArray* array, dsurf::ImageVolume& volume)
{
  std::string error;
  if (!dsurf::GetImageVolume(image, array, dsurf::ForceFieldBytesPerVoxel, volume, error))
  {
    vtkErrorMacro(<< error << ".");
    return false;
  }
  if (!volume.Note.empty())
  {
    vtkDebugMacro(<< volume.Note << ".");
  }
  // Not the array's range: VTK computes it in one serial pass over every voxel (~2.8 s of a
  // 512^3 uint16 solve's 9); a real image differs from its first voxel within a few voxels.
  double value = 0.0;
  if (dsurf::IsConstant(volume.Image, value))
  {
    vtkErrorMacro("The image is constant (" << value << "): it has no boundary to find.");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkDeformableSurfaceFilter::ParametersAreFinite()
{
  // vtkSetClampMacro lets NaN through: a NaN Tau gives NaN coordinates, a NaN Sigma falls
  // back to SigmaFraction, a NaN tolerance never converges.
  const std::string nonFinite = dsurf::FirstNonFinite(
    { { "Tau", this->Tau }, { "Gamma", this->Gamma }, { "EdgeWeight", this->EdgeWeight },
      { "ImageWeight", this->ImageWeight }, { "Sigma", this->Sigma },
      { "SigmaFraction", this->SigmaFraction }, { "RegionWeight", this->RegionWeight },
      { "ConvergenceTolerance", this->ConvergenceTolerance },
      { "RefinementThreshold", this->RefinementThreshold } });
  if (!nonFinite.empty())
  {
    vtkErrorMacro(<< nonFinite << " is not a finite number: set it to a value in its range.");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkDeformableSurfaceFilter::StartMesh(vtkPolyData* start, dsurf::TriangleMesh& mesh)
{
  std::string error;
  if (!BuildMesh(start, mesh, error))
  {
    vtkErrorMacro("Bad initial surface: " << error << ".");
    return false;
  }
  if (!mesh.IsConsistentlyOriented())
  {
    // Normals (the projection direction) and the refinement's invariants need neighbours
    // to agree; each piece keeps the orientation most of its triangles had.
    const int flipped = mesh.OrientConsistently();
    vtkWarningMacro("The initial surface was not consistently oriented: "
      << flipped << " triangle(s) flipped to agree with their neighbours.");
  }
  vtkDebugMacro("Initial surface: " << mesh.NumberOfPoints() << " points, "
                                    << mesh.NumberOfTriangles() << " triangles, signed volume "
                                    << mesh.SignedVolume() << ".");
  return true;
}

//------------------------------------------------------------------------------
// The multilevel solve: dsurf::MultilevelSolver runs the levels (sweeps, error estimator,
// red-green refinement, butterfly, sigma halving, force field per level); here only
// parameters in, the convergence table and AnimateSweeps' snapshots out.
bool vtkDeformableSurfaceFilter::Solve(const dsurf::ImageVolume& volume, dsurf::TriangleMesh& mesh,
  dsurf::MultilevelSolver& solver, vtkTable* table)
{
  dsurf::MultilevelParameters mp;
  this->ExchangeParameters(mp, true);
  this->Snapshots.clear();
  this->AnimationResult = nullptr;
  if (this->AnimateSweeps)
  {
    mp.SweepBatch = 1; // a snapshot exactly every SweepsPerTimeStep sweeps
    this->Snapshots.push_back(MeshSnapshot(mesh, 0));
  }
  if (this->OnPieces)
  {
    // The force exchange calls MPI from the solver's threads: one thread (the caller's).
    mp.Solver.NumberOfThreads = 1;
  }
  solver.SetParameters(mp);
  solver.SetCoarsenCallback(CoarsenMesh);
  solver.SetProgressCallback(
    [this](double f)
    {
      this->UpdateProgress(0.02 + 0.96 * f);
      // On pieces every process stops when one does (MultilevelSolver::SetDistribution).
      return !this->GetAbortExecute();
    });
  ConvergenceColumns columns;
  solver.SetSweepCallback(
    [&columns, this](const dsurf::SweepRecord& r, const dsurf::TriangleMesh& m)
    {
      if (this->AnimateSweeps && r.Sweep % this->SweepsPerTimeStep == 0 &&
        this->Snapshots.size() < MaxSnapshots &&
        static_cast<double>(this->Snapshots.size() + 1) * SnapshotBytes(m) <= MaxSnapshotBytes)
      {
        this->Snapshots.push_back(MeshSnapshot(m, r.Sweep));
      }
      columns.Sweep->InsertNextValue(r.Sweep);
      columns.Level->InsertNextValue(r.Level);
      columns.Sigma->InsertNextValue(r.Sigma);
      columns.Vertices->InsertNextValue(r.Vertices);
      columns.Triangles->InsertNextValue(r.Triangles);
      columns.MeanCorrection->InsertNextValue(r.MeanCorrection);
      columns.MaxCorrection->InsertNextValue(r.MaxCorrection);
      return true;
    });
  std::string error;
  if (!solver.Run(volume.Image, mesh, &error))
  {
    vtkErrorMacro("Deformable surface failed: " << error);
    return false;
  }
  columns.AddTo(table);
  return true;
}

//------------------------------------------------------------------------------
bool vtkDeformableSurfaceFilter::ImageInPieces()
{
  // Every default is distributed; the potential only in its default form (ComputePieceForce).
  return vtkDSPolyDataGather::IsDistributed(this->Controller) && this->EdgeWeight > 0 &&
    this->ImageWeight == 0 &&
    this->EdgeNormalization == GLOBAL_MAXIMUM;
}

//------------------------------------------------------------------------------
bool vtkDeformableSurfaceFilter::ImageOnProcessZeroOnly(vtkImageData* image, const int whole[6])
{
  // A reader that cannot split its file (NIfTI, MetaImage) answers a request for pieces with
  // the whole image on process 0 and nothing on the others: then process 0 solves alone, as
  // with the whole image requested. Collective: every process answers alike.
  const bool empty = !image || image->GetNumberOfPoints() <= 0;
  bool mine = empty;
  if (this->Controller->GetLocalProcessId() == 0)
  {
    mine = !empty && std::equal(whole, whole + 6, image->GetExtent());
  }
  return dsurf::ControllerReductions(this->Controller).Max(mine ? 0.0 : 1.0) == 0.0;
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::SolveOnPieces(vtkImageData* image, vtkDataArray* array,
  vtkPolyData* surface, const int wholeExtent[6], vtkPolyData* output, vtkTable* table)
{
  // Local problems first, agreed by one reduction before any other collective call, so that
  // no process is left waiting; what follows depends only on what every process has alike.
  dsurf::ImageVolume volume;
  std::string problem;
  if (!image || image->GetNumberOfPoints() <= 0)
  {
    problem = "this process's piece of the image is empty";
  }
  else
  {
    dsurf::GetImageVolume(image, array, dsurf::ForceFieldBytesPerVoxel, volume, problem);
  }
  const dsurf::PieceReductions reduce = dsurf::ControllerReductions(this->Controller);
  if (reduce.Max(problem.empty() ? 0.0 : 1.0) > 0.0)
  {
    vtkErrorMacro("Distributed image: "
      << (problem.empty() ? "another process's piece of the image is empty or invalid" : problem)
      << ".");
    return;
  }
  const int rank = this->Controller->GetLocalProcessId();
  const int ranks = this->Controller->GetNumberOfProcesses();
  const dsurf::ImagePiece piece =
    dsurf::ImagePieceOf(volume.Image, image->GetExtent(), wholeExtent, rank, ranks);
  dsurf::TriangleMesh mesh;
  dsurf::MultilevelSolver solver;
  solver.SetDistribution(piece, reduce);
  // Run's image in a distributed solve: the piece's values with the whole image's geometry
  // (MultilevelSolver::SetDistribution); the core reads the values through the piece.
  dsurf::ImageVolume whole;
  whole.Image = piece.Image;
  whole.Image.Geometry = piece.Whole;
  this->OnPieces = true;
  const bool solved = this->ParametersAreFinite() && this->StartMesh(surface, mesh) &&
    this->Solve(whole, mesh, solver, table);
  this->OnPieces = false;
  std::vector<double> held(ranks, 0.0);
  held[rank] = static_cast<double>(piece.Held.NumberOfVoxels());
  reduce.Sum(held);
  if (!solved || rank != 0)
  {
    table->Initialize(); // the surface and the table are delivered once, by process 0
    return;
  }
  this->Report(solver);
  FillOutput(mesh, solver, output);
  const double* used = solver.GetIntensityRange();
  AddFieldData(solver, mesh, used[0] < used[1], false, output->GetFieldData());
  vtkNew<vtkDoubleArray> voxels;
  voxels->SetName("PieceVoxels");
  for (double h : held)
  {
    voxels->InsertNextValue(h);
  }
  output->GetFieldData()->AddArray(voxels);
  AddFieldValue<vtkDoubleArray>(
    output->GetFieldData(), "ImageVoxels", static_cast<double>(piece.Whole.NumberOfVoxels()));
}

//------------------------------------------------------------------------------
int vtkDeformableSurfaceFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* image = vtkImageData::GetData(inputVector[0], 0);
  vtkPolyData* surface = vtkPolyData::GetData(inputVector[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  if (!output || !table)
  {
    return 0;
  }
  output->Initialize();
  table->Initialize();

  // Distributed: before any check that could return early on one process only, every
  // process hands its piece of the surface to process 0, which alone solves; the others keep
  // their outputs empty.
  vtkNew<vtkPolyData> gathered;
  const bool distributed = vtkDSPolyDataGather::IsDistributed(this->Controller);
  if (distributed)
  {
    const bool onZero = vtkDSPolyDataGather::GatherOnProcessZero(
      this->Controller, OwnedSurfacePiece(surface), gathered);
    int wholeExtent[6] = { 0, -1, 0, -1, 0, -1 };
    vtkInformation* imageInfo = inputVector[0]->GetInformationObject(0);
    if (imageInfo && imageInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    {
      imageInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent);
    }
    if (this->ImageInPieces() && !this->ImageOnProcessZeroOnly(image, wholeExtent))
    {
      this->Controller->Broadcast(gathered, 0); // every process solves
      this->SolveOnPieces(
        image, this->GetInputArrayToProcess(0, inputVector), gathered, wholeExtent, output, table);
      return 1;
    }
    if (!onZero)
    {
      return 1;
    }
    surface = gathered;
  }
  if (!image || image->GetNumberOfPoints() <= 0)
  {
    vtkErrorMacro("No input image (port 0) or the image is empty.");
    return 1;
  }
  if (!surface)
  {
    vtkErrorMacro(
      "No initial surface (port 1): connect a vtkPolyData with SetInitialSurfaceConnection().");
    return 1;
  }
  // AnimateSweeps: a time step already computed comes from the cache, before any work.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const double requestedTime =
    this->AnimateSweeps && outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
    : -1.0;
  const vtkMTimeType key[3] = { image->GetMTime(), surface->GetMTime(), this->GetMTime() };
  if (this->ServeFromCache(image, surface, key, requestedTime, output, table))
  {
    return 1;
  }

  dsurf::ImageVolume volume;
  if (!this->ReadImage(image, this->GetInputArrayToProcess(0, inputVector), volume) ||
    !this->ParametersAreFinite())
  {
    return 1;
  }
  // The start: the input, or the last result (warm start) when only the filter's own
  // parameters changed since.
  const bool warm = this->ContinueFromLastResult && !distributed && this->LastResult &&
    this->LastImage == image && this->LastImageTime == image->GetMTime() &&
    this->LastSurface == surface && this->LastSurfaceTime == surface->GetMTime();
  vtkDebugMacro(<< (warm ? "Warm start from the last result." : "Start from the initial surface."));
  dsurf::TriangleMesh mesh;
  dsurf::MultilevelSolver solver;
  if (!this->StartMesh(warm ? this->LastResult.Get() : surface, mesh) ||
    !this->Solve(volume, mesh, solver, table))
  {
    return 1;
  }
  this->Report(solver);
  FillOutput(mesh, solver, output);
  const double* used = solver.GetIntensityRange();
  AddFieldData(solver, mesh, used[0] < used[1], warm, output->GetFieldData());
  // Warm start and time steps: only complete, serial results (an aborted run's steps would be
  // served as the solve's; a distributed run gathers a new surface every time).
  this->KeepResult(image, surface, key, !distributed && !solver.GetAborted(), output, table);
  if (this->AnimateSweeps)
  {
    this->ServeTimeStep(requestedTime, output);
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tau: " << this->Tau << "\n";
  os << indent << "Gamma: " << this->Gamma << "\n";
  os << indent << "EdgeWeight: " << this->EdgeWeight << "\n";
  os << indent << "ImageWeight: " << this->ImageWeight << "\n";
  os << indent << "Sigma: " << this->Sigma << "\n";
  os << indent << "SigmaFraction: " << this->SigmaFraction << "\n";
  os << indent << "EdgeNormalization: " << this->EdgeNormalization << "\n";
  os << indent << "RegionWeight: " << this->RegionWeight << "\n";
  os << indent << "IntensityRange: " << this->IntensityRange[0] << " " << this->IntensityRange[1]
     << "\n";
  os << indent << "MaxSweepsPerLevel: " << this->MaxSweepsPerLevel << "\n";
  os << indent << "ConvergenceTolerance: " << this->ConvergenceTolerance << "\n";
  os << indent << "MaxLevels: " << this->MaxLevels << "\n";
  os << indent << "RefinementThreshold: " << this->RefinementThreshold << "\n";
  os << indent << "UniformRefinement: " << this->UniformRefinement << "\n";
  os << indent << "SubdivideInitialSurface: " << this->SubdivideInitialSurface << "\n";
  os << indent << "HierarchicalSigma: " << this->HierarchicalSigma << "\n";
  os << indent << "ButterflyProlongation: " << this->ButterflyProlongation << "\n";
  os << indent << "MaxVertices: " << this->MaxVertices << "\n";
  os << indent << "CheckTopology: " << this->CheckTopology << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "ProjectExternalForce: " << this->ProjectExternalForce << "\n";
  os << indent << "ContinueFromLastResult: " << this->ContinueFromLastResult << "\n";
  os << indent << "MaxSweeps: " << this->MaxSweeps << "\n";
  os << indent << "AnimateSweeps: " << this->AnimateSweeps << "\n";
  os << indent << "SweepsPerTimeStep: " << this->SweepsPerTimeStep << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
