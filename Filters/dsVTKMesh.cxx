// SPDX-License-Identifier: BSD-3-Clause
#include "dsVTKMesh.h"

#include "dsTriangleMesh.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

namespace dsurf
{
void SetPolyDataGeometry(const TriangleMesh& mesh, vtkPolyData* output)
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
} // namespace dsurf
