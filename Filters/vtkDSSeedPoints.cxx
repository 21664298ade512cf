// SPDX-License-Identifier: BSD-3-Clause
#include "vtkDSSeedPoints.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <cmath>

vtkStandardNewMacro(vtkDSSeedPoints);

vtkDSSeedPoints::vtkDSSeedPoints()
{
  this->SetNumberOfInputPorts(0);
}

namespace
{
// A count or index from a property must not be negative; a negative one counts as empty.
std::size_t Count(int count)
{
  return count > 0 ? static_cast<std::size_t>(count) : 0;
}

template <typename T>
bool SetAt(std::vector<T>& list, int index, T value)
{
  // A NaN never equals the stored value: it is stored again, which only costs a Modified().
  if (index < 0 || Count(index) >= list.size() || list[index] == value)
  {
    return false;
  }
  list[index] = value;
  return true;
}
}

void vtkDSSeedPoints::SetNumberOfPointCoordinates(int count)
{
  if (Count(count) != this->PointCoordinates.size())
  {
    this->PointCoordinates.resize(Count(count), 0.0);
    this->Modified();
  }
}

int vtkDSSeedPoints::GetNumberOfPointCoordinates() const
{
  return static_cast<int>(this->PointCoordinates.size());
}

void vtkDSSeedPoints::SetPointCoordinate(int index, double value)
{
  if (SetAt(this->PointCoordinates, index, value))
  {
    this->Modified();
  }
}

double vtkDSSeedPoints::GetPointCoordinate(int index) const
{
  return index >= 0 && Count(index) < this->PointCoordinates.size() ? this->PointCoordinates[index]
                                                                    : 0.0;
}

void vtkDSSeedPoints::SetNumberOfObjectIds(int count)
{
  if (Count(count) != this->ObjectIds.size())
  {
    this->ObjectIds.resize(Count(count), 0);
    this->Modified();
  }
}

int vtkDSSeedPoints::GetNumberOfObjectIds() const
{
  return static_cast<int>(this->ObjectIds.size());
}

void vtkDSSeedPoints::SetObjectId(int index, int objectId)
{
  if (SetAt(this->ObjectIds, index, objectId))
  {
    this->Modified();
  }
}

int vtkDSSeedPoints::GetObjectId(int index) const
{
  return index >= 0 && Count(index) < this->ObjectIds.size() ? this->ObjectIds[index] : 0;
}

void vtkDSSeedPoints::AddPoint(double x, double y, double z, int objectId)
{
  if (this->ObjectIds.empty())
  {
    this->ObjectIds.assign(this->PointCoordinates.size() / 3, 0);
  }
  this->PointCoordinates.insert(this->PointCoordinates.end(), { x, y, z });
  this->ObjectIds.push_back(objectId);
  this->Modified();
}

void vtkDSSeedPoints::RemoveAllPoints()
{
  if (!this->PointCoordinates.empty() || !this->ObjectIds.empty())
  {
    this->PointCoordinates.clear();
    this->ObjectIds.clear();
    this->Modified();
  }
}

bool vtkDSSeedPoints::CheckLists() const
{
  const std::size_t n = this->PointCoordinates.size();
  if (n % 3 != 0)
  {
    vtkErrorMacro(<< "Points holds " << n
                  << " coordinates, not a multiple of 3 (x y z per point).");
    return false;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!std::isfinite(this->PointCoordinates[i]))
    {
      vtkErrorMacro(<< "Point " << i / 3 << " has a coordinate that is not finite ("
                    << this->PointCoordinates[i] << ").");
      return false;
    }
  }
  if (!this->ObjectIds.empty() && this->ObjectIds.size() != n / 3)
  {
    vtkErrorMacro(<< "ObjectIds holds " << this->ObjectIds.size() << " values for " << n / 3
                  << " points: give one per point, or none (all object 0).");
    return false;
  }
  return true;
}

int vtkDSSeedPoints::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Pieces are handled (piece 0 holds every point, the others none): without this the pipeline
  // would hand every piece the whole list.
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkDSSeedPoints::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->Initialize();
  // Under MPI every process runs the source: only piece 0 holds the points, so Delaunay Seed
  // Surface, which gathers the points of all processes, sees each point once.
  const int piece = outputVector->GetInformationObject(0)->Get(
    vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
  if (piece > 0)
  {
    return 1;
  }
  if (!this->CheckLists())
  {
    return 1;
  }
  const vtkIdType n = static_cast<vtkIdType>(this->PointCoordinates.size() / 3);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkCellArray> vertices;
  vtkNew<vtkIntArray> objectIds;
  objectIds->SetName("ObjectId");
  objectIds->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    points->SetPoint(i, &this->PointCoordinates[3 * i]);
    vertices->InsertNextCell(1, &i);
    objectIds->SetValue(i, this->ObjectIds.empty() ? 0 : this->ObjectIds[i]);
  }
  output->SetPoints(points);
  output->SetVerts(vertices);
  output->GetPointData()->AddArray(objectIds);
  return 1;
}

void vtkDSSeedPoints::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Points: " << this->PointCoordinates.size() / 3 << "\n";
  os << indent << "ObjectIds: " << this->ObjectIds.size() << "\n";
}
