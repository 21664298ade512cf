// SPDX-License-Identifier: BSD-3-Clause
// ContinueFromLastResult of vtkDeformableSurfaceFilter, the warm start of the paper's interactive
// tuning: when on, an update after a change of the filter's own parameters (Tau, Gamma, the
// weights, Sigma, the region force, the hierarchy, the Scalars array...) starts from the last
// surface computed while it was on instead of the initial surface; a change of either input (a
// new image or a new start surface) starts over. Serial only: a distributed run always starts
// from the initial surface. Memory: one copy of the last result (points and triangles). A
// warm-started surface depends on the session's history: a saved state reloaded computes it from
// the start.
#ifndef dsVTKWarmStart_h
#define dsVTKWarmStart_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

class vtkImageData;
class vtkPolyData;

namespace dsurf
{
class WarmStart
{
public:
  /// The filter's property of the same name (its one default).
  bool ContinueFromLastResult = false;

  /// The start for a run on these inputs: the last result when it is on and came from them
  /// unchanged, else nullptr (start from the initial surface).
  vtkPolyData* StartFor(vtkImageData* image, vtkPolyData* surface) const;
  /// Keeps a copy of `output`'s points and triangles (when it is on): downstream filters must
  /// not be able to change where the next run starts.
  void Keep(vtkImageData* image, vtkPolyData* surface, vtkPolyData* output);

private:
  vtkSmartPointer<vtkPolyData> LastResult;
  vtkMTimeType LastImageTime = 0, LastSurfaceTime = 0;
  const void* LastImage = nullptr;
  const void* LastSurface = nullptr;
};
} // namespace dsurf

#endif
