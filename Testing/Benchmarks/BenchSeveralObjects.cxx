// SPDX-License-Identifier: BSD-3-Clause
// Several objects in one run (docs/METHOD.md §9.9): clicks (and picks) with an ObjectId ->
// vtkDelaunaySeedSurface -> vtkDeformableSurfaceFilter, every default, beside what a user gets
// today without the ObjectId (the same seeds solved as one object). Each object is scored
// (ObjectScore.h) against a reference used only to score:
//   spine     ObjectPhantoms.h's spine, a click in each of vertebrae 2, 3 and 4; their labels
//   assembly  SeveralObjectPhantoms.h: two blocks joined by a darker glue line, a click in each
//   engine    SeveralObjectPhantoms.h: the block from 40 picks with the tetrahedra in its bores
//             removed (genus 2), a click in each piston
//   one       ObjectPhantoms.h's horned phantom, one click with an ObjectId and without, three
//             runs of each interleaved: the time of one object (the goal: within 20 %)
//   nuclei    Colin27 (mricron-data ch2.nii.gz), the four clicks of
//             Examples/colin27_nuclei_clicks.csv (caudates and putamina); AAL (aal.nii.gz)
//             labels 71-74 without their voxels darker than 60 in ch2 (CSF)
//   ranges    (only when named) the nuclei run again with the putamina's range typed, over a
//             grid of ranges: how close any one range brings them to their AAL labels
//
//   BenchSeveralObjects [CASE ...]    (CASE: a part of a case's name; none: every case)
#include "../Cxx/ObjectPhantoms.h"
#include "../Cxx/SeveralObjects.h"
#include "BenchCases.h"

#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace dsobjects;

namespace
{
#ifndef DS_EXAMPLES_DIR
#define DS_EXAMPLES_DIR "Examples"
#endif

/// A case: the phantom (image and labels), the seed's points with their ObjectIds, the
/// tetrahedra removed, the label of each ObjectId, and which voxels of a label count.
struct Case
{
  std::string Name;
  SeveralPhantom Phantom;
  std::vector<Point3> Points;
  std::vector<int> Ids;
  std::vector<vtkIdType> Removed;
  std::function<bool(double, vtkIdType)> Keep;
  const char* Unit = "voxels";
};

std::vector<int> Distinct(std::vector<int> ids)
{
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

void Row(const std::string& name, const std::string& method, int id, const ObjectScore& s,
  double scale, const std::string& time, double crossing)
{
  std::printf("| %s | %s | %d | %s | %lld | %.2f / %.2f | %.2f / %.2f | %.3f | %.2f | %.0f |\n",
    name.c_str(), method.c_str(), id, time.c_str(), s.Vertices, s.SurfaceMean / scale,
    s.SurfaceP95 / scale, s.ReferenceMean / scale, s.ReferenceP95 / scale, s.Dice, s.VolumeRatio,
    crossing);
  std::fflush(stdout);
}

void Run(const Case& c)
{
  const double voxel = std::string(c.Unit) == "mm" ? 1.0 : c.Phantom.Phantom.Image->GetSpacing()[0];
  const std::vector<int> objects = Distinct(c.Ids);
  vtkSmartPointer<vtkPolyData> points = LabelledPoints(c.Points, c.Ids);
  const SeveralResult ours = RunSeveral(c.Phantom.Phantom.Image, SeedObjects(points, c.Removed));
  std::vector<std::vector<unsigned char>> interiors(objects.size());
  for (size_t i = 0; i < objects.size(); ++i)
  {
    const int label = c.Phantom.Labels[i];
    const ObjectScore s = ScoreObject(
      ObjectPart(ours.Surface, objects[i]), c.Phantom.Phantom, label, interiors[i], c.Keep);
    char time[64];
    std::snprintf(time, sizeof time, "%.2f", ours.Seconds);
    Row(c.Name, "ObjectId", objects[i], s, voxel, i == 0 ? time : "",
      i == 0 ? FieldValue(ours.Surface, "CrossingPairs") : -1);
  }
  std::printf("| %s | ObjectId: voxels inside two objects %lld, self-intersecting pairs %.0f | | | "
              "| | | | | |\n",
    c.Name.c_str(), OverlapVoxels(interiors), FieldValue(ours.Surface, "SelfIntersections"));
  // Today without ObjectId: the same seeds, one object (the seed's cells unlabelled).
  vtkSmartPointer<vtkPolyData> seed = SeedObjects(points, c.Removed);
  seed->GetCellData()->RemoveArray("ObjectId");
  const SeveralResult one = RunSeveral(c.Phantom.Phantom.Image, seed);
  std::printf("| %s | one object (no ObjectId) | all | %.2f | %lld | | | | | self-intersecting "
              "pairs %.0f |\n",
    c.Name.c_str(), one.Seconds, static_cast<long long>(one.Surface->GetNumberOfPoints()),
    FieldValue(one.Surface, "SelfIntersections"));
}

/// A case of one click per object (the phantom's clicks, its labels as ObjectIds).
Case Clicks(const std::string& name, const SeveralPhantom& phantom)
{
  Case c;
  c.Name = name;
  c.Phantom = phantom;
  c.Points = c.Phantom.Clicks;
  c.Ids = c.Phantom.Labels;
  return c;
}

Case Engine()
{
  Case c;
  c.Name = "engine";
  c.Phantom = EnginePhantom();
  c.Points = EngineBlockPicks();
  c.Ids.assign(c.Points.size(), 1);
  for (int p = 1; p <= 2; ++p)
  {
    c.Points.push_back(c.Phantom.Clicks[p]);
    c.Ids.push_back(1 + p);
  }
  c.Removed = TetrahedraInBores(LabelledPoints(c.Points, c.Ids));
  return c;
}

bool Nuclei(Case& c)
{
  const std::string& templates = MricronTemplates();
  c.Name = "nuclei";
  c.Unit = "mm";
  c.Phantom.Phantom.Image = ReadNifti(templates + "ch2.nii.gz");
  c.Phantom.Phantom.Label = ReadNifti(templates + "aal.nii.gz");
  if (c.Phantom.Phantom.Image->GetNumberOfPoints() == 0 ||
    !SameGrid(c.Phantom.Phantom.Image, c.Phantom.Phantom.Label))
    return false;
  c.Points = ReadClicks(DS_EXAMPLES_DIR "/colin27_nuclei_clicks.csv", &c.Ids);
  c.Phantom.Labels = Distinct(c.Ids); // the ObjectIds are the AAL labels
  vtkDataArray* t1 = c.Phantom.Phantom.Image->GetPointData()->GetScalars();
  c.Keep = [t1](double, vtkIdType v) { return NotCSF(t1, v); };
  return true;
}

/// Dice of the connected threshold [lo, hi] from `click` (ThresholdComponent) against `label`'s
/// voxels that count (Case::Keep).
double ThresholdDice(const Case& c, double lo, double hi, const Point3& click, int label)
{
  const ThresholdResult t = ThresholdComponent(c.Phantom.Phantom.Image, lo, hi, click);
  vtkDataArray* labels = c.Phantom.Phantom.Label->GetPointData()->GetScalars();
  long long in = 0, ref = 0, both = 0;
  for (vtkIdType v = 0; v < labels->GetNumberOfTuples(); ++v)
  {
    const double l = labels->GetComponent(v, 0);
    const bool r = l == label && c.Keep(l, v);
    in += t.Inside[v];
    ref += r ? 1 : 0;
    both += r && t.Inside[v] ? 1 : 0;
  }
  return in + ref > 0 ? 2.0 * both / static_cast<double>(in + ref) : 0.0;
}

/// The nuclei with the putamina's range typed (ObjectIntensityRanges, the same for both; the
/// caudates' estimated), over a grid around the putamina's intensities (AAL 73/74 without CSF:
/// 5-95 % 88-112, median 98, in ch2): what the best single range gives.
void PutaminaRanges(const Case& c)
{
  const std::vector<int> objects = Distinct(c.Ids);
  vtkSmartPointer<vtkPolyData> seed = SeedObjects(LabelledPoints(c.Points, c.Ids), c.Removed);
  std::printf("\n| putamina's range | object | vertices | surface -> AAL mean / 95 %% (mm) | "
              "AAL -> surface mean / 95 %% (mm) | Dice | volume ratio | connected threshold: Dice "
              "|\n|---|---|---|---|---|---|---|---|\n");
  for (double lo : { 88.0, 90.0, 92.0, 94.0 })
    for (double hi : { 102.0, 104.0, 106.0, 108.0 })
    {
      const SeveralResult r =
        RunSeveral(c.Phantom.Phantom.Image, seed, { 73.0, lo, hi, 74.0, lo, hi });
      for (std::size_t i = 0; i < objects.size(); ++i)
      {
        if (objects[i] != 73 && objects[i] != 74)
          continue;
        std::vector<unsigned char> interior;
        const ObjectScore s = ScoreObject(ObjectPart(r.Surface, objects[i]), c.Phantom.Phantom,
          c.Phantom.Labels[i], interior, c.Keep);
        std::printf(
          "| [%.0f, %.0f] | %d | %lld | %.2f / %.2f | %.2f / %.2f | %.3f | %.2f | %.3f |\n", lo, hi,
          objects[i], s.Vertices, s.SurfaceMean, s.SurfaceP95, s.ReferenceMean, s.ReferenceP95,
          s.Dice, s.VolumeRatio, ThresholdDice(c, lo, hi, c.Points[i], c.Phantom.Labels[i]));
        std::fflush(stdout);
      }
    }
}

/// One object with an ObjectId against none: the same solve, timed (fastest of three each).
void OneObject()
{
  const ObjectPhantom p = HornedPhantom();
  vtkSmartPointer<vtkPolyData> with = SeedObjects(LabelledPoints({ p.Click }, { 7 }));
  vtkSmartPointer<vtkPolyData> without = SeedObjects(LabelledPoints({ p.Click }, { 7 }));
  without->GetCellData()->RemoveArray("ObjectId");
  double best[2] = { 1e300, 1e300 };
  long long vertices[2] = { 0, 0 };
  for (int run = 0; run < 3; ++run)
    for (int k = 0; k < 2; ++k)
    {
      const SeveralResult r = RunSeveral(p.Image, k == 0 ? with : without);
      best[k] = std::min(best[k], r.Seconds);
      vertices[k] = r.Surface->GetNumberOfPoints();
    }
  std::printf("| one object (horned, one click) | ObjectId 7 / none | 7 | %.3f / %.3f (%.2fx) | "
              "%lld / %lld | | | | | |\n",
    best[0], best[1], best[0] / best[1], vertices[0], vertices[1]);
}

} // namespace

int main(int argc, char* argv[])
{
  const std::vector<std::string> filters(argv + 1, argv + argc);
  std::printf("Several objects in one run, every default; distances in voxels (nuclei: "
              "mm), surface -> its reference and back, mean / 95 %%; goals: 0.5 voxel (nuclei 1.5 "
              "mm), 0 crossing pairs\n");
  std::printf("| case | run | ObjectId | s | vertices | surface -> ref | ref -> surface | Dice | "
              "volume ratio | crossing pairs |\n|---|---|---|---|---|---|---|---|---|---|\n");
  if (Wanted(filters, "spine"))
    Run(Clicks("spine", SpineThreeClicks()));
  if (Wanted(filters, "assembly"))
    Run(Clicks("assembly", AssemblyPhantom()));
  if (Wanted(filters, "engine"))
    Run(Engine());
  if (Wanted(filters, "one"))
    OneObject();
  Case nuclei;
  const bool ranges = std::find(filters.begin(), filters.end(), "ranges") != filters.end();
  if (Wanted(filters, "nuclei") || ranges)
  {
    if (!Nuclei(nuclei))
      std::printf("| nuclei | missing ch2.nii.gz / aal.nii.gz (mricron-data) | | | | | | | | |\n");
    else if (Wanted(filters, "nuclei"))
      Run(nuclei);
    if (ranges && nuclei.Points.size() > 0)
      PutaminaRanges(nuclei);
  }
  return EXIT_SUCCESS;
}
