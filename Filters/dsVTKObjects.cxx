// SPDX-License-Identifier: BSD-3-Clause
#include "dsVTKObjects.h"

#include "dsMultilevel.h"
#include "dsObjects.h"
#include "dsTriangleMesh.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <cmath>

namespace dsurf
{
bool ReadObjectIds(vtkPolyData* surface, std::vector<long long>& ids, std::string& error)
{
  ids.clear();
  vtkAbstractArray* any = surface->GetCellData()->GetAbstractArray(ObjectIdArrayName);
  if (!any)
  {
    return true;
  }
  vtkDataArray* array = vtkDataArray::SafeDownCast(any);
  if (!array || array->GetNumberOfComponents() != 1)
  {
    error = "the cell array ObjectId must be one number per cell";
    return false;
  }
  const vtkIdType skip = surface->GetNumberOfVerts() + surface->GetNumberOfLines();
  const vtkIdType count = surface->GetNumberOfPolys() + surface->GetNumberOfStrips();
  if (array->GetNumberOfTuples() < skip + count)
  {
    error = "the cell array ObjectId has fewer values than the surface has cells";
    return false;
  }
  ids.resize(static_cast<std::size_t>(count));
  for (vtkIdType c = 0; c < count; ++c)
  {
    // Whole numbers in any type (a Calculator makes doubles).
    const double value = array->GetComponent(skip + c, 0);
    if (!(std::abs(value) < 9e15) || value != std::floor(value))
    {
      error = "the cell array ObjectId must hold whole numbers (cell " + std::to_string(skip + c) +
        " has " + std::to_string(value) + ")";
      return false;
    }
    ids[c] = static_cast<long long>(value);
  }
  return true;
}

void CopyPolygonObjectIds(vtkPolyData* from, vtkPolyData* to)
{
  std::vector<long long> ids;
  std::string ignored;
  if (!ReadObjectIds(from, ids, ignored) || ids.empty())
  {
    return;
  }
  vtkNew<vtkIdTypeArray> array;
  array->SetName(ObjectIdArrayName);
  array->SetNumberOfTuples(static_cast<vtkIdType>(ids.size()));
  for (std::size_t c = 0; c < ids.size(); ++c)
  {
    array->SetValue(static_cast<vtkIdType>(c), static_cast<vtkIdType>(ids[c]));
  }
  to->GetCellData()->AddArray(array);
}

namespace
{
long long UserId(const TriangleMesh& mesh, int object)
{
  return object < static_cast<int>(mesh.ObjectIds.size()) ? mesh.ObjectIds[object] : 0;
}
int ObjectOf(const TriangleMesh& mesh, int point)
{
  return mesh.Objects.empty() ? 0 : mesh.Objects[point];
}
} // namespace

void AddObjectArrays(const TriangleMesh& mesh, vtkPolyData* output)
{
  vtkNew<vtkIdTypeArray> points, cells;
  points->SetName(ObjectIdArrayName);
  cells->SetName(ObjectIdArrayName);
  points->SetNumberOfTuples(mesh.NumberOfPoints());
  cells->SetNumberOfTuples(mesh.NumberOfTriangles());
  for (int v = 0; v < mesh.NumberOfPoints(); ++v)
  {
    points->SetValue(v, static_cast<vtkIdType>(UserId(mesh, ObjectOf(mesh, v))));
  }
  for (int t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    cells->SetValue(t, static_cast<vtkIdType>(UserId(mesh, ObjectOf(mesh, mesh.Triangles[t][0]))));
  }
  output->GetPointData()->AddArray(points);
  output->GetCellData()->AddArray(cells);
}

void AddObjectFieldData(const TriangleMesh& mesh, const std::vector<ObjectRegion>& regions,
  int crossingPairs, vtkFieldData* fd)
{
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("ObjectIds");
  vtkNew<vtkDoubleArray> volumes;
  volumes->SetName("ObjectVolumes");
  vtkNew<vtkIntArray> vertices;
  vertices->SetName("ObjectVertices");
  vtkNew<vtkDoubleArray> ranges;
  ranges->SetName("ObjectIntensityRanges");
  ranges->SetNumberOfComponents(2);
  vtkNew<vtkDoubleArray> weights;
  weights->SetName("ObjectRegionWeights");
  for (int o = 0; o < static_cast<int>(mesh.ObjectIds.size()); ++o)
  {
    const TriangleMesh surface = ObjectSurface(mesh, o);
    ids->InsertNextValue(static_cast<vtkIdType>(mesh.ObjectIds[o]));
    volumes->InsertNextValue(surface.SignedVolume());
    vertices->InsertNextValue(surface.NumberOfPoints());
    const bool on = o < static_cast<int>(regions.size()) && regions[o].On;
    ranges->InsertNextTuple2(on ? regions[o].Low : 0.0, on ? regions[o].High : 0.0);
    weights->InsertNextValue(on ? regions[o].Weight : 0.0);
  }
  fd->AddArray(ids);
  fd->AddArray(volumes);
  fd->AddArray(vertices);
  fd->AddArray(ranges);
  fd->AddArray(weights);
  vtkNew<vtkIntArray> crossing;
  crossing->SetName("CrossingPairs");
  crossing->InsertNextValue(crossingPairs);
  fd->AddArray(crossing);
}
} // namespace dsurf
