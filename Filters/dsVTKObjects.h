// SPDX-License-Identifier: BSD-3-Clause
// The ObjectId arrays of several objects solved in one run (docs/METHOD.md §9.9): read from
// the start surface's cells, written to the output's points, cells and field data.
#ifndef dsVTKObjects_h
#define dsVTKObjects_h

#include <string>
#include <vector>

class vtkFieldData;
class vtkPolyData;

namespace dsurf
{
struct ObjectRegion;
struct TriangleMesh;

/// The name of the arrays: a cell array of the start surface, point and cell arrays of the
/// output, and per-object field data.
constexpr const char* ObjectIdArrayName = "ObjectId";

/// The ObjectId of each polygon and strip of `surface` in cell order without its vertices and
/// lines (as vtkTriangleFilter and the mesh see them); empty when it has no such cell array.
/// False (with a message) when the array is not a one-component integer array.
bool ReadObjectIds(vtkPolyData* surface, std::vector<long long>& ids, std::string& error);

/// The polygon and strip part of `from`'s ObjectId array set on `to`'s cells (for a copy of
/// `from` that keeps only its polygons and strips); nothing when `from` has none.
void CopyPolygonObjectIds(vtkPolyData* from, vtkPolyData* to);

/// Point and cell arrays ObjectId on `output` (the mesh's points and triangles in order).
void AddObjectArrays(const TriangleMesh& mesh, vtkPolyData* output);

/// Per object, in the order of mesh.ObjectIds: ObjectIds, ObjectVolumes (enclosed volume),
/// ObjectVertices, ObjectIntensityRanges (two components; 0 0 where its region force was off)
/// and ObjectRegionWeights (the weight it pulled with, ObjectRegion::Weight; 0 where off), and
/// CrossingPairs (triangle pairs of different objects that intersect).
void AddObjectFieldData(const TriangleMesh& mesh, const std::vector<ObjectRegion>& regions,
  int crossingPairs, vtkFieldData* fd);
} // namespace dsurf

#endif
