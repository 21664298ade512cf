// SPDX-License-Identifier: BSD-3-Clause
// Where front levels look beyond a triangle (docs/METHOD.md §9.3, "Front levels: thin parts";
// MultilevelSolver::FrontTriangles): points of a barycentric grid over the triangle, about a
// voxel apart, each looked at FrontLookSteps depths from the triangle out to FrontLookVoxels
// along its normal. A coarse triangle bridges the mouth of a horn narrower than its edges, so
// no vertex need lie in the horn, but a point beyond the triangle does. Plain C++, no pipeline
// types.
#ifndef dsFrontGrid_h
#define dsFrontGrid_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsTriangleMesh.h"

#include <vector>

namespace dsurf
{
/// The divisions per side of triangle (a, b, d)'s grid: its longest edge in voxels (`voxel` the
/// mean spacing), at least 1 and at most FrontGridMax; 0 for a triangle without a normal to look
/// along.
DEFORMABLESURFACEFILTERS_EXPORT int FrontGridDivisions(
  const Vec3& a, const Vec3& b, const Vec3& d, double voxel);

/// The samples of a grid of `divisions` per side: FrontLookSteps at each of its points (none
/// for 0 divisions).
DEFORMABLESURFACEFILTERS_EXPORT long long FrontGridSamples(int divisions);

/// The FrontGridSamples(divisions) sample points of triangle (a, b, d)'s grid (divisions > 0),
/// into `points` (replacing what it held): grid point by grid point, each followed out along the
/// normal Cross(b - a, d - a) from depth 0 to FrontLookVoxels * voxel.
DEFORMABLESURFACEFILTERS_EXPORT void FrontSamplePoints(const Vec3& a, const Vec3& b, const Vec3& d,
  int divisions, double voxel, std::vector<Vec3>& points);

/// Whether the object lies beyond the triangle: from some grid point, every one of its
/// FrontLookSteps samples is in the object (inObject > 0). `inObject` holds the triangle's
/// `samples` in FrontSamplePoints's order.
DEFORMABLESURFACEFILTERS_EXPORT bool ObjectBeyond(const double* inObject, long long samples);
} // namespace dsurf

#endif
