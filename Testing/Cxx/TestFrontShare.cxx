// SPDX-License-Identifier: BSD-3-Clause
// Front levels per object (docs/METHOD.md §9.3, MultilevelSolver::FrontOf): on the tube and slab
// phantom (SeveralObjectPhantoms.h), two clicks as two objects (ObjectId 1 the ball with its tube
// three voxels wide, 2 the slab cut by the image's faces), every default, as a user runs them.
// - The run has front levels (FrontLevels >= 1): the tube is followed to within a voxel and a
//   half of its end, and not beyond it by more than a voxel; no front is left on the ball and
//   tube (its front share, measured as FrontTriangles measures it, at most FrontShare).
// - The slab runs on beyond its surface (more than FrontShare of its triangles have it beyond
//   them: its front is not followed) and is not spread by the tube's front levels: it encloses
//   at most 2 % more voxels, with at most 25 % more vertices, than the slab clicked alone, which
//   has no front level.
// - A front that grew at each of its last FrontGrowthLevels levels to more than twice its size is
//   no longer followed (FrontGrows), on the fronts measured: a network of thin parts (a click in
//   Colin27's lateral ventricle) grows; the horned phantom's and a capsule's tips do not.
#include "DSTestHelpers.h"
#include "SeveralObjects.h"
#include "dsFrontGrid.h"
#include "dsMultilevel.h"
#include "dsRegion.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"

#include <algorithm>
#include <iostream>

using namespace dsobjects;

namespace
{
/// The farthest vertex of `part` near the tube's axis, beyond the ball's surface (voxels).
double TubeReach(vtkPolyData* part)
{
  double reach = -1e300;
  for (vtkIdType v = 0; v < part->GetNumberOfPoints(); ++v)
  {
    double x[3];
    part->GetPoint(v, x);
    if (tubeslab::TubeAxisDistance({ x[0], x[1], x[2] }) < tubeslab::TubeWidth + 1.0)
      reach = std::max(reach, x[1] - tubeslab::Centre[1] - tubeslab::Radius);
  }
  return reach;
}

/// The share of `part`'s triangles its object (the image in the output's range for `object`)
/// lies beyond: the front as FrontTriangles finds it (dsFrontGrid.h), on the final surface.
double FrontShareOf(vtkPolyData* part, vtkImageData* image, vtkPolyData* output, int object)
{
  double range[2];
  output->GetFieldData()->GetArray("ObjectIntensityRanges")->GetTuple(object - 1, range);
  dsurf::ImageGeometry g;
  image->GetDimensions(g.Dimensions);
  image->GetSpacing(g.Spacing);
  image->GetOrigin(g.Origin);
  const dsurf::ImageView view = dsurf::ImageView::Of(
    vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0), g);
  long long triangles = 0, front = 0;
  std::vector<dsurf::Vec3> points;
  std::vector<double> inObject;
  vtkIdType n;
  const vtkIdType* ids;
  vtkCellArray* polys = part->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(n, ids); ++triangles)
  {
    dsurf::Vec3 c[3];
    for (int k = 0; k < 3; ++k)
      part->GetPoint(ids[k], c[k].data());
    const int divisions = dsurf::FrontGridDivisions(c[0], c[1], c[2], g.MeanSpacing());
    if (divisions == 0)
      continue;
    dsurf::FrontSamplePoints(c[0], c[1], c[2], divisions, g.MeanSpacing(), points);
    inObject.assign(points.size(), 0.0);
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      bool inside = false;
      const double value = dsurf::SampleVolume(view, points[i].data(), &inside);
      inObject[i] = inside && dsurf::RegionSpeed(value, range[0], range[1]) >= dsurf::FrontSpeed;
    }
    front += dsurf::ObjectBeyond(inObject.data(), static_cast<long long>(points.size())) ? 1 : 0;
  }
  return triangles > 0 ? double(front) / triangles : 0.0;
}

long long VoxelsInside(vtkPolyData* surface, vtkImageData* image)
{
  const std::vector<unsigned char> inside = SurfaceInterior(surface, image);
  return std::count(inside.begin(), inside.end(), 1);
}
void FrontGrowth()
{
  using dsurf::FrontGrows;
  // Triangles on the front at each front level, as the runs measured them (docs/METHOD.md §9.3).
  const std::vector<long long> ventricle = { 70, 87, 146, 220, 315, 467, 708 };
  const std::vector<long long> horned = { 38, 23, 26, 26, 24, 30, 30, 27, 25, 25, 32, 30, 28, 28,
    27, 30, 20, 20, 16, 10, 11, 11, 13, 11, 15, 17, 12, 6, 4, 5, 6, 4, 5, 7, 6, 7, 5, 6, 5, 4, 5, 5,
    4, 8, 6, 5, 5, 5, 5, 5, 5, 7, 5 };
  const std::vector<long long> capsule = { 37, 16, 14, 13, 14, 14, 12 };
  int first = -1;
  for (std::size_t n = 1; n <= ventricle.size() && first < 0; ++n)
  {
    first = FrontGrows({ ventricle.begin(), ventricle.begin() + n }) ? static_cast<int>(n) : -1;
  }
  DS_CHECK(first == 4, "a front that branches on: followed for three levels, then not");
  for (const auto* sizes : { &horned, &capsule })
  {
    for (std::size_t n = 1; n <= sizes->size(); ++n)
    {
      DS_CHECK(!FrontGrows({ sizes->begin(), sizes->begin() + n }),
        "a thin part's tip: followed to its end (" + std::to_string(n) + " levels)");
    }
  }
}

} // namespace

int TestFrontShare(int, char*[])
{
  const SeveralPhantom s = TubeSlabPhantom();
  vtkImageData* image = s.Phantom.Image;
  const SeveralResult both = RunSeveral(image, SeedObjects(LabelledPoints(s.Clicks, s.Labels)));
  const SeveralResult alone =
    RunSeveral(image, SeedObjects(LabelledPoints({ s.Clicks[1] }, { s.Labels[1] })));
  vtkSmartPointer<vtkPolyData> tube = ObjectPart(both.Surface, 1);
  vtkSmartPointer<vtkPolyData> slab = ObjectPart(both.Surface, 2);
  const double front = FieldValue(both.Surface, "FrontLevels");
  const double reach = TubeReach(tube);
  const double tubeShare = FrontShareOf(tube, image, both.Surface, 1);
  const double slabShare = FrontShareOf(slab, image, both.Surface, 2);
  const long long slabVoxels = VoxelsInside(slab, image);
  const long long aloneVoxels = VoxelsInside(alone.Surface, image);
  std::cout << "two objects: " << both.Seconds << " s, " << front << " front levels; tube reached "
            << reach << " of " << tubeslab::TubeLength << " voxels, front share " << tubeShare
            << "; slab front share " << slabShare << ", " << slabVoxels << " voxels inside, "
            << slab->GetNumberOfPoints() << " vertices" << std::endl;
  std::cout << "slab alone: " << alone.Seconds << " s, " << FieldValue(alone.Surface, "FrontLevels")
            << " front levels, " << aloneVoxels << " voxels inside, "
            << alone.Surface->GetNumberOfPoints() << " vertices" << std::endl;
  DS_CHECK(front >= 1 && front <= dsurf::MaxFrontLevels, "two objects: FrontLevels counts them");
  DS_CHECK_GE(reach, tubeslab::TubeLength - 1.5, "tube: reach beyond the ball (voxels)");
  DS_CHECK_LE(reach, tubeslab::TubeLength + 1.0, "tube: not beyond its end (voxels)");
  DS_CHECK_LE(tubeShare, dsurf::FrontShare, "tube: share of its triangles on the front");
  DS_CHECK_GE(slabShare, dsurf::FrontShare, "slab: share of its triangles on the front");
  DS_CHECK(FieldValue(alone.Surface, "FrontLevels") == 0, "slab alone: no front level");
  DS_CHECK_LE(double(slabVoxels) / aloneVoxels, 1.02, "slab: voxels inside against alone");
  DS_CHECK_LE(double(slab->GetNumberOfPoints()) / alone.Surface->GetNumberOfPoints(), 1.25,
    "slab: vertices against alone");
  FrontGrowth();
  return dstest::Result("TestFrontShare");
}

int main(int argc, char* argv[])
{
  return TestFrontShare(argc, argv);
}
