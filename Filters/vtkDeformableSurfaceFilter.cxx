// SPDX-License-Identifier: BSD-3-Clause
#include "vtkDeformableSurfaceFilter.h"

#include "dsFieldGrid.h"
#include "dsMultilevel.h"
#include "dsObjects.h"
#include "dsRegionPreview.h"
#include "dsScaleSpace.h"
#include "dsSelfIntersectionCount.h"
#include "dsSolver.h"
#include "dsTriangleMesh.h"
#include "dsVTKAnimation.h"
#include "dsVTKImage.h"
#include "dsVTKMesh.h"
#include "dsVTKObjects.h"
#include "dsVTKPieces.h"
#include "dsVTKRegionPreview.h"
#include "dsVTKWarmStart.h"

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
#include <memory>
#include <string>
#include <type_traits>
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
  std::vector<long long> objectIds;
  if (!dsurf::ReadObjectIds(input, objectIds, error))
  {
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
  // The ObjectId of each triangle, passed on by the triangulation and the cleaning.
  std::vector<long long> cellObjects, triangleObjects;
  if (!objectIds.empty() && !dsurf::ReadObjectIds(tri, cellObjects, error))
  {
    return false;
  }
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
      if (!cellObjects.empty())
      {
        triangleObjects.push_back(cellObjects[it->GetCurrentCellId()]);
      }
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
  // Several objects (docs/METHOD.md §9.9): each triangle's ObjectId names its object.
  if (!triangleObjects.empty() &&
    !dsurf::AssignObjects(mesh, triangleObjects, mesh.ObjectIds, &error))
  {
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

/// The core's coarse copy of a start far finer than sigma_0 (MultilevelSolver::CoarsenStart):
/// vertex clustering on a grid of `edge` (Lindstrom 2000, vtkQuadricClustering), linear in
/// the triangles (~1 s for 1.3 M; decimation by edge collapse took ~60 s). It can merge thin
/// parts: the core keeps the copy only when the topology is unchanged.
bool CoarsenMesh(const dsurf::TriangleMesh& fine, double edge, dsurf::TriangleMesh& coarse)
{
  vtkNew<vtkPolyData> poly;
  dsurf::SetPolyDataGeometry(fine, poly);
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

/// The deformed mesh as vtkPolyData with the solver's per-vertex arrays.
void FillOutput(
  const dsurf::TriangleMesh& mesh, const dsurf::MultilevelSolver& solver, vtkPolyData* output)
{
  const int nPts = mesh.NumberOfPoints();
  dsurf::SetPolyDataGeometry(mesh, output);

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
  dsurf::CopyPolygonObjectIds(owned, piece);
  return piece;
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
    AddFieldValue<vtkDoubleArray>(fd, "RegionWeight", solver.GetRegionWeight());
  }
  AddFieldValue<vtkIntArray>(fd, "Converged", solver.GetLastLevelConverged() ? 1 : 0);
  AddFieldValue<vtkStringArray>(fd, "StopReason", dsurf::StopReasonName(solver.GetStopReason()));
  AddFieldValue<vtkIntArray>(fd, "WarmStart", warm ? 1 : 0);
  // What made a run longer than its schedule (docs/METHOD.md §9.3): levels past sigma's floor
  // that followed a thin part, and levels solved with the surface kept off itself.
  int front = 0, keptApart = 0;
  for (const dsurf::LevelRecord& level : solver.GetLevels())
  {
    front += level.Front ? 1 : 0;
    keptApart += level.KeptApart ? 1 : 0;
  }
  AddFieldValue<vtkIntArray>(fd, "FrontLevels", front);
  AddFieldValue<vtkIntArray>(fd, "KeptApartLevels", keptApart);
}
/// PrintSelf's line of one parameter.
template <typename T>
void PrintParameter(ostream& os, vtkIndent indent, const char* name, T value)
{
  os << indent << name << ": " << value << "\n";
}
void PrintParameter(ostream& os, vtkIndent indent, const char* name, double* pair)
{
  os << indent << name << ": " << pair[0] << " " << pair[1] << "\n";
}
} // namespace

// The accessors of the parameters (vtkDeformableSurfaceFilter_PARAMETERS in the header), as
// vtkSetClampMacro, vtkSetMacro with vtkBooleanMacro, vtkSetVector2Macro and their Get macros
// define them, on the fields that hold the parameters.
// clang-format off
#define vtkDeformableSurfaceFilter_FIELD_TYPE(field) std::remove_reference_t<decltype(this->field)>
#define vtkDeformableSurfaceFilter_GET(name, type, field)                                          \
  type vtkDeformableSurfaceFilter::Get##name()                                                     \
  {                                                                                                \
    return static_cast<type>(this->field);                                                         \
  }
#define vtkDeformableSurfaceFilter_DEFINE_NUMBER(name, type, field, min, max)                      \
  vtkDeformableSurfaceFilter_GET(name, type, field)                                                \
  void vtkDeformableSurfaceFilter::Set##name(type value)                                           \
  {                                                                                                \
    vtkDebugMacro(<< "setting " #name " to " << value);                                            \
    const type clamped = value < (min) ? (min) : (value > (max) ? (max) : value);                  \
    if (this->Get##name() != clamped)                                                              \
    {                                                                                              \
      this->field = static_cast<vtkDeformableSurfaceFilter_FIELD_TYPE(field)>(clamped);            \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  type vtkDeformableSurfaceFilter::Get##name##MinValue()                                           \
  {                                                                                                \
    return (min);                                                                                  \
  }                                                                                                \
  type vtkDeformableSurfaceFilter::Get##name##MaxValue()                                           \
  {                                                                                                \
    return (max);                                                                                  \
  }
#define vtkDeformableSurfaceFilter_DEFINE_CUSTOM(name, type, field)                                \
  vtkDeformableSurfaceFilter_GET(name, type, field)
#define vtkDeformableSurfaceFilter_DEFINE_FLAG(name, field)                                        \
  vtkDeformableSurfaceFilter_GET(name, bool, field)                                                \
  void vtkDeformableSurfaceFilter::Set##name(bool value)                                           \
  {                                                                                                \
    vtkDebugMacro(<< "setting " #name " to " << value);                                            \
    if (this->field != value)                                                                      \
    {                                                                                              \
      this->field = value;                                                                         \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  void vtkDeformableSurfaceFilter::name##On()                                                      \
  {                                                                                                \
    this->Set##name(true);                                                                         \
  }                                                                                                \
  void vtkDeformableSurfaceFilter::name##Off()                                                     \
  {                                                                                                \
    this->Set##name(false);                                                                        \
  }
#define vtkDeformableSurfaceFilter_DEFINE_PAIR(name, type, field)                                  \
  void vtkDeformableSurfaceFilter::Set##name(type first, type second)                              \
  {                                                                                                \
    vtkDebugMacro(<< "setting " #name " to (" << first << "," << second << ")");                   \
    if (this->field[0] != first || this->field[1] != second)                                       \
    {                                                                                              \
      this->field[0] = first;                                                                      \
      this->field[1] = second;                                                                     \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  void vtkDeformableSurfaceFilter::Set##name(const type values[2])                                 \
  {                                                                                                \
    this->Set##name(values[0], values[1]);                                                         \
  }                                                                                                \
  type* vtkDeformableSurfaceFilter::Get##name()                                                    \
  {                                                                                                \
    return this->field;                                                                            \
  }                                                                                                \
  void vtkDeformableSurfaceFilter::Get##name(type& first, type& second)                            \
  {                                                                                                \
    first = this->field[0];                                                                        \
    second = this->field[1];                                                                       \
  }                                                                                                \
  void vtkDeformableSurfaceFilter::Get##name(type values[2])                                       \
  {                                                                                                \
    this->Get##name(values[0], values[1]);                                                         \
  }
vtkDeformableSurfaceFilter_PARAMETERS(vtkDeformableSurfaceFilter_DEFINE_NUMBER,
  vtkDeformableSurfaceFilter_DEFINE_CUSTOM, vtkDeformableSurfaceFilter_DEFINE_FLAG,
  vtkDeformableSurfaceFilter_DEFINE_PAIR);
// clang-format on

//------------------------------------------------------------------------------
vtkDeformableSurfaceFilter::vtkDeformableSurfaceFilter()
  : Parameters(std::make_unique<dsurf::MultilevelParameters>())
  , Animation(std::make_unique<dsurf::SweepAnimation>())
  , Warm(std::make_unique<dsurf::WarmStart>())
  , Preview(std::make_unique<dsurf::RegionPreviewMode>())
{
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
  if (this->Parameters->Solver.Gamma != clamped)
  {
    this->Parameters->Solver.Gamma = clamped;
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
// AnimateSweeps: time steps up to the schedule's cap (dsVTKAnimation.h).
int vtkDeformableSurfaceFilter::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (!this->Animation->AnimateSweeps)
  {
    return 1; // the inputs' time steps, if any, pass through as for any filter
  }
  const dsurf::MultilevelParameters& p = *this->Parameters;
  long long bound = static_cast<long long>(p.MaxLevels + 1) * p.MaxSweepsPerLevel;
  if (p.MaxSweeps > 0)
  {
    bound = std::min<long long>(bound, p.MaxSweeps);
  }
  this->Animation->ReportTimeSteps(bound, outputVector->GetInformationObject(0));
  return 1;
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
    dsurf::RequestImagePiece(this->Controller, *this->Parameters, imageInfo);
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
  if (this->Animation->AnimateSweeps)
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
bool vtkDeformableSurfaceFilter::ReadImage(
  vtkImageData* image, vtkDataArray* array, dsurf::ImageVolume& volume)
{
  std::string error;
  // The preview's labels; a solve's fields are checked as they are made (docs/METHOD.md §9.6).
  const double workBytesPerVoxel = this->Preview->PreviewRegion ? dsurf::PreviewBytesPerVoxel : 0.0;
  if (!dsurf::GetImageVolume(image, array, workBytesPerVoxel, volume, error))
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
  // The clamps let NaN through: a NaN Tau gives NaN coordinates, a NaN Sigma falls back to
  // SigmaFraction, a NaN tolerance never converges. (IntensityRange is the core's to check: a
  // range that is not finite is estimated instead, with a warning.)
#define vtkDeformableSurfaceFilter_NUMBER_VALUE(name, ...)                                         \
  { #name, static_cast<double>(this->Get##name()) },
#define vtkDeformableSurfaceFilter_NO_NUMBER(...)
  const std::string nonFinite = dsurf::FirstNonFinite({ vtkDeformableSurfaceFilter_PARAMETERS(
    vtkDeformableSurfaceFilter_NUMBER_VALUE, vtkDeformableSurfaceFilter_NUMBER_VALUE,
    vtkDeformableSurfaceFilter_NO_NUMBER, vtkDeformableSurfaceFilter_NO_NUMBER) });
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
  dsurf::MultilevelParameters mp = *this->Parameters;
  this->Animation->Begin(mesh);
  if (this->Animation->AnimateSweeps)
  {
    mp.SweepBatch = 1; // a snapshot exactly every SweepsPerTimeStep sweeps
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
      this->Animation->Record(r.Sweep, m);
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
  // The preview reads the whole image on process 0 (RegionPreview is serial).
  return vtkDSPolyDataGather::IsDistributed(this->Controller) &&
    dsurf::PotentialAllowsPieces(*this->Parameters) && !this->Preview->PreviewRegion;
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::Deliver(const dsurf::TriangleMesh& mesh,
  const dsurf::MultilevelSolver& solver, bool warm, vtkPolyData* output)
{
  this->Report(solver);
  FillOutput(mesh, solver, output);
  const double* used = solver.GetIntensityRange();
  AddFieldData(solver, mesh, used[0] < used[1], warm, output->GetFieldData());
  if (!mesh.ObjectIds.empty())
  {
    dsurf::AddObjectArrays(mesh, output);
    dsurf::AddObjectFieldData(
      mesh, solver.GetObjectRegions(), solver.GetCrossingPairs(), output->GetFieldData());
  }
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::SolveOnPieces(vtkImageData* image, vtkDataArray* array,
  vtkPolyData* surface, const int wholeExtent[6], vtkPolyData* output, vtkTable* table)
{
  const dsurf::PieceReductions reduce = dsurf::ControllerReductions(this->Controller);
  const int rank = this->Controller->GetLocalProcessId();
  const int ranks = this->Controller->GetNumberOfProcesses();
  dsurf::ImageVolume volume;
  dsurf::ImagePiece piece;
  std::string problem;
  if (!dsurf::ReadImagePiece(
        reduce, rank, ranks, image, array, wholeExtent, volume, piece, problem))
  {
    vtkErrorMacro("Distributed image: " << problem << ".");
    return;
  }
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
  const std::vector<double> held = dsurf::HeldVoxels(reduce, piece, rank, ranks);
  if (!solved || rank != 0)
  {
    table->Initialize(); // the surface and the table are delivered once, by process 0
    return;
  }
  this->Deliver(mesh, solver, false, output);
  dsurf::AddPieceFieldData(held, piece, output->GetFieldData());
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
    if (this->ImageInPieces() &&
      !dsurf::ImageOnProcessZeroOnly(this->Controller, image, wholeExtent))
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
  const double requestedTime = this->Animation->AnimateSweeps &&
      outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
    : -1.0;
  const vtkMTimeType key[3] = { image->GetMTime(), surface->GetMTime(), this->GetMTime() };
  if (this->Animation->Serve(image, surface, key, requestedTime, output, table))
  {
    vtkDebugMacro(<< "Time " << requestedTime << " from the cache.");
    return 1;
  }

  dsurf::ImageVolume volume;
  if (!this->ReadImage(image, this->GetInputArrayToProcess(0, inputVector), volume) ||
    !this->ParametersAreFinite())
  {
    return 1;
  }
  if (this->Preview->PreviewRegion)
  {
    // The region before the solve (dsVTKRegionPreview.h): no sweeps, no warm start.
    dsurf::TriangleMesh mesh;
    std::string error;
    std::vector<std::string> warnings;
    if (this->StartMesh(surface, mesh) &&
      !dsurf::DeliverRegionPreview(volume.Image, mesh, *this->Parameters, output, error, warnings))
    {
      vtkErrorMacro("Region preview: " << error << ".");
    }
    for (const std::string& w : warnings)
    {
      vtkWarningMacro("Region preview: " << w << ".");
    }
    return 1;
  }
  // The start: the input, or the last result (warm start) when only the filter's own
  // parameters changed since.
  vtkPolyData* last = distributed ? nullptr : this->Warm->StartFor(image, surface);
  vtkDebugMacro(<< (last ? "Warm start from the last result." : "Start from the initial surface."));
  dsurf::TriangleMesh mesh;
  dsurf::MultilevelSolver solver;
  if (!this->StartMesh(last ? last : surface, mesh) || !this->Solve(volume, mesh, solver, table))
  {
    return 1;
  }
  this->Deliver(mesh, solver, last != nullptr, output);
  // Warm start and time steps: only complete, serial results (an aborted run's steps would be
  // served as the solve's; a distributed run gathers a new surface every time).
  const bool complete = !distributed && !solver.GetAborted();
  if (complete)
  {
    this->Warm->Keep(image, surface, output);
  }
  this->Animation->Keep(image, surface, key, complete, output, table);
  if (this->Animation->AnimateSweeps)
  {
    this->Animation->ServeTimeStep(requestedTime, output);
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::AddObjectIntensityRange(double objectId, double low, double high)
{
  std::vector<double>& table = this->Parameters->ObjectIntensityRanges;
  table.insert(table.end(), { objectId, low, high });
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::RemoveAllObjectIntensityRanges()
{
  if (!this->Parameters->ObjectIntensityRanges.empty())
  {
    this->Parameters->ObjectIntensityRanges.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
#define vtkDeformableSurfaceFilter_PRINT(name, ...)                                                \
  PrintParameter(os, indent, #name, this->Get##name());
  vtkDeformableSurfaceFilter_PARAMETERS(vtkDeformableSurfaceFilter_PRINT,
    vtkDeformableSurfaceFilter_PRINT, vtkDeformableSurfaceFilter_PRINT,
    vtkDeformableSurfaceFilter_PRINT);
  os << indent << "ObjectIntensityRanges:";
  for (double v : this->Parameters->ObjectIntensityRanges)
  {
    os << " " << v;
  }
  os << "\n" << indent << "Controller: " << this->Controller << "\n";
}
