#include "vtkDeformableSurfaceFilter.h"

#include "dsMultilevel.h"
#include "dsScaleSpace.h"
#include "dsVTKImage.h"
#include "dsSelfIntersection.h"
#include "dsSolver.h"
#include "dsTriangleMesh.h"

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
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
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
    for (vtkAbstractArray* a : std::initializer_list<vtkAbstractArray*>{ this->Sweep, this->Level,
           this->Sigma, this->Vertices, this->Triangles, this->MeanCorrection, this->MaxCorrection })
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
bool BuildMesh(vtkPolyData* input, dsurf::TriangleMesh& mesh, std::string& error)
{
  if (!UsedPointsInRange(input))
  {
    error = "the initial surface has a NaN, infinite or out-of-range (beyond 1e100) point coordinate";
    return false;
  }
  vtkNew<vtkPolyData> copy;
  copy->ShallowCopy(input);
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(copy);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(triangulate->GetOutputPort());
  clean->PointMergingOn();
  clean->ToleranceIsAbsoluteOff();
  clean->SetTolerance(1e-6);
  clean->ConvertLinesToPointsOff();
  clean->ConvertPolysToLinesOff();
  clean->ConvertStripsToPolysOff();
  clean->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  clean->Update();
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

void FillOutput(const dsurf::TriangleMesh& mesh, const dsurf::MultilevelSolver& solver, vtkPolyData* output)
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
  const auto sized = [nPts](const std::vector<double>& v) {
    return static_cast<int>(v.size()) == nPts ? v : std::vector<double>(nPts, 0.0);
  };
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
void AddFieldData(const dsurf::MultilevelSolver& solver, const dsurf::TriangleMesh& mesh, bool region, bool warm,
  vtkFieldData* fd)
{
  AddFieldValue<vtkIntArray>(fd, "Sweeps", solver.GetTotalSweeps());
  AddFieldValue<vtkIntArray>(fd, "Levels", static_cast<int>(solver.GetLevels().size()));
  AddFieldValue<vtkIntArray>(fd, "InitialSubdivisions", solver.GetInitialSubdivisions());
  AddFieldValue<vtkDoubleArray>(fd, "FinalMeanCorrection", solver.GetFinalMeanCorrection());
  AddFieldValue<vtkIntArray>(fd, "SelfIntersections", dsurf::CountSelfIntersections(mesh));
  AddFieldValue<vtkDoubleArray>(fd, "Sigma", solver.GetFinalSigma());
  AddFieldValue<vtkDoubleArray>(fd, "InitialSigma", solver.GetLevels().empty() ? 0.0 : solver.GetLevels().front().Sigma);
  if (region)
  {
    vtkNew<vtkDoubleArray> usedRange;
    usedRange->SetName("IntensityRange");
    usedRange->SetNumberOfComponents(2);
    usedRange->InsertNextTuple(solver.GetIntensityRange());
    fd->AddArray(usedRange);
  }
  AddFieldValue<vtkIntArray>(fd, "Converged", solver.GetLastLevelConverged() ? 1 : 0);
  AddFieldValue<vtkIntArray>(fd, "WarmStart", warm ? 1 : 0);
}
} // namespace

//------------------------------------------------------------------------------
vtkDeformableSurfaceFilter::vtkDeformableSurfaceFilter()
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
  const long long steps = std::min<long long>(static_cast<long long>(MaxSnapshots) - 1, (bound + S - 1) / S);
  std::vector<double> times(static_cast<std::size_t>(steps + 1));
  for (long long k = 0; k <= steps; ++k)
  {
    times[static_cast<std::size_t>(k)] = static_cast<double>(k * S);
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
  const double range[2] = { 0.0, times.back() };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

void vtkDeformableSurfaceFilter::ServeTimeStep(double t, vtkPolyData* output)
{
  const double k = t < 0 ? -1.0 : std::floor(t / this->SweepsPerTimeStep + 1e-9);
  const bool snapshot = k >= 0 && k < static_cast<double>(this->Snapshots.size());
  output->ShallowCopy(snapshot ? this->Snapshots[static_cast<std::size_t>(k)].Get() : this->AnimationResult.Get());
  if (t >= 0)
  {
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  }
}

//------------------------------------------------------------------------------
// The Gaussian reaches across the whole volume: always ask for all of it, also when the
// pipeline runs distributed and would otherwise hand each process one piece. The surface is
// asked whole in serial, one piece per process when distributed (gathered in RequestData).
int vtkDeformableSurfaceFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  if (vtkInformation* imageInfo = inputVector[0]->GetInformationObject(0))
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
dsurf::MultilevelParameters vtkDeformableSurfaceFilter::SolveParameters() const
{
  dsurf::MultilevelParameters mp;
  mp.Solver.Tau = this->Tau;
  mp.Solver.Gamma = this->Gamma;
  mp.Solver.ProjectExternalForce = this->ProjectExternalForce;
  mp.Solver.NumberOfThreads = this->NumberOfThreads;
  mp.EdgeWeight = this->EdgeWeight;
  mp.ImageWeight = this->ImageWeight;
  mp.InitialSigma = this->Sigma;
  mp.InitialSigmaFraction = this->SigmaFraction;
  mp.Normalization = static_cast<dsurf::EdgeNormalization>(this->EdgeNormalization);
  mp.RegionWeight = this->RegionWeight;
  mp.IntensityRange[0] = this->IntensityRange[0];
  mp.IntensityRange[1] = this->IntensityRange[1];
  mp.HierarchicalSigma = this->HierarchicalSigma;
  mp.MaxLevels = this->MaxLevels;
  mp.MaxSweepsPerLevel = this->MaxSweepsPerLevel;
  mp.Tolerance = this->ConvergenceTolerance;
  mp.RefinementThreshold = this->RefinementThreshold;
  mp.UniformRefinement = this->UniformRefinement;
  mp.InitialEdgeSigmaRatio = this->SubdivideInitialSurface ? 4.0 : 0.0;
  mp.ProlongationMode =
    this->ButterflyProlongation ? dsurf::Prolongation::Butterfly : dsurf::Prolongation::Linear;
  mp.MaxVertices = this->MaxVertices;
  mp.CheckInvariants = this->CheckTopology;
  mp.MaxTotalSweeps = this->MaxSweeps;
  return mp;
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
  vtkDebugMacro(<< "sigma_0 " << (solver.GetLevels().empty() ? 0.0 : solver.GetLevels().front().Sigma)
                << (choice.SpansVolume ? ": the start spans the volume (extent / 6)" : "")
                << (choice.Rays > 0 ? ": the 90th-percentile distance " + std::to_string(choice.StartDistance) +
                        " from the start to its nearest edges (" + std::to_string(choice.RaysWithEdge) + " of " +
                        std::to_string(choice.Rays) + " rays met one)" : std::string()));
  vtkDebugMacro(<< "At most " << solver.GetMaxOutsideVertices()
                << " vertices lay outside the image during a sweep.");
}

//------------------------------------------------------------------------------
void vtkDeformableSurfaceFilter::KeepResult(vtkImageData* image, vtkPolyData* surface, const vtkMTimeType key[3],
  bool complete, vtkPolyData* output, vtkTable* table)
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
  if (vtkDSPolyDataGather::IsDistributed(this->Controller))
  {
    if (!vtkDSPolyDataGather::GatherOnProcessZero(
          this->Controller, OwnedSurfacePiece(surface), gathered))
    {
      return 1;
    }
    surface = gathered;
  }

  // --- the image and its force field ---
  if (!image || image->GetNumberOfPoints() <= 0)
  {
    vtkErrorMacro("No input image (port 0) or the image is empty.");
    return 1;
  }
  if (!surface)
  {
    vtkErrorMacro("No initial surface (port 1): connect a vtkPolyData with SetInitialSurfaceConnection().");
    return 1;
  }
  // AnimateSweeps: a time step already computed comes from the cache, before any work.
  const bool distributed = vtkDSPolyDataGather::IsDistributed(this->Controller);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const double requestedTime = this->AnimateSweeps && outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
    : -1.0;
  const vtkMTimeType key[3] = { image->GetMTime(), surface->GetMTime(), this->GetMTime() };
  if (this->AnimateSweeps && this->AnimationResult && this->AnimationInputs[0] == image &&
    this->AnimationInputs[1] == surface && std::equal(key, key + 3, this->AnimationKey))
  {
    vtkDebugMacro(<< "Time " << requestedTime << " from the cache.");
    this->ServeTimeStep(requestedTime, output);
    table->ShallowCopy(this->AnimationTable);
    return 1;
  }

  dsurf::ImageVolume volume;
  std::string error;
  if (!dsurf::GetImageVolume(image, this->GetInputArrayToProcess(0, inputVector), volume, error))
  {
    vtkErrorMacro(<< error << ".");
    return 1;
  }
  if (!volume.Note.empty())
  {
    vtkDebugMacro(<< volume.Note << ".");
  }
  const dsurf::ImageGeometry& geometry = volume.Geometry;
  double range[2];
  volume.Array->GetRange(range, 0);
  if (range[0] == range[1])
  {
    vtkErrorMacro("The image is constant (" << range[0] << "): it has no boundary to find.");
    return 1;
  }

  // --- the initial surface: the input, or the last result (warm start) when only the
  // filter's own parameters changed since ---
  const bool warm = this->ContinueFromLastResult && !distributed && this->LastResult &&
    this->LastImage == image && this->LastImageTime == image->GetMTime() && this->LastSurface == surface &&
    this->LastSurfaceTime == surface->GetMTime();
  vtkDebugMacro(<< (warm ? "Warm start from the last result." : "Start from the initial surface."));
  dsurf::TriangleMesh mesh;
  if (!BuildMesh(warm ? this->LastResult.Get() : surface, mesh, error))
  {
    vtkErrorMacro("Bad initial surface: " << error << ".");
    return 1;
  }
  if (!mesh.IsConsistentlyOriented())
  {
    // Normals (the projection direction) and the refinement's invariants need neighbours
    // to agree; each piece keeps the orientation most of its triangles had.
    const int flipped = mesh.OrientConsistently();
    vtkWarningMacro("The initial surface was not consistently oriented: " << flipped
                                                                          << " triangle(s) flipped to agree with their neighbours.");
  }
  vtkDebugMacro("Initial surface: " << mesh.NumberOfPoints() << " points, "
                                    << mesh.NumberOfTriangles() << " triangles, signed volume "
                                    << mesh.SignedVolume() << ".");

  // --- the multilevel solve: dsurf::MultilevelSolver runs the
  // levels (sweeps, error estimator, red-green refinement, butterfly, sigma halving,
  // force field per level); here only parameters in and results out.
  dsurf::MultilevelParameters mp = this->SolveParameters();
  this->Snapshots.clear();
  this->AnimationResult = nullptr;
  if (this->AnimateSweeps)
  {
    mp.SweepBatch = 1; // a snapshot exactly every SweepsPerTimeStep sweeps
    this->Snapshots.push_back(MeshSnapshot(mesh, 0));
  }
  dsurf::MultilevelSolver solver;
  solver.SetParameters(mp);
  solver.SetProgressCallback([this](double f) {
    this->UpdateProgress(0.02 + 0.96 * f);
    return !this->GetAbortExecute();
  });
  ConvergenceColumns columns;
  solver.SetSweepCallback([&columns, this](const dsurf::SweepRecord& r, const dsurf::TriangleMesh& m) {
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
  if (!solver.Run(volume.Values, geometry, mesh, &error))
  {
    vtkErrorMacro("Deformable surface failed: " << error);
    output->Initialize();
    return 1;
  }
  this->Report(solver);

  // --- outputs ---
  FillOutput(mesh, solver, output);
  AddFieldData(solver, mesh, this->RegionWeight > 0, warm, output->GetFieldData());
  columns.AddTo(table);
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
  os << indent << "IntensityRange: " << this->IntensityRange[0] << " " << this->IntensityRange[1] << "\n";
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
