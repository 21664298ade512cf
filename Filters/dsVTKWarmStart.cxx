// SPDX-License-Identifier: BSD-3-Clause
#include "dsVTKWarmStart.h"

#include "dsVTKObjects.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

namespace dsurf
{
vtkPolyData* WarmStart::StartFor(vtkImageData* image, vtkPolyData* surface) const
{
  const bool same = this->LastImage == image && this->LastImageTime == image->GetMTime() &&
    this->LastSurface == surface && this->LastSurfaceTime == surface->GetMTime();
  return this->ContinueFromLastResult && this->LastResult && same ? this->LastResult.Get()
                                                                  : nullptr;
}

void WarmStart::Keep(vtkImageData* image, vtkPolyData* surface, vtkPolyData* output)
{
  if (!this->ContinueFromLastResult)
  {
    return;
  }
  // Points and triangles only (with AnimateSweeps the output becomes a time step), and each
  // triangle's ObjectId when there are several objects (docs/METHOD.md §9.9).
  vtkNew<vtkPolyData> shape;
  shape->SetPoints(output->GetPoints());
  shape->SetPolys(output->GetPolys());
  CopyPolygonObjectIds(output, shape);
  this->LastResult = vtkSmartPointer<vtkPolyData>::New();
  this->LastResult->DeepCopy(shape);
  this->LastImage = image;
  this->LastImageTime = image->GetMTime();
  this->LastSurface = surface;
  this->LastSurfaceTime = surface->GetMTime();
}
} // namespace dsurf
