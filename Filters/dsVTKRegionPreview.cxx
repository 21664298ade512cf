// SPDX-License-Identifier: BSD-3-Clause
#include "dsVTKRegionPreview.h"

#include "dsMultilevel.h"
#include "dsRegionPreview.h"
#include "dsVTKObjects.h"

#include "vtkAppendPolyData.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>

namespace dsurf
{
namespace
{
/// The 0.5 iso-surface of the voxels labelled `value`, in world coordinates.
vtkSmartPointer<vtkPolyData> LabelBoundary(
  const std::vector<unsigned short>& labels, const ImageGeometry& g, unsigned short value)
{
  vtkNew<vtkImageData> mask; // index space, padded by a voxel so the surface closes
  mask->SetDimensions(g.Dimensions[0] + 2, g.Dimensions[1] + 2, g.Dimensions[2] + 2);
  mask->SetOrigin(-1, -1, -1);
  vtkNew<vtkUnsignedCharArray> inside;
  inside->SetName("Region");
  inside->SetNumberOfTuples(mask->GetNumberOfPoints());
  inside->FillValue(0);
  const int nx = g.Dimensions[0], ny = g.Dimensions[1];
  for (std::size_t v = 0; v < labels.size(); ++v)
  {
    if (labels[v] == value)
    {
      const long long i = v % nx, j = (v / nx) % ny, k = v / (static_cast<long long>(nx) * ny);
      inside->SetValue(i + 1 + (nx + 2) * (j + 1 + (ny + 2) * (k + 1)), 1);
    }
  }
  mask->GetPointData()->SetScalars(inside);
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(mask);
  contour->SetValue(0, 0.5);
  contour->ComputeNormalsOff();
  contour->ComputeScalarsOff();
  contour->Update();
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->ShallowCopy(contour->GetOutput());
  vtkNew<vtkPoints> world;
  world->SetDataTypeToDouble();
  world->SetNumberOfPoints(surface->GetNumberOfPoints());
  for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
  {
    double ijk[3], x[3];
    surface->GetPoint(p, ijk);
    g.IndexToWorld(ijk, x);
    world->SetPoint(p, x);
  }
  surface->SetPoints(world);
  return surface;
}
} // namespace

bool DeliverRegionPreview(const ImageView& image, TriangleMesh& start,
  const MultilevelParameters& parameters, vtkPolyData* output, std::string& error,
  std::vector<std::string>& warnings)
{
  MultilevelSolver solver;
  solver.SetParameters(parameters);
  if (!solver.EstimateRegions(image, start, &error))
  {
    return false;
  }
  warnings = solver.GetWarnings();
  const std::vector<ObjectRegion>& regions = solver.GetObjectRegions();
  if (std::none_of(regions.begin(), regions.end(), [](const ObjectRegion& r) { return r.On; }))
  {
    warnings.push_back("the region force is off (RegionWeight 0, a start spanning the image or "
                       "an open start without an IntensityRange, or no range found): nothing to "
                       "preview");
  }
  std::vector<long long> counts;
  const std::vector<unsigned short> labels = RegionPreview(image, start, regions, counts);
  vtkNew<vtkAppendPolyData> append;
  for (std::size_t o = 0; o < regions.size(); ++o)
  {
    if (counts[o] == 0)
    {
      continue;
    }
    vtkSmartPointer<vtkPolyData> part =
      LabelBoundary(labels, image.Geometry, static_cast<unsigned short>(o + 1));
    if (!start.ObjectIds.empty())
    {
      vtkNew<vtkIdTypeArray> ids;
      ids->SetName(ObjectIdArrayName);
      ids->SetNumberOfTuples(part->GetNumberOfCells());
      ids->FillValue(static_cast<vtkIdType>(start.ObjectIds[o]));
      part->GetCellData()->AddArray(ids);
    }
    append->AddInputData(part);
  }
  if (append->GetNumberOfInputConnections(0) > 0)
  {
    append->Update();
    output->ShallowCopy(append->GetOutput());
  }
  vtkFieldData* fd = output->GetFieldData();
  vtkNew<vtkIdTypeArray> voxels;
  voxels->SetName("PreviewVoxels");
  for (long long c : counts)
  {
    voxels->InsertNextValue(static_cast<vtkIdType>(c));
  }
  fd->AddArray(voxels);
  for (const ObjectRegion& r : regions)
  {
    if (r.On)
    {
      vtkNew<vtkDoubleArray> range;
      range->SetName("IntensityRange");
      range->SetNumberOfComponents(2);
      range->InsertNextTuple2(r.Low, r.High);
      fd->AddArray(range);
      break;
    }
  }
  if (!start.ObjectIds.empty())
  {
    vtkNew<vtkDoubleArray> ranges;
    ranges->SetName("ObjectIntensityRanges");
    ranges->SetNumberOfComponents(2);
    for (const ObjectRegion& r : regions)
    {
      ranges->InsertNextTuple2(r.On ? r.Low : 0.0, r.On ? r.High : 0.0);
    }
    fd->AddArray(ranges);
  }
  return true;
}
} // namespace dsurf
