// SPDX-License-Identifier: BSD-3-Clause
// Several objects in one run (docs/METHOD.md §9.9): clicks carrying an ObjectId into Delaunay
// Seed Surface, its output into Deformable Surface with every default.
// - Assembly (SeveralObjectPhantoms.h: two blocks of one material joined by a darker glue line
//   one voxel thick), a click in each: each surface within half a voxel (mean, both ways) of its
//   own block, no intersecting pair between them, no voxel inside both.
// - The spine and the engine: TestSeveralObjectsMeet.
// - One object with an ObjectId gives the same surface as without one, and the output carries
//   ObjectId per point and per cell and the per-object field data.
// - A warm start (ContinueFromLastResult) keeps the objects; starts that cross are an error.
// - A range given for one object (ObjectIntensityRanges) is the one it uses, and that object, a
//   click, pulls with RegionWeight 1 while the other keeps the default (ObjectRegionWeights).
// - Delaunay Seed Surface seeds each ObjectId group on its own and numbers TetraIds on.
#include "DSTestHelpers.h"
#include "OneClick.h"
#include "SeveralObjectsCheck.h"
#include "TestDelaunaySeedUtils.h"

#include "vtkCommand.h"
#include "vtkUnstructuredGrid.h"

#include <iostream>

using namespace dsobjects;

namespace
{

void Assembly()
{
  const SeveralPhantom s = AssemblyPhantom();
  const std::vector<int> ids = { 1, 2 };
  const SeveralResult r = RunSeveral(s.Phantom.Image, SeedObjects(LabelledPoints(s.Clicks, ids)));
  CheckObjects(s, r, ids, { 0.5, 0.5 }, "assembly");
  vtkDataArray* objectIds = r.Surface->GetFieldData()->GetArray("ObjectIds");
  DS_CHECK(objectIds && objectIds->GetNumberOfTuples() == 2 && objectIds->GetTuple1(0) == 1 &&
      objectIds->GetTuple1(1) == 2,
    "field ObjectIds lists the objects");
  DS_CHECK(r.Surface->GetFieldData()->GetArray("ObjectVolumes") &&
      r.Surface->GetFieldData()->GetArray("ObjectIntensityRanges"),
    "per-object volumes and ranges");
}

void GivenRanges()
{
  // A range given for object 2 only: it uses it, object 1 its estimate.
  const SeveralPhantom s = AssemblyPhantom();
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, s.Phantom.Image);
  filter->SetInitialSurfaceData(SeedObjects(LabelledPoints(s.Clicks, { 1, 2 })));
  filter->AddObjectIntensityRange(2, 80, 150);
  filter->AddObjectIntensityRange(7, 1, 2); // no such object: ignored
  filter->Update();
  vtkDataArray* ranges = filter->GetOutput()->GetFieldData()->GetArray("ObjectIntensityRanges");
  DS_CHECK(ranges && ranges->GetNumberOfTuples() == 2 && ranges->GetComponent(1, 0) == 80 &&
      ranges->GetComponent(1, 1) == 150 && ranges->GetComponent(0, 0) != 80,
    "object 2 uses its given range, object 1 its estimate");
  vtkDataArray* weights = filter->GetOutput()->GetFieldData()->GetArray("ObjectRegionWeights");
  DS_CHECK(weights && weights->GetNumberOfTuples() == 2 && weights->GetTuple1(0) == 0.3 &&
      weights->GetTuple1(1) == 1.0 && FieldValue(filter->GetOutput(), "RegionWeight") == 0.3,
    "object 2, a click given its range, pulls with 1; object 1 and the RegionWeight field 0.3");
  filter->RemoveAllObjectIntensityRanges();
  filter->Update();
  ranges = filter->GetOutput()->GetFieldData()->GetArray("ObjectIntensityRanges");
  DS_CHECK(ranges && ranges->GetComponent(1, 0) != 80, "removed: estimated again");
}

void WarmStartAndCrossingStarts()
{
  // ContinueFromLastResult: a second run from the last result keeps the objects apart.
  const SeveralPhantom s = AssemblyPhantom();
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, s.Phantom.Image);
  filter->SetInitialSurfaceData(SeedObjects(LabelledPoints(s.Clicks, { 1, 2 })));
  filter->ContinueFromLastResultOn();
  filter->Update();
  filter->SetConvergenceTolerance(5e-4);
  filter->Update();
  vtkPolyData* warm = filter->GetOutput();
  DS_CHECK(FieldValue(warm, "WarmStart") == 1 && FieldValue(warm, "CrossingPairs") == 0 &&
      warm->GetCellData()->GetArray("ObjectId"),
    "a warm start keeps the objects (ObjectId, no crossing)");
  // Two clicks closer than their seed spheres: the starts cross, an error and no surface.
  vtkNew<vtkDeformableSurfaceFilter> crossing;
  crossing->SetInputData(0, s.Phantom.Image);
  Point3 near = s.Clicks[0];
  near[0] += 4.0;
  crossing->SetInitialSurfaceData(SeedObjects(LabelledPoints({ s.Clicks[0], near }, { 1, 2 })));
  vtkNew<dsseedtest::MessageCounter> messages;
  crossing->AddObserver(vtkCommand::ErrorEvent, messages);
  crossing->Update();
  DS_CHECK(messages->Errors == 1 && crossing->GetOutput()->GetNumberOfPoints() == 0,
    "crossing starts: an error and an empty output");
}

void OneObjectUnchanged()
{
  // A click with ObjectId 7 is the same solve as the click without it.
  const ObjectPhantom p = HornedPhantom();
  const SeveralResult with = RunSeveral(p.Image, SeedObjects(LabelledPoints({ p.Click }, { 7 })));
  const SeveralResult without = RunSeveral(p.Image, SeedFromClick(p.Click, 5.0));
  bool same = with.Surface->GetNumberOfPoints() == without.Surface->GetNumberOfPoints() &&
    with.Surface->GetNumberOfPoints() > 0;
  for (vtkIdType i = 0; same && i < with.Surface->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    with.Surface->GetPoint(i, a);
    without.Surface->GetPoint(i, b);
    same = a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
  }
  DS_CHECK(same, "one object with an ObjectId: the same surface as without");
  vtkDataArray* pointIds = with.Surface->GetPointData()->GetArray("ObjectId");
  DS_CHECK(pointIds && pointIds->GetRange()[0] == 7 && pointIds->GetRange()[1] == 7,
    "every point carries the object's id");
  DS_CHECK(!without.Surface->GetPointData()->GetArray("ObjectId"),
    "no ObjectId array without one on the start");
}

void SeedGroups()
{
  // Two tetrahedra's corners, ObjectIds 5 and 3: two hulls, cells labelled, TetraIds on.
  const std::vector<Point3> points = { { 0, 0, 0 }, { 10, 0, 0 }, { 0, 10, 0 }, { 0, 0, 10 },
    { 30, 0, 0 }, { 40, 0, 0 }, { 30, 10, 0 }, { 30, 0, 10 } };
  const std::vector<int> ids = { 5, 5, 5, 5, 3, 3, 3, 3 };
  vtkNew<vtkDelaunaySeedSurface> seed;
  seed->SetInputData(LabelledPoints(points, ids));
  seed->Update();
  vtkPolyData* surface = seed->GetOutput();
  vtkDataArray* cellIds = surface->GetCellData()->GetArray("ObjectId");
  DS_CHECK(surface->GetNumberOfPolys() == 8 && cellIds, "two tetrahedra's surfaces, labelled");
  vtkUnstructuredGrid* tets = seed->GetTetrahedra();
  vtkDataArray* tetraIds = tets->GetCellData()->GetArray("TetraId");
  vtkDataArray* tetObjects = tets->GetCellData()->GetArray("ObjectId");
  DS_CHECK(tets->GetNumberOfCells() == 2 && tetraIds && tetObjects && tetraIds->GetTuple1(0) == 0 &&
      tetraIds->GetTuple1(1) == 1 && tetObjects->GetTuple1(0) == 3 && tetObjects->GetTuple1(1) == 5,
    "TetraIds 0 and 1, ascending ObjectId first");
  for (vtkIdType c = 0; cellIds && c < surface->GetNumberOfCells(); ++c)
  {
    double x[3];
    surface->GetPoint(surface->GetCell(c)->GetPointId(0), x);
    DS_CHECK(cellIds->GetTuple1(c) == (x[0] >= 30 ? 3 : 5), "each cell carries its group's id");
  }
  // Removing the second group's tetrahedron by its TetraId (1) leaves that group no seed.
  seed->AddRemovedTetrahedron(1);
  vtkNew<dsseedtest::MessageCounter> messages;
  seed->AddObserver(vtkCommand::ErrorEvent, messages);
  seed->AddObserver(vtkCommand::WarningEvent, messages);
  seed->Update();
  DS_CHECK(seed->GetOutput()->GetNumberOfCells() == 0 && messages->Errors > 0,
    "a group without a seed: an error and an empty output");
}
} // namespace

int TestSeveralObjects(int, char*[])
{
  SeedGroups();
  OneObjectUnchanged();
  Assembly();
  GivenRanges();
  WarmStartAndCrossingStarts();
  return dstest::Result("TestSeveralObjects");
}

int main(int argc, char* argv[])
{
  return TestSeveralObjects(argc, argv);
}
