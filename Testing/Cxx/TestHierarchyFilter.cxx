// SPDX-License-Identifier: BSD-3-Clause
// vtkDeformableSurfaceFilter runs the whole hierarchy with its defaults: from ParaView's
// Box (vtkCubeSource, 24 points, faces separate) enclosing a 128^3 volume onto a
// sphere of radius 32. Checks the output arrays RefinementLevel and VertexLabel, the
// convergence table's Level and Sigma columns (sigma halves per level), the accuracy,
// and UniformRefinement / HierarchicalSigma through the filter.
#include "DSSurfaceInvariants.h"
#include "HierarchyPhantoms.h"

#include "vtkAbstractArray.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDeformableSurfaceFilter.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkTable.h"
#include "vtkVariant.h"

int TestHierarchyFilter(int, char*[])
{
  const int n = 128;
  const std::vector<float> sphere = dsphantom::Sphere(n, 32.0);
  vtkNew<vtkImageData> image;
  image->SetDimensions(n, n, n);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(static_cast<vtkIdType>(sphere.size()));
  std::copy(sphere.begin(), sphere.end(), values->GetPointer(0));
  image->GetPointData()->SetScalars(values);

  vtkNew<vtkCubeSource> box;
  box->SetBounds(0.5, n - 1.5, 0.5, n - 1.5, 0.5, n - 1.5);

  for (int uniform = 0; uniform < 2; ++uniform)
  {
    vtkNew<vtkDeformableSurfaceFilter> filter;
    filter->SetInputData(0, image);
    filter->SetInitialSurfaceConnection(box->GetOutputPort());
    filter->SetUniformRefinement(uniform != 0);
    // Four refinements (the cap; sigma's floor would need six here): uniform refinement to the
    // floor would split the box 4^6 times.
    filter->SetMaxLevels(4);
    filter->SetCheckTopology(true);
    const std::string name = uniform ? "uniform" : "adaptive";
    dstest::UpdateAndCheckSurface(filter, name);
    vtkPolyData* out = filter->GetOutput();
    vtkTable* table = filter->GetConvergenceTable();
    DS_CHECK(out->GetNumberOfCells() > 0, name + ": a surface came out");
    vtkDataArray* level = out->GetPointData()->GetArray("RefinementLevel");
    vtkDataArray* label = out->GetPointData()->GetArray("VertexLabel");
    DS_CHECK(level && label, name + ": RefinementLevel and VertexLabel arrays");
    if (!level || !label || out->GetNumberOfPoints() == 0)
    {
      continue;
    }
    double range[2];
    level->GetRange(range);
    DS_CHECK(range[0] == 0 && range[1] == 4, name + ": levels 0..4 present");
    label->GetRange(range);
    DS_CHECK(uniform ? range[1] == 0 : range[1] >= 2,
      name + ": labels (all N when uniform, M/D when adaptive)");
    const int levels = static_cast<int>(out->GetFieldData()->GetArray("Levels")->GetTuple1(0));
    DS_CHECK(levels == 5, name + ": five levels solved");
    vtkAbstractArray* reason = out->GetFieldData()->GetAbstractArray("StopReason");
    DS_CHECK(reason && reason->GetVariantValue(0).ToString() == "MaxLevels",
      name + ": StopReason MaxLevels (the cap came before sigma's floor)");
    // Sigma per sweep halves from level to level.
    vtkDataArray* lv = vtkDataArray::SafeDownCast(table->GetColumnByName("Level"));
    vtkDataArray* sg = vtkDataArray::SafeDownCast(table->GetColumnByName("Sigma"));
    bool halves = lv && sg && table->GetNumberOfRows() > 0;
    for (vtkIdType r = 1; halves && r < table->GetNumberOfRows(); ++r)
    {
      const int dl = static_cast<int>(lv->GetTuple1(r) - lv->GetTuple1(r - 1));
      halves = std::abs(sg->GetTuple1(r) - sg->GetTuple1(r - 1) * std::pow(0.5, dl)) < 1e-9;
    }
    DS_CHECK(halves, name + ": sigma halves per level in the convergence table");
    double sum = 0, maxD = 0;
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      double p[3];
      out->GetPoint(i, p);
      const double d = dsphantom::SphereDistance({ p[0], p[1], p[2] }, n, 32.0);
      sum += d;
      maxD = std::max(maxD, d);
    }
    std::cout << "  " << name << ": " << out->GetNumberOfCells() << " triangles, "
              << table->GetNumberOfRows() << " sweeps" << std::endl;
    DS_CHECK_LE(sum / out->GetNumberOfPoints(), 0.15, name + ": mean |distance| (voxels)");
    DS_CHECK_LE(maxD, 0.5, name + ": max |distance| (voxels)");
    DS_CHECK_LE(out->GetFieldData()->GetArray("SelfIntersections")->GetTuple1(0), 0,
      name + ": self-intersections");
  }

  // A start finer than the voxels (ParaView's Sphere, radius 30, 320 x 320: edges <= 0.85
  // voxel) is not refined further -- the image has no detail for smaller triangles -- but
  // sigma still halves level by level down to its floor (2 -> 1 -> 2/3: three levels),
  // so the surface ends on the fine-scale boundary, not on the blurred one of sigma 2.
  {
    vtkNew<vtkSphereSource> fine;
    fine->SetCenter(0.5 * (n - 1), 0.5 * (n - 1), 0.5 * (n - 1));
    fine->SetRadius(30.0);
    fine->SetThetaResolution(320);
    fine->SetPhiResolution(320);
    vtkNew<vtkDeformableSurfaceFilter> filter;
    filter->SetInputData(0, image);
    filter->SetInitialSurfaceConnection(fine->GetOutputPort());
    filter->SetSigma(2.0);
    dstest::UpdateAndCheckSurface(filter, "fine start");
    vtkPolyData* out = filter->GetOutput();
    const int levels = static_cast<int>(out->GetFieldData()->GetArray("Levels")->GetTuple1(0));
    const double finalSigma = out->GetFieldData()->GetArray("Sigma")->GetTuple1(0);
    fine->Update();
    double sum = 0;
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      double p[3];
      out->GetPoint(i, p);
      sum += dsphantom::SphereDistance({ p[0], p[1], p[2] }, n, 32.0);
    }
    std::cout << "  fine start: " << fine->GetOutput()->GetNumberOfPoints() << " input points -> "
              << out->GetNumberOfPoints() << " output points, " << levels
              << " level(s), final sigma " << finalSigma << std::endl;
    DS_CHECK(levels == 3 && std::abs(finalSigma - 2.0 / 3.0) < 1e-12,
      "sigma halves to its floor, 2/3 voxel: three levels");
    DS_CHECK_LE(out->GetNumberOfPoints(), fine->GetOutput()->GetNumberOfPoints(),
      "output points of a sub-voxel start (not refined: at most the input's)");
    DS_CHECK_LE(sum / out->GetNumberOfPoints(), 0.15, "fine start: mean |distance| (voxels)");
  }
  return dstest::Result("TestHierarchyFilter");
}

int main(int argc, char* argv[])
{
  return TestHierarchyFilter(argc, argv);
}
