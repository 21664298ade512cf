// SPDX-License-Identifier: BSD-3-Clause
#include "vtkDelaunaySeedSurface.h"

#include "dsObjects.h"
#include "dsSeedSurface.h"
#include "dsTrilinear.h"
#include "dsVTKImage.h"

#include "vtkAppendFilter.h"
#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDSPolyDataGather.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDelaunay3D.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLinearSubdivisionFilter.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPlatonicSolidSource.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkDelaunaySeedSurface);
vtkCxxSetObjectMacro(vtkDelaunaySeedSurface, Controller, vtkMultiProcessController);

namespace
{
// Trilinear value of component 0 of the image's scalars at a physical point (dsTrilinear.h);
// false outside the image's extent. Read as double: no float conversion of the intensities.
bool SampleImage(vtkImageData* image, vtkDataArray* scalars, const double x[3], double& value)
{
  double ijk[3];
  image->TransformPhysicalPointToContinuousIndex(x, ijk);
  const int* ext = image->GetExtent();
  const int lo[3] = { ext[0], ext[2], ext[4] };
  const int hi[3] = { ext[1], ext[3], ext[5] };
  dsurf::TrilinearCell cell;
  if (!dsurf::LocateTrilinearCell(ijk, lo, hi, 1e-9, cell))
  {
    return false;
  }
  value = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    const double w = cell.Weight(corner);
    if (w != 0.0)
    {
      value += w * scalars->GetComponent(cell.Corner(corner), 0);
    }
  }
  return true;
}

// Collects every process's points (with their point data) on process 0, in process order, and
// turns inputId into indices of the concatenation of all processes' inputs. Collective: every
// process must call it. Returns false on the processes other than 0.
bool GatherPointsOnProcessZero(vtkMultiProcessController* controller, vtkIdType numberOfInputPoints,
  vtkSmartPointer<vtkPolyData>& points, std::vector<vtkIdType>& inputId)
{
  const int nProcs = controller->GetNumberOfProcesses();
  const int me = controller->GetLocalProcessId();
  // Each process offsets its input IDs by the input sizes of the processes before it, so the
  // IDs stay unique once the pieces are appended.
  long long localCount = numberOfInputPoints;
  std::vector<long long> counts(static_cast<std::size_t>(nProcs), 0);
  controller->AllGather(&localCount, counts.data(), 1);
  vtkIdType offset = 0;
  for (int p = 0; p < me; ++p)
  {
    offset += static_cast<vtkIdType>(counts[p]);
  }

  vtkNew<vtkPolyData> piece;
  piece->ShallowCopy(points);
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("vtkDSInputId");
  ids->SetNumberOfTuples(static_cast<vtkIdType>(inputId.size()));
  for (std::size_t i = 0; i < inputId.size(); ++i)
  {
    ids->SetValue(static_cast<vtkIdType>(i), offset + inputId[i]);
  }
  piece->GetPointData()->AddArray(ids);
  vtkNew<vtkPolyData> all;
  if (!vtkDSPolyDataGather::GatherOnProcessZero(controller, piece, all))
  {
    return false;
  }

  inputId.clear();
  points = vtkSmartPointer<vtkPolyData>::New();
  vtkIdTypeArray* allIds =
    vtkIdTypeArray::SafeDownCast(all->GetPointData()->GetArray("vtkDSInputId"));
  if (allIds && all->GetNumberOfPoints() > 0)
  {
    inputId.assign(allIds->GetPointer(0), allIds->GetPointer(0) + allIds->GetNumberOfTuples());
    points->ShallowCopy(all);
    points->GetPointData()->RemoveArray("vtkDSInputId");
  }
  return true;
}

// Larger coordinates are dropped like non-finite ones: vtkDelaunay3D squares distances and
// builds a bounding tetrahedron much larger than the points, which overflows for coordinates
// beyond about 1e150 (it then crashes). No data set means such values.
constexpr double MaxCoordinate = 1e100;

// Copies the input's finite, non-ghost points with their point data and records each one's
// input index in inputId. Delaunay3D's bounds and locator break on non-finite points (and on
// coordinates beyond MaxCoordinate); a ghost copy of another process's point is dropped because
// that process contributes the point itself.
vtkSmartPointer<vtkPolyData> CleanPoints(
  vtkObject* self, vtkPointSet* input, std::vector<vtkIdType>& inputId)
{
  const vtkIdType nIn = input->GetNumberOfPoints();
  vtkSmartPointer<vtkPolyData> finite = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> finitePoints;
  finitePoints->SetDataTypeToDouble();
  vtkDataArray* ghosts = input->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName());
  finite->GetPointData()->CopyAllocate(input->GetPointData(), nIn);
  vtkIdType nonFinite = 0;
  for (vtkIdType i = 0; i < nIn; ++i)
  {
    if (ghosts &&
      (static_cast<int>(ghosts->GetTuple1(i)) &
        (vtkDataSetAttributes::DUPLICATEPOINT | vtkDataSetAttributes::HIDDENPOINT)))
    {
      continue;
    }
    double x[3];
    input->GetPoint(i, x);
    if (std::abs(x[0]) <= MaxCoordinate && std::abs(x[1]) <= MaxCoordinate &&
      std::abs(x[2]) <= MaxCoordinate) // false for NaN too
    {
      finite->GetPointData()->CopyData(input->GetPointData(), i, finitePoints->InsertNextPoint(x));
      inputId.push_back(i);
    }
    else
    {
      ++nonFinite;
    }
  }
  finite->SetPoints(finitePoints);
  finite->GetPointData()->RemoveArray(vtkDataSetAttributes::GhostArrayName());
  if (nonFinite > 0)
  {
    vtkWarningWithObjectMacro(self,
      "Ignored " << nonFinite << " point(s) with NaN, infinite or out-of-range (beyond "
                 << MaxCoordinate << ") coordinates.");
  }
  return finite;
}

// Coordinates near the largest double overflow on the way to the surface (a sphere seed's
// radius added to them, edge midpoints, pinch copies): such a surface is replaced by an error
// and an empty output rather than passed on with infinite points.
void EmptyIfNotFinite(vtkObject* self, vtkPolyData* surface)
{
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double x[3];
    surface->GetPoint(i, x);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    {
      vtkErrorWithObjectMacro(self,
        "The point coordinates are too large: the seed surface "
        "overflows to infinite coordinates; no surface.");
      surface->Initialize();
      return;
    }
  }
}

// The full tetrahedrisation in the core's terms, with what the removal rules and outputs need.
struct SeedComplex
{
  vtkSmartPointer<vtkUnstructuredGrid> Grid; // vtkDelaunay3D's output (points, point data)
  std::vector<dsurf::Vec3> Points;
  std::vector<dsurf::SeedTet> Tets; // the VTK_TETRA cells in order: the index is the TetraId
  std::vector<double> Radius;       // circumradius of each tetrahedron
  double FlatVolume = 0.0;          // |volume| at or below which a tetrahedron counts as flat
  bool AnySolid = false;            // at least one tetrahedron is not flat
};

// Tetrahedrises all points with vtkDelaunay3D and measures every tetrahedron. Flatness is
// relative to the bounding-box diagonal so it does not depend on the data's units.
SeedComplex Tetrahedralize(vtkPolyData* finite, double tolerance)
{
  vtkNew<vtkDelaunay3D> delaunay;
  delaunay->SetInputData(finite);
  delaunay->SetAlpha(0.0); // our own Alpha rule keeps the tetrahedron IDs stable
  delaunay->SetTolerance(tolerance);
  delaunay->Update();
  SeedComplex complex;
  complex.Grid = delaunay->GetOutput();
  vtkUnstructuredGrid* grid = complex.Grid;

  auto& points = complex.Points;
  auto& tets = complex.Tets;
  points.resize(static_cast<std::size_t>(grid->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    grid->GetPoint(i, points[i].data());
  }
  vtkNew<vtkIdList> cellPoints;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    if (grid->GetCellType(c) == VTK_TETRA)
    {
      grid->GetCellPoints(c, cellPoints);
      tets.push_back(
        { cellPoints->GetId(0), cellPoints->GetId(1), cellPoints->GetId(2), cellPoints->GetId(3) });
    }
  }

  double bounds[6];
  finite->GetBounds(bounds);
  const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  complex.FlatVolume = 1e-10 * diagonal * diagonal * diagonal;
  complex.Radius.resize(tets.size());
  for (std::size_t t = 0; t < tets.size(); ++t)
  {
    const auto& c = tets[t];
    complex.Radius[t] =
      dsurf::SeedTetCircumradius(points[c[0]], points[c[1]], points[c[2]], points[c[3]]);
    complex.AnySolid = complex.AnySolid ||
      std::abs(dsurf::SeedTetSignedVolume(points[c[0]], points[c[1]], points[c[2]], points[c[3]])) >
        complex.FlatVolume;
  }
  return complex;
}

// Rule 1: the user's tetrahedron IDs. IDs outside this tetrahedrisation (stale after the points
// changed) are ignored with one warning.
void RemoveById(
  vtkObject* self, const std::vector<vtkIdType>& removedIds, std::vector<unsigned char>& status)
{
  const vtkIdType nTets = static_cast<vtkIdType>(status.size());
  vtkIdType outOfRange = 0;
  for (vtkIdType id : removedIds)
  {
    if (id >= 0 && id < nTets)
    {
      status[id] = dsurf::SeedRemovedById;
    }
    else
    {
      ++outOfRange;
    }
  }
  if (outOfRange > 0)
  {
    vtkWarningWithObjectMacro(
      self, << outOfRange << " RemovedTetrahedra ID(s) are not in [0, " << nTets << "): ignored.");
  }
}

// Rule 2: circumsphere radius above alpha (only tetrahedra no earlier rule removed).
void RemoveByAlpha(
  const std::vector<double>& radius, double alpha, std::vector<unsigned char>& status)
{
  for (std::size_t t = 0; t < status.size(); ++t)
  {
    if (status[t] == dsurf::SeedKept && radius[t] > alpha)
    {
      status[t] = dsurf::SeedRemovedByAlpha;
    }
  }
}

// Rule 3: image value at the centroid outside [range[0], range[1]], or centroid outside the
// image. Returns every tetrahedron's centroid value (NaN outside) for the output, or nothing
// when there is no image with point scalars (then the rule is skipped with a warning).
std::vector<double> RemoveByIntensity(vtkObject* self, vtkImageData* image, const double range[2],
  const SeedComplex& complex, std::vector<unsigned char>& status)
{
  std::vector<double> centroidValue;
  std::string how;
  vtkDataArray* scalars = image ? dsurf::ChooseImageScalars(image, nullptr, how) : nullptr;
  if (!scalars || scalars->GetNumberOfComponents() != 1)
  {
    vtkWarningWithObjectMacro(self,
      "UseIntensityRange is on but no image with one-component point scalars is connected to "
      "port 1 (Image)"
        << (how.empty() ? std::string() : " (" + how + ")") << ": the intensity rule is skipped.");
    return centroidValue;
  }
  const auto& points = complex.Points;
  centroidValue.assign(complex.Tets.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t t = 0; t < complex.Tets.size(); ++t)
  {
    const auto& c = complex.Tets[t];
    double centroid[3];
    for (int d = 0; d < 3; ++d)
    {
      centroid[d] = 0.25 * (points[c[0]][d] + points[c[1]][d] + points[c[2]][d] + points[c[3]][d]);
    }
    double value;
    const bool inside = SampleImage(image, scalars, centroid, value);
    if (inside)
    {
      centroidValue[t] = value;
    }
    if (status[t] == dsurf::SeedKept && (!inside || value < range[0] || value > range[1]))
    {
      status[t] = dsurf::SeedRemovedByIntensity;
    }
  }
  return centroidValue;
}

// The boundary of the kept tetrahedra, with pinches and flat tetrahedra resolved by the core
// (which may mark more tetrahedra in status), subdivided to the target edge length.
dsurf::SeedSurface ExtractSurface(vtkObject* self, const SeedComplex& complex,
  std::vector<unsigned char>& status, double targetEdgeLength)
{
  dsurf::SeedBoundaryReport report;
  dsurf::SeedSurface surface =
    dsurf::ExtractSeedBoundary(complex.Points, complex.Tets, status, complex.FlatVolume, report);
  if (surface.Triangles.empty())
  {
    vtkWarningWithObjectMacro(self,
      "Every one of the " << static_cast<vtkIdType>(complex.Tets.size())
                          << " tetrahedra was removed: the surface is empty.");
  }
  else
  {
    const std::string summary = report.Summary();
    if (!summary.empty())
    {
      vtkWarningWithObjectMacro(self, "Seed surface: " << summary << ".");
    }
    dsurf::SubdivideSeedSurface(surface, targetEdgeLength);
  }
  return surface;
}

// Output 0: the surface, each point with the input point it came from (-1 for new points).
void BuildSurfaceOutput(
  const dsurf::SeedSurface& surface, const std::vector<vtkIdType>& inputId, vtkPolyData* surfaceOut)
{
  vtkNew<vtkPoints> outPoints;
  outPoints->SetDataTypeToDouble();
  outPoints->SetNumberOfPoints(static_cast<vtkIdType>(surface.Points.size()));
  vtkNew<vtkIdTypeArray> seedId;
  seedId->SetName("SeedPointId");
  seedId->SetNumberOfTuples(static_cast<vtkIdType>(surface.Points.size()));
  for (std::size_t p = 0; p < surface.Points.size(); ++p)
  {
    outPoints->SetPoint(static_cast<vtkIdType>(p), surface.Points[p].data());
    const std::int64_t source = surface.SourcePoint[p];
    seedId->SetValue(static_cast<vtkIdType>(p), source >= 0 ? inputId[source] : -1);
  }
  vtkNew<vtkCellArray> triangles;
  triangles->AllocateExact(
    static_cast<vtkIdType>(surface.Triangles.size()), 3 * surface.Triangles.size());
  for (const auto& tri : surface.Triangles)
  {
    const vtkIdType ids[3] = { tri[0], tri[1], tri[2] };
    triangles->InsertNextCell(3, ids);
  }
  surfaceOut->SetPoints(outPoints);
  surfaceOut->SetPolys(triangles);
  surfaceOut->GetPointData()->AddArray(seedId);
}

// Output 1: every tetrahedron with its stable ID and why it was removed.
void BuildTetrahedraOutput(const SeedComplex& complex, const std::vector<unsigned char>& status,
  const std::vector<double>& centroidValue, vtkUnstructuredGrid* tetsOut)
{
  const auto& tets = complex.Tets;
  const vtkIdType nTets = static_cast<vtkIdType>(tets.size());
  vtkNew<vtkCellArray> tetCells;
  tetCells->AllocateExact(nTets, 4 * nTets);
  vtkNew<vtkIdTypeArray> tetraId;
  tetraId->SetName("TetraId");
  vtkNew<vtkUnsignedCharArray> removed;
  removed->SetName("Removed");
  vtkNew<vtkDoubleArray> circumradius;
  circumradius->SetName("Circumradius");
  for (vtkIdType t = 0; t < nTets; ++t)
  {
    const vtkIdType ids[4] = { tets[t][0], tets[t][1], tets[t][2], tets[t][3] };
    tetCells->InsertNextCell(4, ids);
    tetraId->InsertNextValue(t);
    removed->InsertNextValue(status[t]);
    circumradius->InsertNextValue(complex.Radius[t]);
  }
  tetsOut->SetPoints(complex.Grid->GetPoints());
  tetsOut->GetPointData()->ShallowCopy(complex.Grid->GetPointData());
  tetsOut->SetCells(VTK_TETRA, tetCells);
  tetsOut->GetCellData()->AddArray(tetraId);
  tetsOut->GetCellData()->AddArray(removed);
  tetsOut->GetCellData()->AddArray(circumradius);
  tetsOut->GetCellData()->SetActiveScalars("Removed");
  if (!centroidValue.empty())
  {
    vtkNew<vtkDoubleArray> values;
    values->SetName("CentroidValue");
    values->SetNumberOfTuples(nTets);
    for (vtkIdType t = 0; t < nTets; ++t)
    {
      values->SetValue(t, centroidValue[t]);
    }
    tetsOut->GetCellData()->AddArray(values);
  }
}

// Every cell of `data` labelled `value` in an id-type cell array `name`.
void LabelCells(vtkDataSet* data, const char* name, long long value)
{
  vtkNew<vtkIdTypeArray> labels;
  labels->SetName(name);
  labels->SetNumberOfTuples(data->GetNumberOfCells());
  labels->FillValue(static_cast<vtkIdType>(value));
  data->GetCellData()->AddArray(labels);
}

// The TetraIds of one group's tetrahedra moved past the groups before it.
void ShiftTetraIds(vtkUnstructuredGrid* tets, vtkIdType first)
{
  vtkIdTypeArray* ids = vtkIdTypeArray::SafeDownCast(tets->GetCellData()->GetArray("TetraId"));
  for (vtkIdType t = 0; ids && t < ids->GetNumberOfTuples(); ++t)
  {
    ids->SetValue(t, ids->GetValue(t) + first);
  }
}

constexpr const char* ObjectIdName = "ObjectId";

// Indices of the first `enough` points of `points` that are pairwise farther apart than
// tolerance x the bounding-box diagonal (vtkDelaunay3D's merge distance), in input order.
std::vector<vtkIdType> FirstDistinctPoints(
  vtkPolyData* points, double tolerance, std::size_t enough)
{
  std::vector<vtkIdType> distinct;
  const double merge = tolerance * std::sqrt(points->GetLength2());
  for (vtkIdType i = 0; i < points->GetNumberOfPoints() && distinct.size() < enough; ++i)
  {
    double x[3];
    points->GetPoint(i, x);
    bool repeated = false;
    for (vtkIdType j : distinct)
    {
      double y[3];
      points->GetPoint(j, y);
      repeated = repeated || std::sqrt(vtkMath::Distance2BetweenPoints(x, y)) <= merge;
    }
    if (!repeated)
    {
      distinct.push_back(i);
    }
  }
  return distinct;
}

// One to three points: a sphere of `radius` around each (an icosahedron subdivided twice,
// projected onto the sphere: 162 vertices, 320 well-shaped triangles), outward-oriented,
// each sphere's vertices carrying its point's SeedPointId. Overlapping spheres are warned
// about: their union is not a manifold surface.
void BuildSphereSeeds(vtkObject* self, vtkPolyData* points, const std::vector<vtkIdType>& inputId,
  double radius, vtkPolyData* output)
{
  vtkNew<vtkPlatonicSolidSource> icosahedron;
  icosahedron->SetSolidTypeToIcosahedron();
  vtkNew<vtkLinearSubdivisionFilter> subdivide;
  subdivide->SetInputConnection(icosahedron->GetOutputPort());
  subdivide->SetNumberOfSubdivisions(2);
  subdivide->Update();
  vtkPolyData* unit = subdivide->GetOutput();
  const vtkIdType perSphere = unit->GetNumberOfPoints();
  // Outward orientation: the first triangle's normal points away from the centre.
  bool flip = false;
  {
    vtkIdType npts;
    const vtkIdType* ids;
    unit->GetPolys()->InitTraversal();
    unit->GetPolys()->GetNextCell(npts, ids);
    double a[3], b[3], c[3], ab[3], ac[3], n[3];
    unit->GetPoint(ids[0], a);
    unit->GetPoint(ids[1], b);
    unit->GetPoint(ids[2], c);
    vtkMath::Subtract(b, a, ab);
    vtkMath::Subtract(c, a, ac);
    vtkMath::Cross(ab, ac, n);
    flip = vtkMath::Dot(n, a) < 0;
  }

  vtkNew<vtkPoints> outPoints;
  outPoints->SetDataTypeToDouble();
  vtkNew<vtkCellArray> triangles;
  vtkNew<vtkIdTypeArray> seedId;
  seedId->SetName("SeedPointId");
  const vtkIdType n = points->GetNumberOfPoints();
  for (vtkIdType s = 0; s < n; ++s)
  {
    double c[3];
    points->GetPoint(s, c);
    for (vtkIdType t = 0; t < s; ++t)
    {
      double o[3];
      points->GetPoint(t, o);
      if (std::sqrt(vtkMath::Distance2BetweenPoints(c, o)) < 2 * radius)
      {
        vtkWarningWithObjectMacro(self,
          "Seed spheres around points " << inputId[t] << " and " << inputId[s]
                                        << " overlap (SeedRadius " << radius
                                        << "): pick farther apart or use a smaller SeedRadius.");
      }
    }
    for (vtkIdType p = 0; p < perSphere; ++p)
    {
      double x[3];
      unit->GetPoint(p, x);
      const double len = vtkMath::Norm(x);
      outPoints->InsertNextPoint(
        c[0] + radius * x[0] / len, c[1] + radius * x[1] / len, c[2] + radius * x[2] / len);
      seedId->InsertNextValue(inputId[s]);
    }
    vtkCellArray* polys = unit->GetPolys();
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType npts;
      const vtkIdType* ids;
      it->GetCurrentCell(npts, ids);
      const vtkIdType tri[3] = { ids[0] + s * perSphere, ids[flip ? 2 : 1] + s * perSphere,
        ids[flip ? 1 : 2] + s * perSphere };
      triangles->InsertNextCell(3, tri);
    }
  }
  output->SetPoints(outPoints);
  output->SetPolys(triangles);
  output->GetPointData()->AddArray(seedId);
}
} // namespace

vtkDelaunaySeedSurface::vtkDelaunaySeedSurface()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkDelaunaySeedSurface::~vtkDelaunaySeedSurface()
{
  this->SetController(nullptr);
}

void vtkDelaunaySeedSurface::SetImageConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

void vtkDelaunaySeedSurface::SetImageData(vtkImageData* image)
{
  this->SetInputData(1, image);
}

void vtkDelaunaySeedSurface::AddRemovedTetrahedron(vtkIdType id)
{
  this->RemovedTetrahedra.push_back(id);
  this->Modified();
}

void vtkDelaunaySeedSurface::RemoveAllRemovedTetrahedra()
{
  if (!this->RemovedTetrahedra.empty())
  {
    this->RemovedTetrahedra.clear();
    this->Modified();
  }
}

vtkIdType vtkDelaunaySeedSurface::GetNumberOfRemovedTetrahedra() const
{
  return static_cast<vtkIdType>(this->RemovedTetrahedra.size());
}

vtkIdType vtkDelaunaySeedSurface::GetRemovedTetrahedron(vtkIdType i) const
{
  return i >= 0 && i < this->GetNumberOfRemovedTetrahedra() ? this->RemovedTetrahedra[i] : -1;
}

vtkUnstructuredGrid* vtkDelaunaySeedSurface::GetTetrahedra()
{
  return vtkUnstructuredGrid::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkDelaunaySeedSurface::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  }
  else
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkDelaunaySeedSurface::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkUnstructuredGrid");
  return 1;
}

int vtkDelaunaySeedSurface::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->Superclass::RequestUpdateExtent(request, inputVector, outputVector);
  // The centroid of any tetrahedron may fall anywhere in the image: ask for all of it, also
  // when the pipeline runs distributed and would otherwise hand each process one piece.
  if (vtkInformation* imageInfo = inputVector[1]->GetInformationObject(0))
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
  return 1;
}

int vtkDelaunaySeedSurface::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0], 0);
  vtkImageData* image = vtkImageData::GetData(inputVector[1], 0);
  vtkPolyData* surfaceOut = vtkPolyData::GetData(outputVector, 0);
  vtkUnstructuredGrid* tetsOut = vtkUnstructuredGrid::GetData(outputVector, 1);
  if (!input || !surfaceOut || !tetsOut)
  {
    vtkErrorMacro("Missing input or output.");
    return 0;
  }
  surfaceOut->Initialize();
  tetsOut->Initialize();

  std::vector<vtkIdType> inputId;
  vtkSmartPointer<vtkPolyData> finite = CleanPoints(this, input, inputId);
  // Distributed input: one process tetrahedrises all points, the others output nothing, so
  // the seed is the one of the whole point set and is not duplicated downstream. The gather is
  // collective, so no process may return before it.
  if (vtkDSPolyDataGather::IsDistributed(this->Controller) &&
    !GatherPointsOnProcessZero(this->Controller, input->GetNumberOfPoints(), finite, inputId))
  {
    return 1;
  }
  const std::string nonFinite =
    dsurf::FirstNonFinite({ { "SeedRadius", this->SeedRadius }, { "Alpha", this->Alpha },
      { "TargetEdgeLength", this->TargetEdgeLength }, { "Tolerance", this->Tolerance } });
  if (!nonFinite.empty())
  {
    vtkErrorMacro(<< nonFinite << " is not a finite number: set it to a value in its range.");
    return 1;
  }
  if (inputId.empty())
  {
    vtkErrorMacro("No point with finite coordinates (within 1e100): nothing to seed from.");
    return 1;
  }
  vtkDataArray* objectIds = finite->GetPointData()->GetArray("ObjectId");
  if (!objectIds)
  {
    this->SeedObject(finite, inputId, image, this->RemovedTetrahedra, surfaceOut, tetsOut);
    return 1;
  }
  this->SeedObjects(finite, inputId, objectIds, image, surfaceOut, tetsOut);
  return 1;
}

//------------------------------------------------------------------------------
// Several objects (docs/METHOD.md §9.9): each group of points with one ObjectId is seeded on
// its own, in ascending ObjectId; TetraIds run on from one group to the next.
void vtkDelaunaySeedSurface::SeedObjects(vtkPolyData* finite, const std::vector<vtkIdType>& inputId,
  vtkDataArray* objectIds, vtkImageData* image, vtkPolyData* surfaceOut,
  vtkUnstructuredGrid* tetsOut)
{
  std::map<long long, std::vector<vtkIdType>> groups;
  for (vtkIdType p = 0; p < finite->GetNumberOfPoints(); ++p)
  {
    const double value = objectIds->GetComponent(p, 0);
    if (objectIds->GetNumberOfComponents() != 1 || !(std::abs(value) < 9e15) ||
      value != std::floor(value))
    {
      vtkErrorMacro("The point array ObjectId must hold one whole number per point (point "
        << inputId[p] << " has " << value << "): no surface.");
      return;
    }
    groups[static_cast<long long>(value)].push_back(p);
  }
  if (static_cast<int>(groups.size()) > dsurf::MaxObjects)
  {
    vtkErrorMacro("The points carry " << groups.size() << " ObjectId values; at most "
                                      << dsurf::MaxObjects
                                      << " objects are seeded (and solved) at once: no surface.");
    return;
  }
  vtkNew<vtkAppendPolyData> surfaces;
  vtkNew<vtkAppendFilter> tetrahedra;
  vtkIdType firstTetra = 0;
  for (const auto& group : groups)
  {
    vtkNew<vtkPolyData> points;
    vtkNew<vtkPoints> xyz;
    xyz->SetDataTypeToDouble();
    std::vector<vtkIdType> ids;
    for (vtkIdType p : group.second)
    {
      xyz->InsertNextPoint(finite->GetPoint(p));
      ids.push_back(inputId[p]);
    }
    points->SetPoints(xyz);
    std::vector<vtkIdType> removed;
    for (vtkIdType id : this->RemovedTetrahedra)
    {
      removed.push_back(id - firstTetra); // ids of other groups fall outside this one's range
    }
    vtkNew<vtkPolyData> surface;
    vtkNew<vtkUnstructuredGrid> tets;
    if (!this->SeedObject(points, ids, image, removed, surface, tets))
    {
      vtkErrorMacro("The points of ObjectId " << group.first << " give no seed: no surface.");
      surfaceOut->Initialize();
      tetsOut->Initialize();
      return;
    }
    LabelCells(surface, ObjectIdName, group.first);
    surfaces->AddInputData(surface);
    if (tets->GetNumberOfCells() > 0)
    {
      ShiftTetraIds(tets, firstTetra);
      LabelCells(tets, ObjectIdName, group.first);
      tetrahedra->AddInputData(tets);
      firstTetra += tets->GetNumberOfCells();
    }
  }
  surfaces->Update();
  surfaceOut->ShallowCopy(surfaces->GetOutput());
  if (tetrahedra->GetNumberOfInputConnections(0) > 0)
  {
    tetrahedra->Update();
    tetsOut->ShallowCopy(tetrahedra->GetOutput());
  }
}

//------------------------------------------------------------------------------
bool vtkDelaunaySeedSurface::SeedObject(vtkPolyData* finite, const std::vector<vtkIdType>& inputId,
  vtkImageData* image, const std::vector<vtkIdType>& removedIds, vtkPolyData* surfaceOut,
  vtkUnstructuredGrid* tetsOut)
{
  const std::vector<vtkIdType> distinct = FirstDistinctPoints(finite, this->Tolerance, 4);
  if (distinct.size() < 4)
  {
    // Too few points for a tetrahedron (a click, or the same click twice): one small sphere
    // around each distinct point.
    if (finite->GetNumberOfPoints() >= 4)
    {
      vtkWarningMacro("The " << finite->GetNumberOfPoints() << " points merge into "
                             << distinct.size() << " within Tolerance x the bounding-box diagonal ("
                             << this->Tolerance * std::sqrt(finite->GetLength2())
                             << "): a seed sphere around each instead of their hull; lower "
                                "Tolerance to keep them apart.");
    }
    vtkNew<vtkPoints> centres;
    std::vector<vtkIdType> centreIds;
    for (vtkIdType p : distinct)
    {
      centres->InsertNextPoint(finite->GetPoint(p));
      centreIds.push_back(inputId[p]);
    }
    vtkNew<vtkPolyData> clicks;
    clicks->SetPoints(centres);
    BuildSphereSeeds(this, clicks, centreIds, this->SeedRadius, surfaceOut);
    EmptyIfNotFinite(this, surfaceOut);
    return surfaceOut->GetNumberOfPolys() > 0;
  }

  const SeedComplex complex = Tetrahedralize(finite, this->Tolerance);
  if (!complex.AnySolid)
  {
    vtkErrorMacro("The " << inputId.size()
                         << " points span no volume (all coplanar, collinear or coincident): "
                            "no tetrahedra, no surface.");
    return surfaceOut->GetNumberOfPolys() > 0;
  }

  // The removal rules in order of precedence: a tetrahedron keeps the first reason it got.
  std::vector<unsigned char> status(complex.Tets.size(), dsurf::SeedKept);
  RemoveById(this, removedIds, status);
  if (this->Alpha > 0.0)
  {
    RemoveByAlpha(complex.Radius, this->Alpha, status);
  }
  std::vector<double> centroidValue;
  if (this->UseIntensityRange)
  {
    centroidValue = RemoveByIntensity(this, image, this->IntensityRange, complex, status);
  }

  const dsurf::SeedSurface surface = ExtractSurface(this, complex, status, this->TargetEdgeLength);
  BuildSurfaceOutput(surface, inputId, surfaceOut);
  EmptyIfNotFinite(this, surfaceOut);
  BuildTetrahedraOutput(complex, status, centroidValue, tetsOut);
  return surfaceOut->GetNumberOfPolys() > 0;
}

void vtkDelaunaySeedSurface::PrintSelf(ostream& os, vtkIndent indent)
{
  os << indent << "SeedRadius: " << this->SeedRadius << "\n";
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RemovedTetrahedra: " << this->RemovedTetrahedra.size() << " ID(s)\n";
  os << indent << "Alpha: " << this->Alpha << "\n";
  os << indent << "UseIntensityRange: " << this->UseIntensityRange << "\n";
  os << indent << "IntensityRange: " << this->IntensityRange[0] << " " << this->IntensityRange[1]
     << "\n";
  os << indent << "TargetEdgeLength: " << this->TargetEdgeLength << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
