// SPDX-License-Identifier: BSD-3-Clause
// The objects of a run that solves several at once (docs/METHOD.md §9.9). Plain C++.
#ifndef dsObjects_h
#define dsObjects_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTriangleMesh.h"

#include <string>
#include <vector>

namespace dsurf
{
/// The triangles of object `object` of `mesh` (mesh.Objects per point) as a mesh of their own,
/// its points renumbered in their order, topology built. Empty when the object has none.
DEFORMABLESURFACEFILTERS_EXPORT TriangleMesh ObjectSurface(const TriangleMesh& mesh, int object);

/// The signed volume each object of `mesh` encloses (mesh.Objects per point; one object without
/// them), as TriangleMesh::SignedVolume sums it: positive for outward normals.
DEFORMABLESURFACEFILTERS_EXPORT std::vector<double> ObjectVolumes(const TriangleMesh& mesh);

/// The most objects one run solves: each is extracted, probed for its sigma_0 and its range
/// and contoured on its own, so the work grows with objects x triangles.
constexpr int MaxObjects = 256;

/// mesh.Objects from one label per triangle: the labels' distinct values, ascending, become
/// objects 0, 1, ... (`ids` receives the values). A point's object is its triangles'; false
/// (with a message) when a point's triangles carry different labels, i.e. two objects share a
/// point, or with more than MaxObjects labels. Topology needed.
DEFORMABLESURFACEFILTERS_EXPORT bool AssignObjects(TriangleMesh& mesh,
  const std::vector<long long>& triangleLabels, std::vector<long long>& ids, std::string* error);
} // namespace dsurf

#endif
