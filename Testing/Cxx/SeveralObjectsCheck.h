// SPDX-License-Identifier: BSD-3-Clause
// What a user checks on several objects solved in one run (docs/METHOD.md §9.9), shared by
// TestSeveralObjects and TestSeveralObjectsMeet: each object's surface against its label, no
// pair of objects crossing, no surface through itself, no voxel inside two objects.
#ifndef SeveralObjectsCheck_h
#define SeveralObjectsCheck_h

#include "DSTestHelpers.h"
#include "SeveralObjects.h"

#include <iostream>
#include <string>
#include <vector>

namespace dsobjects
{
/// Scores every object of `result` against its label; checks what the user checks.
inline void CheckObjects(const SeveralPhantom& s, const SeveralResult& result,
  const std::vector<int>& ids, const std::vector<double>& meanGoals, const std::string& name)
{
  vtkPolyData* out = result.Surface;
  std::cout << name << ": " << out->GetNumberOfPoints() << " vertices, " << result.Seconds << " s, "
            << FieldValue(out, "CrossingPairs") << " crossing pairs, "
            << FieldValue(out, "SelfIntersections") << " intersecting pairs" << std::endl;
  DS_CHECK(FieldValue(out, "CrossingPairs") == 0, name + ": no pair of objects crosses");
  DS_CHECK(FieldValue(out, "SelfIntersections") == 0, name + ": no surface intersects itself");
  DS_CHECK(out->GetPointData()->GetArray("ObjectId") && out->GetCellData()->GetArray("ObjectId"),
    name + ": ObjectId per point and per cell");
  std::vector<std::vector<unsigned char>> interiors(ids.size());
  for (size_t i = 0; i < ids.size(); ++i)
  {
    vtkSmartPointer<vtkPolyData> part = ObjectPart(out, ids[i]);
    const ObjectScore sc = ScoreObject(part, s.Phantom, s.Labels[i], interiors[i]);
    const double voxel = s.Phantom.Image->GetSpacing()[0];
    std::cout << "  object " << ids[i] << ": " << sc.Vertices << " vertices; surface -> label "
              << sc.SurfaceMean / voxel << " (95 % " << sc.SurfaceP95 / voxel
              << "), label -> surface " << sc.ReferenceMean / voxel << " (95 % "
              << sc.ReferenceP95 / voxel << ") voxels; Dice " << sc.Dice << ", volume ratio "
              << sc.VolumeRatio << std::endl;
    DS_CHECK_LE(
      sc.SurfaceMean / voxel, meanGoals[i], name + ": surface -> its label, mean (voxels)");
    DS_CHECK_LE(
      sc.ReferenceMean / voxel, meanGoals[i], name + ": its label -> surface, mean (voxels)");
  }
  const long long overlap = OverlapVoxels(interiors);
  std::cout << "  voxels inside two objects: " << overlap << std::endl;
  DS_CHECK(overlap == 0, name + ": no voxel inside two objects");
}

} // namespace dsobjects

#endif
