// SPDX-License-Identifier: BSD-3-Clause
// Several objects in one run (docs/METHOD.md §9.9), as a user sets them up: clicks (or picks)
// carrying an ObjectId point array into Delaunay Seed Surface, its output into Deformable
// Surface, every default; and the scores of each object's surface (the output's cells of one
// ObjectId) against its label. Shared by TestSeveralObjects and BenchObjects.
#ifndef SeveralObjects_h
#define SeveralObjects_h

#include "ObjectScore.h"
#include "SeveralObjectPhantoms.h"

#include "vtkCellData.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkDeformableSurfaceFilter.h"
#include "vtkDelaunaySeedSurface.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkThreshold.h"
#include "vtkUnstructuredGrid.h"

#include <chrono>
#include <vector>

namespace dsobjects
{
/// Points with a point array ObjectId (ids[i] for points[i]).
inline vtkSmartPointer<vtkPolyData> LabelledPoints(
  const std::vector<Point3>& points, const std::vector<int>& ids)
{
  vtkNew<vtkPoints> xyz;
  vtkNew<vtkIdTypeArray> objectIds;
  objectIds->SetName("ObjectId");
  for (size_t i = 0; i < points.size(); ++i)
  {
    xyz->InsertNextPoint(points[i].data());
    objectIds->InsertNextValue(ids[i]);
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(xyz);
  cloud->GetPointData()->AddArray(objectIds);
  return cloud;
}

/// Delaunay Seed Surface on labelled points (removed: TetraIds to remove).
inline vtkSmartPointer<vtkPolyData> SeedObjects(
  vtkPolyData* points, const std::vector<vtkIdType>& removed = {})
{
  vtkNew<vtkDelaunaySeedSurface> seed;
  seed->SetInputData(points);
  for (vtkIdType id : removed)
    seed->AddRemovedTetrahedron(id);
  seed->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(seed->GetOutput());
  return out;
}

struct SeveralResult
{
  vtkSmartPointer<vtkPolyData> Surface;
  double Seconds = 0;
};

/// Deformable Surface from `seed` on `image`, every default but the ranges given per object
/// (`objectRanges`: ObjectId, low, high, ...; the filter's ObjectIntensityRanges).
inline SeveralResult RunSeveral(
  vtkImageData* image, vtkPolyData* seed, const std::vector<double>& objectRanges = {})
{
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceData(seed);
  for (std::size_t i = 0; i + 2 < objectRanges.size(); i += 3)
    filter->AddObjectIntensityRange(objectRanges[i], objectRanges[i + 1], objectRanges[i + 2]);
  const auto t0 = std::chrono::steady_clock::now();
  filter->Update();
  SeveralResult r;
  r.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.Surface = vtkSmartPointer<vtkPolyData>::New();
  r.Surface->ShallowCopy(filter->GetOutput());
  return r;
}

/// The cells of `surface` whose ObjectId is `id`, as a surface.
inline vtkSmartPointer<vtkPolyData> ObjectPart(vtkPolyData* surface, int id)
{
  vtkNew<vtkThreshold> threshold;
  threshold->SetInputData(surface);
  threshold->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "ObjectId");
  threshold->SetLowerThreshold(id - 0.5);
  threshold->SetUpperThreshold(id + 0.5);
  threshold->SetThresholdFunction(vtkThreshold::THRESHOLD_BETWEEN);
  vtkNew<vtkDataSetSurfaceFilter> geometry;
  geometry->SetInputConnection(threshold->GetOutputPort());
  geometry->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(geometry->GetOutput());
  return out;
}

/// The TetraIds a user removes from the engine's seed (EngineBlockPicks and two clicks): the
/// tetrahedra whose centroids lie in a bore, the dark air the user sees.
inline std::vector<vtkIdType> TetrahedraInBores(vtkPolyData* labelledPoints)
{
  vtkNew<vtkDelaunaySeedSurface> probe;
  probe->SetInputData(labelledPoints);
  probe->Update();
  std::vector<vtkIdType> inBores;
  vtkUnstructuredGrid* tets = probe->GetTetrahedra();
  vtkDataArray* ids = tets->GetCellData()->GetArray("TetraId");
  for (vtkIdType t = 0; ids && t < tets->GetNumberOfCells(); ++t)
  {
    double c[3] = { 0, 0, 0 }, x[3];
    for (int k = 0; k < 4; ++k)
    {
      tets->GetPoint(tets->GetCell(t)->GetPointId(k), x);
      for (int a = 0; a < 3; ++a)
        c[a] += x[a] / 4;
    }
    for (double bx : engine::BoreX)
      if (std::hypot(c[0] - bx, c[1] - engine::BoreY) < engine::BoreRadius)
        inBores.push_back(static_cast<vtkIdType>(ids->GetTuple1(t)));
  }
  return inBores;
}

/// One object's score (ObjectScore.h) against label `label`, and its interior's voxels.
inline ObjectScore ScoreObject(vtkPolyData* part, const ObjectPhantom& phantom, int label,
  std::vector<unsigned char>& interior,
  const std::function<bool(double, vtkIdType)>& keep = nullptr)
{
  const std::vector<unsigned char> reference = MaskOf(phantom.Label,
    [label, &keep](double l, vtkIdType v) { return l == label && (!keep || keep(l, v)); });
  interior = SurfaceInterior(part, phantom.Image);
  return Score(part, interior, reference, MaskBoundary(reference, phantom.Image), phantom.Image);
}

/// Voxels inside two or more of the interiors.
inline long long OverlapVoxels(const std::vector<std::vector<unsigned char>>& interiors)
{
  long long overlap = 0;
  for (size_t v = 0; !interiors.empty() && v < interiors[0].size(); ++v)
  {
    int n = 0;
    for (const auto& in : interiors)
      n += in[v];
    overlap += n > 1 ? 1 : 0;
  }
  return overlap;
}

/// A one-value field of the output (-1 when absent).
inline double FieldValue(vtkPolyData* surface, const char* name)
{
  vtkDataArray* a = surface->GetFieldData()->GetArray(name);
  return a && a->GetNumberOfTuples() > 0 ? a->GetTuple1(0) : -1.0;
}
} // namespace dsobjects

#endif
