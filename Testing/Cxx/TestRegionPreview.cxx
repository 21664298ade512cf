// SPDX-License-Identifier: BSD-3-Clause
// PreviewRegion (docs/METHOD.md §9.3): what the region force will grow through, before the solve.
// - Spine phantom, one click in the middle vertebra: the preview's range is the one the solve
//   uses (the same estimate), the region holds the click's body and reaches neither neighbour;
//   with a range that takes in the discs (60 to 3000 HU) the leak into both neighbours shows.
// - Assembly phantom, a click with an ObjectId in each block: one region per object, labelled,
//   each within its own block plus the glue line it shares.
// - Bad input: no region force (RegionWeight 0) gives an empty surface with PreviewVoxels 0.
#include "DSTestHelpers.h"
#include "OneClick.h"
#include "SeveralObjects.h"

#include <iostream>

using namespace dsobjects;

namespace
{
struct Preview
{
  vtkSmartPointer<vtkPolyData> Surface;
  std::vector<unsigned char> Inside;
};

Preview RunPreview(
  vtkImageData* image, vtkPolyData* seed, double lo = 0, double hi = 0, double regionWeight = -1)
{
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceData(seed);
  filter->SetPreviewRegion(true);
  if (lo < hi)
    filter->SetIntensityRange(lo, hi);
  if (regionWeight >= 0)
    filter->SetRegionWeight(regionWeight);
  filter->Update();
  Preview p;
  p.Surface = vtkSmartPointer<vtkPolyData>::New();
  p.Surface->ShallowCopy(filter->GetOutput());
  p.Inside = SurfaceInterior(p.Surface, image);
  return p;
}

/// Voxels of `inside` whose label is `label`.
long long WithLabel(const std::vector<unsigned char>& inside, vtkImageData* labels, int label)
{
  vtkDataArray* a = labels->GetPointData()->GetScalars();
  long long n = 0;
  for (vtkIdType v = 0; v < a->GetNumberOfTuples(); ++v)
    n += inside[v] && a->GetTuple1(v) == label ? 1 : 0;
  return n;
}

void Spine()
{
  const ObjectPhantom p = SpinePhantom();
  vtkSmartPointer<vtkPolyData> seed = SeedFromClick(p.Click, 5.0);
  const Preview preview = RunPreview(p.Image, seed);
  const ClickResult solved = RunOneClick(p.Image, p.Click, ClickSettings());
  vtkDataArray* range = preview.Surface->GetFieldData()->GetArray("IntensityRange");
  DS_CHECK(range && solved.HasRange && range->GetComponent(0, 0) == solved.UsedRange[0] &&
      range->GetComponent(0, 1) == solved.UsedRange[1],
    "the preview's range is the solve's");
  const long long own = WithLabel(preview.Inside, p.Label, spine::Middle);
  const long long below = WithLabel(preview.Inside, p.Label, spine::Middle - 1);
  const long long above = WithLabel(preview.Inside, p.Label, spine::Middle + 1);
  std::cout << "spine, the estimated range " << (range ? range->GetComponent(0, 0) : 0) << " "
            << (range ? range->GetComponent(0, 1) : 0) << ": " << own << " voxels of the vertebra, "
            << below << " and " << above << " of its neighbours" << std::endl;
  DS_CHECK(own > 0 && below == 0 && above == 0, "the click's vertebra, neither neighbour");
  const Preview wide = RunPreview(p.Image, seed, 60, 3000);
  const long long leakBelow = WithLabel(wide.Inside, p.Label, spine::Middle - 1);
  const long long leakAbove = WithLabel(wide.Inside, p.Label, spine::Middle + 1);
  std::cout << "spine, IntensityRange 60 3000: " << leakBelow << " and " << leakAbove
            << " voxels of the neighbours" << std::endl;
  DS_CHECK(leakBelow > 0 && leakAbove > 0, "a range taking in the discs shows the leak");
}

void Assembly()
{
  const SeveralPhantom s = AssemblyPhantom();
  const Preview preview =
    RunPreview(s.Phantom.Image, SeedObjects(LabelledPoints(s.Clicks, { 1, 2 })));
  vtkDataArray* ids = preview.Surface->GetCellData()->GetArray("ObjectId");
  vtkDataArray* voxels = preview.Surface->GetFieldData()->GetArray("PreviewVoxels");
  DS_CHECK(ids && ids->GetRange()[0] == 1 && ids->GetRange()[1] == 2, "both objects, labelled");
  DS_CHECK(voxels && voxels->GetNumberOfTuples() == 2 && voxels->GetTuple1(0) > 0 &&
      voxels->GetTuple1(1) > 0,
    "voxels per object");
  for (int id : { 1, 2 })
  {
    std::vector<unsigned char> inside =
      SurfaceInterior(ObjectPart(preview.Surface, id), s.Phantom.Image);
    const long long own = WithLabel(inside, s.Phantom.Label, id);
    const long long other = WithLabel(inside, s.Phantom.Label, 3 - id);
    std::cout << "assembly, object " << id << ": " << own << " voxels of its block, " << other
              << " of the other" << std::endl;
    DS_CHECK(own > 0 && other == 0, "each region in its own block");
  }
}

void Off()
{
  const ObjectPhantom p = SpinePhantom();
  const Preview preview = RunPreview(p.Image, SeedFromClick(p.Click, 5.0), 0, 0, 0.0);
  vtkDataArray* voxels = preview.Surface->GetFieldData()->GetArray("PreviewVoxels");
  DS_CHECK(preview.Surface->GetNumberOfCells() == 0 && voxels && voxels->GetNumberOfTuples() == 0,
    "no region force: nothing to preview");
}
} // namespace

int TestRegionPreview(int, char*[])
{
  Spine();
  Assembly();
  Off();
  return dstest::Result("TestRegionPreview");
}

int main(int argc, char* argv[])
{
  return TestRegionPreview(argc, argv);
}
