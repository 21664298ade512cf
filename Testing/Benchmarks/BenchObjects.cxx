// SPDX-License-Identifier: BSD-3-Clause
// One click finds a homogeneous object: the README's one-click workflow (a click ->
// vtkDelaunaySeedSurface -> vtkDeformableSurfaceFilter, every default unless said) on objects
// that are not a brain, beside the alternative a user would pick: a connected threshold (the
// voxels in the same range, the 6-connected component holding the click; the range is the one
// the filter used, its output's IntensityRange, or the case's own when the output has none).
// Both are scored the same way (ObjectScore.h) against a reference used only to score:
//   spine         ObjectPhantoms.h's spine, one click in the middle body; the middle body's label
//   horned        ObjectPhantoms.h's horned ventricle, one click in the body; its label
//   caudate-left  Colin27 (mricron-data ch2.nii.gz), the click of Examples/
//   caudate-right   colin27_caudate_clicks.csv in each caudate head, a 3 mm seed sphere; AAL
//                   (aal.nii.gz) label 71 / 72 without its voxels darker than 60 in ch2 (CSF)
//   wm            Colin27, each of the 50 clicks of Examples/colin27_wm_clicks.csv with
//                 IntensityRange 62 130 (the README's click; given its range, a click pulls
//                 with RegionWeight 1); the brain
//                 mask (ch2bet.nii.gz > 0); one row of medians and worst values
//
//   BenchObjects [--wm-clicks N] [--max-sweeps-per-level N] [--verbose] [--write DIR] [CASE ...]
// CASE: a part of a case's name (e.g. `spine`, `caudate`); none: every case. --wm-clicks: the
// first N white-matter clicks only; --max-sweeps-per-level: the filter's MaxSweepsPerLevel for
// every case (docs/METHOD.md §9.7: what a click's first level does with more than the default's
// 2 000); --verbose: a row per white-matter click; --write: each
// surface as DIR/CASE_ours.vtp and DIR/CASE_threshold.vtp, its image as DIR/CASE_image.vti.
#include "../Cxx/ObjectPhantoms.h"
#include "../Cxx/ObjectScore.h"
#include "../Cxx/OneClick.h"
#include "BenchCases.h"

#include "vtkDSNIFTIImageReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

using namespace dsobjects;

namespace
{
#ifndef DS_EXAMPLES_DIR
#define DS_EXAMPLES_DIR "Examples"
#endif
const std::string& Templates = MricronTemplates();

/// One object: its image, reference mask and boundary, the click and how the user runs it.
struct ObjectCase
{
  vtkSmartPointer<vtkImageData> Image;
  std::vector<unsigned char> Reference;
  vtkSmartPointer<vtkPolyData> ReferenceBoundary;
  std::array<double, 3> Click;
  ClickSettings Settings;
  double FallbackRange[2]; ///< the threshold's range when the filter's output gives none
  vtkIdType ReferenceStride = 1;
};

/// --write DIR: where each case's surfaces and image go (NAME_ours.vtp, NAME_threshold.vtp,
/// NAME_image.vti); empty: none.
std::string& WriteDirectory()
{
  static std::string directory;
  return directory;
}

/// --max-sweeps-per-level N: the filter's MaxSweepsPerLevel for every case; 0: its default.
int& MaxSweepsOption()
{
  static int sweeps = 0;
  return sweeps;
}

void Write(vtkPolyData* surface, const std::string& name)
{
  if (WriteDirectory().empty())
    return;
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(surface);
  writer->SetDataModeToBinary(); // inline base64: Debian 12's expat cannot read appended data
  writer->SetFileName((WriteDirectory() + "/" + name + ".vtp").c_str());
  writer->Write();
}

void WriteImage(vtkImageData* image, const std::string& name)
{
  if (WriteDirectory().empty())
    return;
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  writer->SetDataModeToBinary();
  writer->SetFileName((WriteDirectory() + "/" + name + ".vti").c_str());
  writer->Write();
}

struct Pair
{
  ObjectScore Ours, Threshold;
  double Range[2] = { 0, 0 };
};

Pair RunCase(const ObjectCase& c, const std::string& name)
{
  Pair p;
  ClickSettings settings = c.Settings;
  settings.MaxSweepsPerLevel = MaxSweepsOption();
  const ClickResult click = RunOneClick(c.Image, c.Click, settings);
  Write(click.Surface, name + "_ours");
  WriteImage(c.Image, name + "_image");
  p.Ours = Score(click.Surface, SurfaceInterior(click.Surface, c.Image), c.Reference,
    c.ReferenceBoundary, c.Image, c.ReferenceStride);
  p.Ours.Seconds = click.Seconds;
  p.Range[0] = click.HasRange ? click.UsedRange[0] : c.FallbackRange[0];
  p.Range[1] = click.HasRange ? click.UsedRange[1] : c.FallbackRange[1];
  const ThresholdResult t = ThresholdComponent(c.Image, p.Range[0], p.Range[1], c.Click);
  Write(t.Surface, name + "_threshold");
  p.Threshold =
    Score(t.Surface, t.Inside, c.Reference, c.ReferenceBoundary, c.Image, c.ReferenceStride);
  p.Threshold.Seconds = t.Seconds;
  p.Threshold.VerticesOutside = -1; // its voxels are the image's: nothing can lie outside
  return p;
}

void Header()
{
  std::printf("| case | method | s | vertices | surface -> ref mean / 95%% | ref -> surface mean / "
              "95%% | Dice | volume ratio | %% outside | self-int. | vertices outside image | "
              "goal | met |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
}

void Row(const std::string& name, const std::string& method, const ObjectScore& s,
  const std::string& time, const std::string& unit, const std::string& goal, const std::string& met)
{
  char selfInt[32], outside[32];
  std::snprintf(selfInt, sizeof selfInt, "%d", s.SelfIntersections);
  std::snprintf(outside, sizeof outside, "%lld", s.VerticesOutside);
  std::printf("| %s | %s | %s | %lld | %.2f / %.2f %s | %.2f / %.2f %s | %.3f | %.2f | %.1f | %s | "
              "%s | %s | %s |\n",
    name.c_str(), method.c_str(), time.c_str(), s.Vertices, s.SurfaceMean, s.SurfaceP95,
    unit.c_str(), s.ReferenceMean, s.ReferenceP95, unit.c_str(), s.Dice, s.VolumeRatio,
    100.0 * s.OutsideShare, s.SelfIntersections < 0 ? "-" : selfInt,
    s.VerticesOutside < 0 ? "-" : outside, goal.c_str(), met.c_str());
  std::fflush(stdout);
}

std::string Format(const char* format, double a, double b = 0)
{
  char text[128];
  std::snprintf(text, sizeof text, format, a, b);
  return text;
}

/// Our row and the threshold's beside it (its time as a share of ours).
void PrintPair(const std::string& name, const Pair& p, const std::string& unit,
  const std::string& goal, bool met)
{
  Row(name, "one click", p.Ours, Format("%.2f", p.Ours.Seconds), unit, goal, met ? "yes" : "NO");
  Row(name, Format("threshold [%g, %g] + component", p.Range[0], p.Range[1]), p.Threshold,
    Format("%.3f (ours / it: %.0f)", p.Threshold.Seconds,
      p.Ours.Seconds / std::max(1e-6, p.Threshold.Seconds)),
    unit, "", "");
}

ObjectCase PhantomCase(const ObjectPhantom& phantom, double lo, double hi)
{
  ObjectCase c;
  c.Image = phantom.Image;
  const int object = phantom.ObjectLabel;
  c.Reference = MaskOf(phantom.Label, [object](double l, vtkIdType) { return l == object; });
  c.ReferenceBoundary = MaskBoundary(c.Reference, phantom.Image);
  c.Click = phantom.Click;
  c.FallbackRange[0] = lo;
  c.FallbackRange[1] = hi;
  return c;
}

void Spine()
{
  // Fallback range: above the discs and soft tissue (<= 132 HU with partial volume) to bone.
  const Pair p = RunCase(PhantomCase(SpinePhantom(), 150.0, 3000.0), "spine");
  PrintPair("spine", p, "mm", "<= 5 % outside, Dice >= 0.9",
    p.Ours.OutsideShare <= 0.05 && p.Ours.Dice >= 0.9);
}

void Horned()
{
  const Pair p = RunCase(PhantomCase(HornedPhantom(), 0.0, 45.0), "horned");
  PrintPair("horned", p, "vx", "ref -> surface mean <= 0.5, 95 % <= 1.5 vx, 0 self-int.",
    p.Ours.ReferenceMean <= 0.5 && p.Ours.ReferenceP95 <= 1.5 && p.Ours.SelfIntersections == 0);
}

/// The 5, 25, 50, 75 and 95 % quantiles of `t1` over the voxels `in` holds that are not CSF
/// (60 or brighter, as the references), and their count.
std::vector<double> Quantiles(vtkDataArray* t1, const std::function<bool(vtkIdType)>& in)
{
  std::vector<double> values;
  for (vtkIdType v = 0; v < t1->GetNumberOfTuples(); ++v)
  {
    const double value = t1->GetComponent(v, 0);
    if (value >= Colin27CSFBelow && in(v))
      values.push_back(value);
  }
  std::sort(values.begin(), values.end());
  std::vector<double> q;
  for (double share : { 0.05, 0.25, 0.5, 0.75, 0.95 })
    q.push_back(
      values.empty() ? 0.0 : values[static_cast<std::size_t>(share * (values.size() - 1))]);
  q.push_back(static_cast<double>(values.size()));
  return q;
}

/// Why no intensity range gives the caudates: the T1 of the grey matter around them (AAL labels,
/// without CSF) spans the caudates' own values.
void CaudateNeighbours(vtkImageData* head, vtkImageData* aal)
{
  vtkDataArray* t1 = head->GetPointData()->GetScalars();
  vtkDataArray* labels = aal->GetPointData()->GetScalars();
  auto labelIn = [labels](double low, double high)
  {
    return [labels, low, high](vtkIdType v)
    {
      const double l = labels->GetComponent(v, 0);
      return l >= low && l <= high;
    };
  };
  std::printf(
    "\nColin27's T1 (ch2) in AAL labels, voxels of 60 or more: quantiles 5 / 25 / 50 / 75 / "
    "95 %%\n| labels | voxels | T1 |\n|---|---|---|\n");
  const struct
  {
    const char* Name;
    double Low, High;
  } groups[] = { { "caudate, left (71)", 71, 71 }, { "caudate, right (72)", 72, 72 },
    { "putamina (73, 74)", 73, 74 }, { "pallida (75, 76)", 75, 76 }, { "thalami (77, 78)", 77, 78 },
    { "cortex (1-70)", 1, 70 } };
  for (const auto& g : groups)
  {
    const std::vector<double> q = Quantiles(t1, labelIn(g.Low, g.High));
    std::printf("| %s | %.0f | %.0f / %.0f / %.0f / %.0f / %.0f |\n", g.Name, q[5], q[0], q[1],
      q[2], q[3], q[4]);
  }
}

/// Colin27's caudate heads: AAL 71 (left, x < 0 in the template's RAS) and 72 without CSF.
void Caudates(const std::vector<std::string>& filters)
{
  const vtkSmartPointer<vtkImageData> head = ReadNifti(Templates + "ch2.nii.gz");
  const vtkSmartPointer<vtkImageData> aal = ReadNifti(Templates + "aal.nii.gz");
  if (head->GetNumberOfPoints() == 0 || !SameGrid(head, aal))
  {
    std::printf("| caudate | | missing or misaligned ch2.nii.gz / aal.nii.gz (mricron-data) |\n");
    return;
  }
  for (const auto& click : ReadClicks(DS_EXAMPLES_DIR "/colin27_caudate_clicks.csv"))
  {
    const int label = click[0] < 0 ? 71 : 72;
    const std::string name = label == 71 ? "caudate-left" : "caudate-right";
    if (!Wanted(filters, name))
      continue;
    ObjectCase c;
    c.Image = head;
    c.Reference = NucleusWithoutCSF(aal, head, label);
    c.ReferenceBoundary = MaskBoundary(c.Reference, head);
    c.Click = click;
    c.Settings.SeedRadius = CaudateSeedRadius;
    c.FallbackRange[0] = 75.0; // grey matter between CSF and white matter
    c.FallbackRange[1] = 100.0;
    const Pair p = RunCase(c, name);
    PrintPair(name, p, "mm", "mean <= 1.5 mm both ways, volume +-15 %",
      p.Ours.SurfaceMean <= 1.5 && p.Ours.ReferenceMean <= 1.5 &&
        std::abs(p.Ours.VolumeRatio - 1.0) <= 0.15);
  }
  CaudateNeighbours(head, aal);
}

double Median(std::vector<double> v)
{
  if (v.empty())
    return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

/// The white-matter clicks: a row of medians and one of the worst values over the clicks.
void WhiteMatter(int limit, bool verbose)
{
  const vtkSmartPointer<vtkImageData> head = ReadNifti(Templates + "ch2.nii.gz");
  const vtkSmartPointer<vtkImageData> brain = ReadNifti(Templates + "ch2bet.nii.gz");
  if (head->GetNumberOfPoints() == 0 || !SameGrid(head, brain))
  {
    std::printf("| wm | | missing or misaligned ch2.nii.gz / ch2bet.nii.gz (mricron-data) |\n");
    return;
  }
  ObjectCase c;
  c.Image = head;
  c.Reference = MaskOf(brain, [](double v, vtkIdType) { return v > 0; });
  c.ReferenceBoundary = MaskBoundary(c.Reference, head);
  c.ReferenceStride = BrainBoundaryStride;
  c.Settings.IntensityRange[0] = c.FallbackRange[0] = Colin27BrainRange[0];
  c.Settings.IntensityRange[1] = c.FallbackRange[1] = Colin27BrainRange[1];
  std::vector<std::array<double, 3>> clicks = ReadClicks(DS_EXAMPLES_DIR "/colin27_wm_clicks.csv");
  if (limit > 0 && static_cast<int>(clicks.size()) > limit)
    clicks.resize(limit);
  std::vector<Pair> pairs;
  for (size_t k = 0; k < clicks.size(); ++k)
  {
    c.Click = clicks[k];
    pairs.push_back(RunCase(c, Format("wm%.0f", double(k + 1))));
    if (verbose)
      PrintPair(Format("wm %.0f", double(k + 1)) + Format(" (%.1f, %.1f", c.Click[0], c.Click[1]) +
          Format(", %.1f)", c.Click[2]),
        pairs.back(), "mm", "",
        pairs.back().Ours.SelfIntersections == 0 && pairs.back().Ours.SurfaceMean <= 1.0);
  }
  if (pairs.empty())
    return;
  // Medians and worst values, field by field.
  auto summary = [&](const std::function<const ObjectScore&(const Pair&)>& of, bool worst)
  {
    ObjectScore s;
    std::vector<double> f[11];
    for (const Pair& p : pairs)
    {
      const ObjectScore& o = of(p);
      const double v[11] = { o.Seconds, double(o.Vertices), o.SurfaceMean, o.SurfaceP95,
        o.ReferenceMean, o.ReferenceP95, o.Dice, o.VolumeRatio, o.OutsideShare,
        double(o.SelfIntersections), double(o.VerticesOutside) };
      for (int k = 0; k < 11; ++k)
        f[k].push_back(v[k]);
    }
    double r[11];
    for (int k = 0; k < 11; ++k)
    {
      const bool lowIsWorse = k == 6; // Dice
      r[k] = !worst  ? Median(f[k])
        : lowIsWorse ? *std::min_element(f[k].begin(), f[k].end())
                     : *std::max_element(f[k].begin(), f[k].end());
    }
    s.Seconds = r[0];
    s.Vertices = static_cast<long long>(r[1]);
    s.SurfaceMean = r[2];
    s.SurfaceP95 = r[3];
    s.ReferenceMean = r[4];
    s.ReferenceP95 = r[5];
    s.Dice = r[6];
    s.VolumeRatio = r[7];
    s.OutsideShare = r[8];
    s.SelfIntersections = static_cast<int>(r[9]);
    s.VerticesOutside = static_cast<long long>(r[10]);
    return s;
  };
  int folds = 0, far = 0;
  for (const Pair& p : pairs)
  {
    folds += p.Ours.SelfIntersections != 0 ? 1 : 0;
    far += p.Ours.SurfaceMean > 1.0 ? 1 : 0;
  }
  const std::string name = Format("wm, %.0f clicks", double(pairs.size()));
  const std::string met = folds == 0 && far == 0
    ? "yes"
    : Format("NO: %.0f fold, %.0f > 1 mm", double(folds), double(far));
  for (bool worst : { false, true })
  {
    const ObjectScore ours =
      summary([](const Pair& p) -> const ObjectScore& { return p.Ours; }, worst);
    const ObjectScore it =
      summary([](const Pair& p) -> const ObjectScore& { return p.Threshold; }, worst);
    const std::string what = worst ? "worst" : "median";
    Row(name, "one click, " + what, ours, Format("%.2f", ours.Seconds), "mm",
      worst ? "" : "none folds, each <= 1.0 mm mean", worst ? "" : met);
    Row(name, "threshold [62, 130] + component, " + what, it,
      Format("%.3f (ours / it: %.0f)", it.Seconds, ours.Seconds / std::max(1e-6, it.Seconds)), "mm",
      "", "");
  }
}

} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> filters;
  int wmClicks = 0;
  bool verbose = false;
  for (int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    if (arg == "--wm-clicks" && a + 1 < argc)
      wmClicks = std::atoi(argv[++a]);
    else if (arg == "--write" && a + 1 < argc)
      WriteDirectory() = argv[++a];
    else if (arg == "--max-sweeps-per-level" && a + 1 < argc)
      MaxSweepsOption() = std::atoi(argv[++a]);
    else if (arg == "--verbose")
      verbose = true;
    else if (!arg.empty() && arg[0] == '-')
    {
      std::fprintf(stderr,
        "usage: %s [--wm-clicks N] [--max-sweeps-per-level N] [--verbose] [--write DIR] "
        "[CASE ...]\n",
        argv[0]);
      return EXIT_FAILURE;
    }
    else
      filters.push_back(arg);
  }
  std::printf("One click, every default unless said; distances: mm (horned: voxels of "
              "1 mm); threshold: the filter's range, the 6-connected component of the click\n");
  if (MaxSweepsOption() > 0)
    std::printf("Every case with MaxSweepsPerLevel %d (not the default)\n", MaxSweepsOption());
  Header();
  if (Wanted(filters, "spine"))
    Spine();
  if (Wanted(filters, "horned"))
    Horned();
  if (Wanted(filters, "caudate-left") || Wanted(filters, "caudate-right"))
    Caudates(filters);
  if (Wanted(filters, "wm"))
    WhiteMatter(wmClicks, verbose);
  return EXIT_SUCCESS;
}
