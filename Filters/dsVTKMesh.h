// SPDX-License-Identifier: BSD-3-Clause
// The core's triangle mesh as vtkPolyData, for the filter's output, its time steps and the
// coarse copy of a huge start.
#ifndef dsVTKMesh_h
#define dsVTKMesh_h

class vtkPolyData;

namespace dsurf
{
struct TriangleMesh;

/// The mesh's points (double) and triangles into `output` (nothing else).
void SetPolyDataGeometry(const TriangleMesh& mesh, vtkPolyData* output);
} // namespace dsurf

#endif
