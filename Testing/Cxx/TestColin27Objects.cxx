// SPDX-License-Identifier: BSD-3-Clause
// Real objects that are not a brain, on Colin27 (mricron-data), as a user runs them; the clicks
// are the committed CSVs of Examples/, chosen on the image; the AAL labels and the brain mask
// only score (ObjectScore.h). docs/RESULTS.md has every number and what was tried.
// - The caudate nuclei, one click each (a 3 mm seed, every default), against AAL 71 / 72
//   without their voxels darker than 60 (CSF).
// - White-matter clicks (the README's click settings: RegionWeight 1, IntensityRange 62 130),
//   the first WhiteMatterClicks of Examples/colin27_wm_clicks.csv, against ch2bet > 0.
// - The caudates and putamina in one run, four clicks with four ObjectIds (every default),
//   against AAL 71-74 without CSF.
// The issues' goals (1.5 mm both ways for the nuclei, every white-matter click within 1.0 mm)
// are not all met: the bounds asserted here are today's results with a margin, so a change
// that loses ground fails; what must hold outright is asserted outright (no surface crosses
// itself or another, no voxel lies in two objects). Not run under the sanitizers (its label is
// not cxx): a few real-sized solves, too slow there.
#include "Colin27Cases.h"
#include "DSTestHelpers.h"
#include "OneClick.h"
#include "SeveralObjects.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#ifndef DS_EXAMPLES_DIR
#define DS_EXAMPLES_DIR "Examples"
#endif

using namespace dsobjects;

namespace
{
/// The first white-matter clicks run: the first is one of the seven that grow around a
/// ventricle and rest as two sheets where they meet (2.52 mm, docs/RESULTS.md).
constexpr int WhiteMatterClicks = 5;

void Print(const std::string& name, const ObjectScore& s)
{
  std::printf("%s: %lld vertices, surface -> reference %.2f / %.2f mm (mean / 95 %%), reference "
              "-> surface %.2f / %.2f mm, Dice %.3f, volume %.2f, self-intersecting pairs %d\n",
    name.c_str(), s.Vertices, s.SurfaceMean, s.SurfaceP95, s.ReferenceMean, s.ReferenceP95, s.Dice,
    s.VolumeRatio, s.SelfIntersections);
}

/// One click in each caudate head: on the head (0.53 / 0.63 mm), short of the body and tail
/// along the ventricle (AAL -> surface 4.11 / 3.30 mm, volume 0.60 / 0.63).
void Caudates(vtkImageData* head, vtkImageData* aal)
{
  ClickSettings settings;
  settings.SeedRadius = 3.0;
  for (const auto& click : ReadClicks(DS_EXAMPLES_DIR "/colin27_caudate_clicks.csv"))
  {
    const int label = click[0] < 0 ? 71 : 72;
    const std::vector<unsigned char> reference = NucleusWithoutCSF(aal, head, label);
    const ClickResult r = RunOneClick(head, click, settings);
    const ObjectScore s = Score(
      r.Surface, SurfaceInterior(r.Surface, head), reference, MaskBoundary(reference, head), head);
    const std::string name = label == 71 ? "left caudate" : "right caudate";
    Print(name, s);
    DS_CHECK(s.SelfIntersections == 0, name + ": no self-intersecting pairs");
    DS_CHECK_LE(s.SurfaceMean, 0.8, name + ": surface -> AAL mean (mm; goal 1.5)");
    DS_CHECK_LE(s.ReferenceMean, 4.6, name + ": AAL -> surface mean (mm; goal 1.5, not met)");
    DS_CHECK_GE(s.Dice, 0.65, name + ": Dice");
    DS_CHECK_GE(s.VolumeRatio, 0.5, name + ": volume ratio (goal 0.85-1.15, not met)");
    DS_CHECK_LE(s.VolumeRatio, 1.15, name + ": volume ratio");
  }
}

/// White-matter clicks with the README's range: none folds (the goal), each near the brain.
void WhiteMatter(vtkImageData* head, vtkImageData* brain)
{
  const std::vector<unsigned char> reference =
    MaskOf(brain, [](double v, vtkIdType) { return v > 0; });
  const vtkSmartPointer<vtkPolyData> boundary = MaskBoundary(reference, head);
  ClickSettings settings;
  settings.RegionWeight = 1.0;
  settings.IntensityRange[0] = 62.0;
  settings.IntensityRange[1] = 130.0;
  std::vector<std::array<double, 3>> clicks = ReadClicks(DS_EXAMPLES_DIR "/colin27_wm_clicks.csv");
  clicks.resize(std::min<std::size_t>(clicks.size(), WhiteMatterClicks));
  DS_CHECK(clicks.size() == WhiteMatterClicks, "white-matter clicks read");
  for (std::size_t k = 0; k < clicks.size(); ++k)
  {
    const ClickResult r = RunOneClick(head, clicks[k], settings);
    // Every 8th point of the mask's boundary (~45 000 of 355 000): the statistics are the same.
    const ObjectScore s =
      Score(r.Surface, SurfaceInterior(r.Surface, head), reference, boundary, head, 8);
    const std::string name = "white-matter click " + std::to_string(k + 1);
    Print(name, s);
    DS_CHECK(s.SelfIntersections == 0, name + ": does not fold");
    // The first grows around a ventricle, a pocket inside the mask (2.52 mm); the others end at
    // 0.68-0.86 mm (the goal, 1.0 mm, is met by 37 of all 50 clicks).
    DS_CHECK_LE(s.SurfaceMean, k == 0 ? 3.0 : 1.0, name + ": surface -> brain mask mean (mm)");
    DS_CHECK_GE(s.Dice, 0.95, name + ": Dice against the brain mask");
  }
}

/// The caudates and putamina in one run: they meet but never cross; the caudates end on their
/// heads (0.62 / 0.78 mm), the putamina 1.7-1.8 mm from labels drawn 2.9-3.2 mm from them.
void Nuclei(vtkImageData* head, vtkImageData* aal)
{
  std::vector<int> ids;
  const std::vector<Point3> clicks = ReadClicks(DS_EXAMPLES_DIR "/colin27_nuclei_clicks.csv", &ids);
  DS_CHECK(clicks.size() == 4, "four nuclei clicks read");
  const SeveralResult run = RunSeveral(head, SeedObjects(LabelledPoints(clicks, ids)));
  DS_CHECK(FieldValue(run.Surface, "CrossingPairs") == 0, "nuclei: no crossing pairs");
  DS_CHECK(FieldValue(run.Surface, "SelfIntersections") == 0, "nuclei: no self-intersections");
  ObjectPhantom phantom;
  phantom.Image = head;
  phantom.Label = aal;
  vtkDataArray* t1 = head->GetPointData()->GetScalars();
  const auto notCSF = [t1](double, vtkIdType v) { return t1->GetComponent(v, 0) >= 60.0; };
  std::vector<std::vector<unsigned char>> interiors(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    const bool caudate = ids[i] == 71 || ids[i] == 72;
    const ObjectScore s =
      ScoreObject(ObjectPart(run.Surface, ids[i]), phantom, ids[i], interiors[i], notCSF);
    const std::string name = "nucleus " + std::to_string(ids[i]);
    Print(name, s);
    DS_CHECK_LE(s.SurfaceMean, caudate ? 1.0 : 2.2, name + ": surface -> AAL mean (mm; goal 1.5)");
    DS_CHECK_LE(s.ReferenceMean, 3.7, name + ": AAL -> surface mean (mm; goal 1.5, not met)");
    DS_CHECK_GE(s.Dice, 0.55, name + ": Dice");
  }
  DS_CHECK(OverlapVoxels(interiors) == 0, "nuclei: no voxel inside two objects");
}
} // namespace

int TestColin27Objects(int, char*[])
{
  const std::string& dir = MricronTemplates();
  const vtkSmartPointer<vtkImageData> head = ReadNifti(dir + "ch2.nii.gz");
  const vtkSmartPointer<vtkImageData> aal = ReadNifti(dir + "aal.nii.gz");
  const vtkSmartPointer<vtkImageData> brain = ReadNifti(dir + "ch2bet.nii.gz");
  const bool ok = head->GetNumberOfPoints() > 0 && SameGrid(head, aal) && SameGrid(head, brain);
  DS_CHECK(ok,
    "Colin27, its AAL labels and brain mask read from " + dir +
      " (mricron-data: scripts/install-deps.sh installs it)");
  if (ok)
  {
    Caudates(head, aal);
    WhiteMatter(head, brain);
    Nuclei(head, aal);
  }
  return dstest::Result("TestColin27Objects");
}

int main(int argc, char* argv[])
{
  return TestColin27Objects(argc, argv);
}
