// SPDX-License-Identifier: BSD-3-Clause
// One click near its object's face (docs/METHOD.md §9.3): OneClick.h's workflow (a seed sphere
// of the default 5 mm radius around one point, Deformable Surface with every default but
// RegionWeight) at clicks whose seed lies well inside the object, touches its face or crosses
// it, on two phantoms:
//   slab  SeveralObjectPhantoms.h's tube and slab (1 mm voxels), the slab clicked at y 56.3,
//         z 32.3, d voxels beyond its face (x = 48.3 + d)
//   ball  ObjectPhantoms.h's bright ball (120, radius 16, in 70, noise s.d. 4), clicked d
//         voxels inside its surface along +x
// Each row: the range the filter used (field data IntensityRange), InitialSigma, the levels and
// front levels, the vertices at the end of each level (GetConvergenceTable), and the surface
// scored against the object's label (ObjectScore.h: volume ratio, distances both ways in
// voxels, Dice).
//
// sigma_0 from a click is its seed's distance to the nearest edges (docs/METHOD.md §9.1), here
// the object's own face as seen from the seed's far side, so the whole seed lies in that edge's
// basin and the edge force pulls the far side toward the face; a click's first levels drop that
// inward pull where the image says object (METHOD.md §9.3), so at RegionWeight 0.3 (the
// default) every ball click finds the ball. The slab, cut by the image's faces, ends short of
// its volume at 0.3 (0.6-0.9); at RegionWeight 1 every click finds its object.
//
//   BenchNearFace [CASE ...]    (CASE: a part of a case's name; none: every case)
#include "../Cxx/ObjectScore.h"
#include "../Cxx/OneClick.h"
#include "../Cxx/SeveralObjectPhantoms.h"
#include "BenchCases.h"

#include "vtkTable.h"

#include <cstdio>
#include <string>
#include <vector>

using namespace dsobjects;

namespace
{
/// The vertices at the end of each level, from the convergence table (one row per sweep).
std::string LevelVertices(vtkTable* table)
{
  std::string out;
  const vtkIdType rows = table ? table->GetNumberOfRows() : 0;
  for (vtkIdType r = 0; r < rows; ++r)
  {
    const int level = table->GetValueByName(r, "Level").ToInt();
    if (r + 1 == rows || table->GetValueByName(r + 1, "Level").ToInt() != level)
      out +=
        (out.empty() ? "" : " ") + std::to_string(table->GetValueByName(r, "Vertices").ToInt());
  }
  return out;
}

double FieldOf(vtkPolyData* surface, const char* name)
{
  vtkDataArray* a = surface->GetFieldData()->GetArray(name);
  return a && a->GetNumberOfTuples() > 0 ? a->GetTuple1(0) : -1.0;
}

void Row(const std::string& name, const ObjectPhantom& phantom, const Point3& click, double d,
  double weight)
{
  const vtkSmartPointer<vtkPolyData> seed = SeedFromClick(click, 5.0);
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, phantom.Image);
  filter->SetInitialSurfaceData(seed);
  filter->SetRegionWeight(weight);
  filter->Update();
  vtkPolyData* surface = filter->GetOutput();
  const int object = phantom.ObjectLabel;
  const std::vector<unsigned char> reference =
    MaskOf(phantom.Label, [object](double l, vtkIdType) { return l == object; });
  const ObjectScore s = Score(surface, SurfaceInterior(surface, phantom.Image), reference,
    MaskBoundary(reference, phantom.Image), phantom.Image);
  double range[2] = { 0, 0 };
  if (vtkDataArray* a = surface->GetFieldData()->GetArray("IntensityRange"))
    a->GetTuple(0, range);
  std::printf("| %s | %.0f | %.1f | %.1f - %.1f | %.2f | %.0f (%.0f front) | %s | %.3f | %.2f / "
              "%.2f | %.3f |\n",
    name.c_str(), d, weight, range[0], range[1], FieldOf(surface, "InitialSigma"),
    FieldOf(surface, "Levels"), FieldOf(surface, "FrontLevels"),
    LevelVertices(filter->GetConvergenceTable()).c_str(), s.VolumeRatio, s.SurfaceMean,
    s.ReferenceMean, s.Dice);
  std::fflush(stdout);
}
} // namespace

int main(int argc, char* argv[])
{
  const std::vector<std::string> filters(argv + 1, argv + argc);
  std::printf("One click d voxels inside its object's face (the 5 mm seed touches the face at d = "
              "5); distances in voxels, surface -> label boundary / back\n");
  std::printf("| case | d | RegionWeight | IntensityRange | InitialSigma | levels | vertices per "
              "level | volume ratio | mean distance | Dice |\n|---|---|---|---|---|---|---|---|---|"
              "---|\n");
  const std::vector<double> depths = { 10, 7, 6, 5, 4 };
  if (Wanted(filters, "slab"))
  {
    const SeveralPhantom slab = TubeSlabPhantom();
    ObjectPhantom p = slab.Phantom;
    p.ObjectLabel = 2;
    for (double weight : { 0.3, 1.0 })
      for (double d : depths)
        Row("slab", p, { tubeslab::SlabX + d, 56.3, tubeslab::Centre[2] }, d, weight);
  }
  if (Wanted(filters, "ball"))
  {
    for (double weight : { 0.3, 1.0 })
      for (double d : depths)
      {
        const ObjectPhantom p = BrightBall(d);
        Row("ball", p, p.Click, d, weight);
      }
  }
  return 0;
}
