// SPDX-License-Identifier: BSD-3-Clause
// The bad-input matrix, one named row per case: what vtkDeformableSurfaceFilter (and, for the
// image cases, vtkImageScaleSpaceGradient) tells the user (the text of the error or warning,
// caught through ErrorEvent/WarningEvent observers) and what it outputs (empty, or a surface
// that keeps the invariants of DSSurfaceInvariants.h), with the inputs bit-identical after the
// run. Rows: images (no scalars, chosen array missing, 3 components, 1-D, 2-D, 1x1x1, empty,
// NaN/Inf voxel, constant, negative or NaN spacing, NaN origin, singular direction, spacing
// 1e-6 and 1e6); start surfaces (empty, vertices/lines, lines only, strips, quads, non-manifold
// fin, NaN coordinate, zero-area and repeated-point triangles, open cap, entirely outside);
// parameters (Abort from a ProgressEvent observer, NaN and +Inf values, every clamp with its
// clamped value and a sane run); vtkImageScaleSpaceGradient's parameters; vtkDelaunaySeedSurface
// from 0-3 points, copies, NaN points, two far clusters and NaN/out-of-range parameters. Cases
// covered elsewhere with other assertions (TestDeformableSurfaceInput, TestImageScalarsChoice,
// TestScaleSpaceBadInput, TestDelaunaySeedBadInput) are repeated here so that every row asserts
// message, output and inputs the same way.
#include "DSSurfaceInvariants.h"
#include "SoftBallImage.h"
#include "TestSolverMeshes.h"

#include "vtkDeformableSurfaceFilter.h"
#include "vtkDelaunaySeedSurface.h"
#include "vtkImageScaleSpaceGradient.h"

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkStripper.h"
#include "vtkTriangleFilter.h"
#include "vtkUnstructuredGrid.h"

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace
{
constexpr int N = 32; // the test image is N^3 voxels
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
constexpr double Inf = std::numeric_limits<double>::infinity();

/// A soft ball of radius 8 voxels around voxel (16, 16, 16), spacing `s`, named "density";
/// with fewer voxels along an axis, the part of it through the centre (the 1-D and 2-D cases).
vtkSmartPointer<vtkImageData> Ball(double s = 1.0, int nx = N, int ny = N, int nz = N)
{
  auto whole = dstest::SoftBallImage(N, 16.0, 8.0);
  whole->SetSpacing(s, s, s);
  if (nx == N && ny == N && nz == N)
  {
    return whole;
  }
  auto part = vtkSmartPointer<vtkImageData>::New();
  part->SetDimensions(nx, ny, nz);
  part->SetSpacing(s, s, s);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
  vtkIdType id = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        values->SetValue(id++,
          whole->GetScalarComponentAsFloat(
            nx == 1 ? 16 : i, ny == 1 ? 16 : j, nz == 1 ? 16 : k, 0));
      }
  part->GetPointData()->SetScalars(values);
  return part;
}

/// A triangulated UV sphere of radius 11 voxels around the ball (scaled by s, centre shifted by
/// dx).
vtkSmartPointer<vtkPolyData> Start(double s = 1.0, double dx = 0.0, double endPhi = 180.0)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter((16.0 + dx) * s, 16.0 * s, 16.0 * s);
  sphere->SetRadius(11.0 * s);
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(16);
  sphere->SetEndPhi(endPhi);
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(sphere->GetOutputPort());
  tri->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(tri->GetOutput());
  return out;
}

/// `poly` with extra cells of another kind sharing its points (vertices, lines).
vtkSmartPointer<vtkPolyData> WithExtraCells(vtkPolyData* poly, bool verts, bool lines)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(poly);
  vtkNew<vtkCellArray> cells;
  for (vtkIdType i = 0; i + 1 < poly->GetNumberOfPoints(); i += 7)
  {
    const vtkIdType ids[2] = { i, i + 1 };
    cells->InsertNextCell(lines ? 2 : 1, ids);
  }
  if (verts)
  {
    out->SetVerts(cells);
  }
  if (lines)
  {
    out->SetLines(cells);
  }
  return out;
}

/// A box of six quads around the ball (as ParaView's Box gives before merging, but shared points).
vtkSmartPointer<vtkPolyData> AsQuads()
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        pts->InsertNextPoint(6.0 + 20.0 * i, 6.0 + 20.0 * j, 6.0 + 20.0 * k);
  vtkNew<vtkCellArray> quads;
  const vtkIdType faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  for (const auto& f : faces)
  {
    quads->InsertNextCell(4, f);
  }
  out->SetPoints(pts);
  out->SetPolys(quads);
  return out;
}

vtkSmartPointer<vtkPolyData> AsStrips()
{
  vtkNew<vtkStripper> stripper;
  stripper->SetInputData(Start());
  stripper->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(stripper->GetOutput());
  return out;
}

/// The start sphere with one more triangle on three points: `degenerate` picks a
/// zero-area triangle (three collinear new points) or one naming the same point twice.
vtkSmartPointer<vtkPolyData> WithDegenerate(bool duplicatePoint)
{
  auto out = Start();
  vtkPoints* pts = out->GetPoints();
  const vtkIdType a = pts->InsertNextPoint(16, 16, 16);
  const vtkIdType b = pts->InsertNextPoint(17, 16, 16);
  const vtkIdType c = pts->InsertNextPoint(18, 16, 16);
  const vtkIdType ids[3] = { a, b, duplicatePoint ? a : c };
  out->GetPolys()->InsertNextCell(3, ids);
  return out;
}

vtkSmartPointer<vtkImageData> Edited(
  vtkSmartPointer<vtkImageData> image, const std::function<void(vtkImageData*)>& edit)
{
  edit(image);
  return image;
}

enum class Output
{
  Empty,  // no points, no cells
  Surface // a surface keeping the invariants
};

struct Row
{
  std::string Name;
  std::function<vtkSmartPointer<vtkImageData>()> Image;
  std::function<vtkSmartPointer<vtkPolyData>()> Surface;
  std::function<void(vtkDeformableSurfaceFilter*)> Configure; // may be empty
  std::string Error;   // a substring of the error; empty: no error allowed
  std::string Warning; // a substring of a warning; empty: no warning allowed
  Output Expect;
  bool Gradient = false;                     // an image case: vtkImageScaleSpaceGradient too
  std::string GradientError = std::string(); // empty: the gradient must succeed
};

void CheckMessages(const dstest::MessageCounter& m, const std::string& error,
  const std::string& warning, const std::string& label)
{
  if (error.empty())
  {
    DS_CHECK(m.Errors == 0, label + ": no error, got: " + m.ErrorText);
  }
  else
  {
    DS_CHECK(m.Errors == 1 && m.ErrorText.find(error) != std::string::npos,
      label + ": one error saying '" + error + "', got: " + m.ErrorText);
  }
  if (warning.empty())
  {
    DS_CHECK(m.Warnings == 0, label + ": no warning, got: " + m.WarningText);
  }
  else
  {
    DS_CHECK(m.WarningText.find(warning) != std::string::npos,
      label + ": a warning saying '" + warning + "', got: " + m.WarningText);
  }
}

void RunGradient(const Row& row, vtkImageData* image)
{
  const std::string label = row.Name + " [gradient]";
  vtkNew<vtkImageScaleSpaceGradient> gradient;
  vtkNew<dstest::MessageCounter> messages;
  messages->Watch(gradient);
  gradient->SetInputData(image);
  gradient->SetSigma(1.5 * image->GetSpacing()[0]);
  gradient->Update();
  CheckMessages(*messages, row.GradientError, "", label);
  vtkImageData* out = gradient->GetOutput();
  vtkDataArray* force = out->GetPointData()->GetArray("Force");
  if (row.GradientError.empty())
  {
    double bad = 0;
    for (vtkIdType i = 0; force && i < force->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < force->GetNumberOfComponents(); ++c)
      {
        bad += std::isfinite(force->GetComponent(i, c)) ? 0 : 1;
      }
    }
    DS_CHECK(force && force->GetNumberOfTuples() == image->GetNumberOfPoints(),
      label + ": a Force per voxel");
    DS_CHECK_LE(bad, 0, label + ": non-finite Force components");
  }
  else
  {
    DS_CHECK(out->GetNumberOfPoints() == 0 && !force, label + ": empty output");
  }
}

void RunRow(const Row& row)
{
  std::cout << "--- " << row.Name << std::endl;
  vtkSmartPointer<vtkImageData> image = row.Image();
  vtkSmartPointer<vtkPolyData> start = row.Surface();
  const dstest::InputGuard guard{ image, start };
  vtkNew<vtkDeformableSurfaceFilter> filter;
  vtkNew<dstest::MessageCounter> messages;
  messages->Watch(filter);
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceData(start);
  filter->SetSigma(1.5 * image->GetSpacing()[0]);
  filter->SetMaxLevels(1);
  filter->SetMaxSweepsPerLevel(150);
  if (row.Configure)
  {
    row.Configure(filter);
  }
  filter->Update();
  CheckMessages(*messages, row.Error, row.Warning, row.Name);
  vtkPolyData* out = filter->GetOutput();
  if (row.Expect == Output::Empty)
  {
    DS_CHECK(
      out->GetNumberOfPoints() == 0 && out->GetNumberOfCells() == 0, row.Name + ": empty output");
  }
  else
  {
    dstest::CheckSurfaceInvariants(start, out, row.Name);
  }
  if (row.Gradient)
  {
    RunGradient(row, image);
  }
  guard.Check(row.Name);
}

/// A progress observer that sets AbortExecute at the first report at or after `fraction`.
void AbortAt(vtkDeformableSurfaceFilter* filter, double fraction)
{
  struct Aborter : public vtkCommand
  {
    static Aborter* New() { return new Aborter; }
    void Execute(vtkObject* caller, unsigned long, void* data) override
    {
      if (*static_cast<double*>(data) >= this->Fraction)
      {
        static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
      }
    }
    double Fraction = 0;
  };
  vtkNew<Aborter> aborter;
  aborter->Fraction = fraction;
  filter->AddObserver(vtkCommand::ProgressEvent, aborter);
}

std::vector<Row> ImageRows()
{
  auto ball = [] { return Ball(); };
  auto start = [] { return Start(); };
  const char* threeD = "A 3-D image is needed";
  return {
    { "no scalars",
      []
      {
        auto i = vtkSmartPointer<vtkImageData>::New();
        i->SetDimensions(N, N, N);
        return i;
      },
      start, nullptr, "no point arrays", "", Output::Empty, true, "no point arrays" },
    { "the chosen array missing, two others",
      []
      {
        auto i = Ball();
        vtkNew<vtkFloatArray> other;
        other->DeepCopy(i->GetPointData()->GetScalars());
        other->SetName("other");
        i->GetPointData()->AddArray(other);
        i->GetPointData()->SetActiveScalars(nullptr);
        return i;
      },
      start,
      [](vtkDeformableSurfaceFilter* f)
      { f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "missing"); },
      "choose one of 'density', 'other'", "", Output::Empty },
    { "the chosen array missing, active scalars used", ball, start,
      [](vtkDeformableSurfaceFilter* f)
      { f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "missing"); },
      "", "", Output::Surface },
    { "3-component scalars",
      []
      {
        auto i = Ball();
        vtkNew<vtkFloatArray> v;
        v->SetName("vectors");
        v->SetNumberOfComponents(3);
        v->SetNumberOfTuples(i->GetNumberOfPoints());
        v->Fill(1.0);
        i->GetPointData()->SetScalars(v);
        return i;
      },
      start, nullptr, "'vectors' has 3 components", "", Output::Empty, true, "3 components" },
    { "1-D image 32x1x1", [] { return Ball(1.0, N, 1, 1); }, start, nullptr, threeD, "",
      Output::Empty, true, "3-D" },
    { "2-D image 32x32x1", [] { return Ball(1.0, N, N, 1); }, start, nullptr, threeD, "",
      Output::Empty, true, "3-D" },
    { "1x1x1 image", [] { return Ball(1.0, 1, 1, 1); }, start, nullptr, threeD, "", Output::Empty,
      true, "3-D" },
    { "empty image", [] { return vtkSmartPointer<vtkImageData>::New(); }, start, nullptr,
      "image is empty", "", Output::Empty, true, "empty" },
    { "a NaN voxel",
      []
      {
        return Edited(
          Ball(), [](vtkImageData* i) { i->GetPointData()->GetScalars()->SetTuple1(777, NaN); });
      },
      start, nullptr, "1 non-finite values", "", Output::Empty, true, "non-finite" },
    { "an Inf voxel",
      []
      {
        return Edited(
          Ball(), [](vtkImageData* i) { i->GetPointData()->GetScalars()->SetTuple1(999, Inf); });
      },
      start, nullptr, "1 non-finite values", "", Output::Empty, true, "non-finite" },
    { "constant image",
      [] {
        return Edited(Ball(), [](vtkImageData* i) { i->GetPointData()->GetScalars()->Fill(3.0); });
      },
      start, nullptr, "The image is constant", "", Output::Empty },
    { "negative spacing",
      [] { return Edited(Ball(), [](vtkImageData* i) { i->SetSpacing(-1, 1, 1); }); }, start,
      nullptr, "spacing must be positive", "", Output::Empty, true, "spacing must be positive" },
    { "NaN spacing",
      [] { return Edited(Ball(), [](vtkImageData* i) { i->SetSpacing(1, NaN, 1); }); }, start,
      nullptr, "spacing must be positive", "", Output::Empty, true, "spacing must be positive" },
    { "NaN origin", [] { return Edited(Ball(), [](vtkImageData* i) { i->SetOrigin(0, NaN, 0); }); },
      start, nullptr, "the image origin must be finite", "", Output::Empty, true,
      "the image origin must be finite" },
    { "singular direction matrix",
      []
      {
        return Edited(
          Ball(), [](vtkImageData* i) { i->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 0); });
      },
      start, nullptr, "direction matrix must be a rotation", "", Output::Empty, true,
      "direction matrix" },
    { "spacing 1e-6", [] { return Ball(1e-6); }, [] { return Start(1e-6); }, nullptr, "", "",
      Output::Surface, true },
    { "spacing 1e6", [] { return Ball(1e6); }, [] { return Start(1e6); }, nullptr, "", "",
      Output::Surface, true },
  };
}

std::vector<Row> SurfaceRows()
{
  auto ball = [] { return Ball(); };
  return {
    { "empty surface", ball, [] { return vtkSmartPointer<vtkPolyData>::New(); }, nullptr,
      "no polygons or triangle strips", "", Output::Empty },
    { "vertices and lines besides the triangles", ball,
      [] { return WithExtraCells(Start(), true, true); }, nullptr, "", "", Output::Surface },
    { "only lines", ball,
      []
      {
        auto s = WithExtraCells(Start(), false, true);
        s->SetPolys(vtkNew<vtkCellArray>());
        return s;
      },
      nullptr, "no polygons or triangle strips", "", Output::Empty },
    { "triangle strips", ball, [] { return AsStrips(); }, nullptr, "", "", Output::Surface },
    { "quads (a box)", ball, [] { return AsQuads(); }, nullptr, "", "", Output::Surface },
    { "non-manifold edge", ball,
      [] {
        return dstest::MakeFin({ 14, 14, 14 });
      },
      nullptr, "not a manifold triangle mesh", "", Output::Empty },
    { "a NaN coordinate", ball,
      []
      {
        auto s = Start();
        s->GetPoints()->SetPoint(5, NaN, 16, 16);
        return s;
      },
      nullptr, "non-finite point coordinate", "", Output::Empty },
    { "a zero-area triangle", ball, [] { return WithDegenerate(false); }, nullptr, "", "",
      Output::Surface },
    { "a triangle naming a point twice", ball, [] { return WithDegenerate(true); }, nullptr, "", "",
      Output::Surface },
    { "an open surface (a cap)", ball, [] { return Start(1.0, 0.0, 60.0); }, nullptr, "", "",
      Output::Surface },
    { "a surface entirely outside the volume", ball, [] { return Start(1.0, 100.0); }, nullptr, "",
      "outside the image", Output::Surface },
  };
}

std::vector<Row> ParameterRows()
{
  auto ball = [] { return Ball(); };
  auto start = [] { return Start(); };
  return {
    { "Abort at 30 % (from a ProgressEvent observer)", ball, start,
      [](vtkDeformableSurfaceFilter* f) { AbortAt(f, 0.3); }, "", "", Output::Surface },
    { "Tau NaN", ball, start, [](vtkDeformableSurfaceFilter* f) { f->SetTau(NaN); },
      "Tau is not a finite number", "", Output::Empty },
    { "Sigma NaN", ball, start, [](vtkDeformableSurfaceFilter* f) { f->SetSigma(NaN); },
      "Sigma is not a finite number", "", Output::Empty },
    { "SigmaFraction NaN", ball, start,
      [](vtkDeformableSurfaceFilter* f)
      {
        f->SetSigma(0);
        f->SetSigmaFraction(NaN);
      },
      "SigmaFraction is not a finite number", "", Output::Empty },
    { "EdgeWeight NaN", ball, start, [](vtkDeformableSurfaceFilter* f) { f->SetEdgeWeight(NaN); },
      "EdgeWeight is not a finite number", "", Output::Empty },
    { "RegionWeight NaN", ball, start,
      [](vtkDeformableSurfaceFilter* f) { f->SetRegionWeight(NaN); },
      "RegionWeight is not a finite number", "", Output::Empty },
    { "ConvergenceTolerance NaN", ball, start,
      [](vtkDeformableSurfaceFilter* f) { f->SetConvergenceTolerance(NaN); },
      "ConvergenceTolerance is not a finite number", "", Output::Empty },
    { "RefinementThreshold NaN", ball, start,
      [](vtkDeformableSurfaceFilter* f) { f->SetRefinementThreshold(NaN); },
      "RefinementThreshold is not a finite number", "", Output::Empty },
    { "Sigma +Inf (clamped to VTK_DOUBLE_MAX)", ball, start,
      [](vtkDeformableSurfaceFilter* f) { f->SetSigma(Inf); }, "voxels along x, at most 100000", "",
      Output::Empty },
    { "EdgeWeight +Inf (clamped to VTK_DOUBLE_MAX)", ball, start,
      [](vtkDeformableSurfaceFilter* f) { f->SetEdgeWeight(Inf); }, "the force field is not finite",
      "", Output::Empty },
    { "IntensityRange NaN", ball, start,
      [](vtkDeformableSurfaceFilter* f)
      {
        f->SetRegionWeight(1);
        f->SetIntensityRange(NaN, 1);
      },
      "", "the intensity range must be finite", Output::Surface },
  };
}

/// vtkImageScaleSpaceGradient's parameters: NaN is refused by name, a sigma near
/// VTK_DOUBLE_MAX (what +Inf clamps to) as too many voxels, a weight near it overflows the
/// field and is refused too.
void GradientParameterRows()
{
  const std::vector<std::pair<std::string, std::function<void(vtkImageScaleSpaceGradient*)>>>
    rows = {
      { "Sigma is not a finite number", [](vtkImageScaleSpaceGradient* g) { g->SetSigma(NaN); } },
      { "SigmaFraction is not a finite number",
        [](vtkImageScaleSpaceGradient* g)
        {
          g->SetSigma(0);
          g->SetSigmaFraction(NaN);
        } },
      { "EdgeWeight is not a finite number",
        [](vtkImageScaleSpaceGradient* g) { g->SetEdgeWeight(NaN); } },
      { "ImageWeight is not a finite number",
        [](vtkImageScaleSpaceGradient* g) { g->SetImageWeight(NaN); } },
      { "voxels along x, at most 100000", [](vtkImageScaleSpaceGradient* g) { g->SetSigma(Inf); } },
      { "the force field is not finite",
        [](vtkImageScaleSpaceGradient* g) { g->SetEdgeWeight(Inf); } },
      { "the force field is not finite",
        [](vtkImageScaleSpaceGradient* g) { g->SetImageWeight(Inf); } },
    };
  for (const auto& row : rows)
  {
    const std::string label = "gradient parameter: " + row.first;
    std::cout << "--- " << label << std::endl;
    auto image = Ball();
    const dstest::InputGuard guard{ image };
    vtkNew<vtkImageScaleSpaceGradient> gradient;
    vtkNew<dstest::MessageCounter> messages;
    messages->Watch(gradient);
    gradient->SetInputData(image);
    gradient->SetSigma(1.5);
    row.second(gradient);
    gradient->Update();
    CheckMessages(*messages, row.first, "", label);
    DS_CHECK(gradient->GetOutput()->GetNumberOfPoints() == 0, label + ": empty output");
    guard.Check(label);
  }
}

/// vtkDelaunaySeedSurface from few or odd points: the message, then either an empty output or
/// a closed, outward, manifold surface with the expected Euler characteristic (2 per sphere).
void SeedRows()
{
  struct SeedRow
  {
    std::string Name;
    std::vector<std::array<double, 3>> Points;
    std::string Error, Warning;
    long Euler; // 0 with Triangles 0: an empty output
    vtkIdType Triangles;
    std::function<void(vtkDelaunaySeedSurface*)> Configure = nullptr;
  };
  std::vector<std::array<double, 3>> cube, clusters;
  for (int c = 0; c < 8; ++c)
  {
    cube.push_back({ 10.0 * (c & 1), 10.0 * ((c >> 1) & 1), 10.0 * (c >> 2) });
  }
  for (const double shift : { 0.0, 1e5 })
  {
    for (const auto& p : cube)
    {
      clusters.push_back({ p[0] + shift, p[1], p[2] });
    }
  }
  auto withNaN = cube;
  withNaN.push_back({ NaN, 0, 0 });
  withNaN.push_back({ 0, Inf, 0 });
  const std::vector<SeedRow> rows = {
    { "seed: 0 points", {}, "No point with finite coordinates", "", 0, 0 },
    { "seed: only NaN points", { { NaN, 1, 2 } }, "No point with finite coordinates",
      "Ignored 1 point(s)", 0, 0 },
    { "seed: 1 point", { { 1, 2, 3 } }, "", "", 2, 320 },
    { "seed: 2 points", { { 0, 0, 0 }, { 20, 0, 0 } }, "", "", 4, 640 },
    { "seed: 3 points", { { 0, 0, 0 }, { 20, 0, 0 }, { 0, 20, 0 } }, "", "", 6, 960 },
    { "seed: 5 copies of one point", std::vector<std::array<double, 3>>(5, { 4, 5, 6 }), "",
      "The 5 points merge into 1", 2, 320 },
    { "seed: cube corners and two non-finite points", withNaN, "", "Ignored 2 point(s)", 2, 12 },
    // Each cube is far below Tolerance x diagonal (1e-3 x 1e5): documented to merge, and said so.
    { "seed: two far clusters (cubes 1e5 apart)", clusters, "", "The 16 points merge into 2", 4,
      640 },
    { "seed: SeedRadius NaN", { { 1, 2, 3 } }, "SeedRadius is not a finite number", "", 0, 0,
      [](vtkDelaunaySeedSurface* f) { f->SetSeedRadius(NaN); } },
    { "seed: Alpha NaN", cube, "Alpha is not a finite number", "", 0, 0,
      [](vtkDelaunaySeedSurface* f) { f->SetAlpha(NaN); } },
    { "seed: TargetEdgeLength NaN", cube, "TargetEdgeLength is not a finite number", "", 0, 0,
      [](vtkDelaunaySeedSurface* f) { f->SetTargetEdgeLength(NaN); } },
    { "seed: Tolerance NaN", cube, "Tolerance is not a finite number", "", 0, 0,
      [](vtkDelaunaySeedSurface* f) { f->SetTolerance(NaN); } },
    // Clamped to 1: every point within one diagonal of the first, so all merge into one.
    { "seed: Tolerance 5 (clamped to 1)", cube, "", "The 8 points merge into 1", 2, 320,
      [](vtkDelaunaySeedSurface* f) { f->SetTolerance(5); } },
  };
  for (const SeedRow& row : rows)
  {
    std::cout << "--- " << row.Name << std::endl;
    vtkNew<vtkPoints> points;
    for (const auto& p : row.Points)
    {
      points->InsertNextPoint(p.data());
    }
    vtkNew<vtkPolyData> cloud;
    cloud->SetPoints(points);
    const dstest::InputGuard guard{ cloud };
    vtkNew<vtkDelaunaySeedSurface> seed;
    vtkNew<dstest::MessageCounter> messages;
    messages->Watch(seed);
    seed->SetInputData(cloud);
    if (row.Configure)
    {
      row.Configure(seed);
    }
    seed->Update();
    CheckMessages(*messages, row.Error, row.Warning, row.Name);
    vtkPolyData* out = seed->GetOutput();
    DS_CHECK(out->GetNumberOfPolys() == row.Triangles,
      row.Name + ": " + std::to_string(row.Triangles) + " triangles, got " +
        std::to_string(out->GetNumberOfPolys()));
    if (row.Triangles > 0)
    {
      const auto f = dstest::Measure(out);
      dstest::CheckClosedManifold(f, out->GetNumberOfPoints(), row.Euler, true, row.Name);
    }
    else
    {
      DS_CHECK(out->GetNumberOfPoints() == 0 && seed->GetTetrahedra()->GetNumberOfCells() == 0,
        row.Name + ": empty outputs");
    }
    guard.Check(row.Name);
  }
}

/// Out-of-range values are clamped by the setters: the clamped value, then a sane run.
void ClampRows()
{
  struct Clamp
  {
    std::string Name;
    std::function<void(vtkDeformableSurfaceFilter*)> Set;
    std::function<double(vtkDeformableSurfaceFilter*)> Get;
    double Expected;
    std::string Warning; // Gamma warns; the vtkSetClampMacro setters clamp silently
  };
  const std::vector<Clamp> clamps = {
    { "Gamma 3", [](vtkDeformableSurfaceFilter* f) { f->SetGamma(3); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetGamma(); }, 0.5,
      "outside the stable range" },
    { "Gamma -1", [](vtkDeformableSurfaceFilter* f) { f->SetGamma(-1); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetGamma(); }, 1e-6,
      "outside the stable range" },
    { "Gamma NaN", [](vtkDeformableSurfaceFilter* f) { f->SetGamma(NaN); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetGamma(); }, 1e-6,
      "outside the stable range" },
    { "Tau 2", [](vtkDeformableSurfaceFilter* f) { f->SetTau(2); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetTau(); }, 1.0, "" },
    { "Tau -1", [](vtkDeformableSurfaceFilter* f) { f->SetTau(-1); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetTau(); }, 0.0, "" },
    { "EdgeWeight -1", [](vtkDeformableSurfaceFilter* f) { f->SetEdgeWeight(-1); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetEdgeWeight(); }, 0.0, "" },
    { "ImageWeight -1", [](vtkDeformableSurfaceFilter* f) { f->SetImageWeight(-1); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetImageWeight(); }, 0.0, "" },
    { "RegionWeight -1", [](vtkDeformableSurfaceFilter* f) { f->SetRegionWeight(-1); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetRegionWeight(); }, 0.0, "" },
    { "Sigma -1", [](vtkDeformableSurfaceFilter* f) { f->SetSigma(-1); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetSigma(); }, 0.0, "" },
    { "SigmaFraction 5",
      [](vtkDeformableSurfaceFilter* f)
      {
        f->SetSigma(0);
        f->SetSigmaFraction(5);
      },
      [](vtkDeformableSurfaceFilter* f) { return f->GetSigmaFraction(); }, 1.0, "" },
    { "ConvergenceTolerance -1",
      [](vtkDeformableSurfaceFilter* f) { f->SetConvergenceTolerance(-1); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetConvergenceTolerance(); }, 0.0, "" },
    { "ConvergenceTolerance 7",
      [](vtkDeformableSurfaceFilter* f) { f->SetConvergenceTolerance(7); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetConvergenceTolerance(); }, 1.0, "" },
    { "RefinementThreshold -1",
      [](vtkDeformableSurfaceFilter* f) { f->SetRefinementThreshold(-1); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetRefinementThreshold(); }, 0.0, "" },
    { "MaxSweepsPerLevel 0", [](vtkDeformableSurfaceFilter* f) { f->SetMaxSweepsPerLevel(0); },
      [](vtkDeformableSurfaceFilter* f) { return f->GetMaxSweepsPerLevel(); }, 1.0, "" },
    { "MaxLevels 99",
      [](vtkDeformableSurfaceFilter* f)
      {
        f->SetMaxLevels(99);
        f->SetMaxVertices(3000);
      },
      [](vtkDeformableSurfaceFilter* f) { return f->GetMaxLevels(); }, 10.0, "" },
  };
  for (const Clamp& c : clamps)
  {
    std::cout << "--- clamp: " << c.Name << std::endl;
    auto image = Ball();
    auto start = Start();
    const dstest::InputGuard guard{ image, start };
    vtkNew<vtkDeformableSurfaceFilter> f;
    vtkNew<dstest::MessageCounter> setMessages;
    f->SetInputData(0, image);
    f->SetInitialSurfaceData(start);
    f->SetSigma(1.5);
    f->SetMaxLevels(1);
    f->SetMaxSweepsPerLevel(150);
    setMessages->Watch(f);
    c.Set(f);
    const double value = c.Get(f);
    std::cout << "  clamped to " << value << std::endl;
    DS_CHECK(value == c.Expected,
      c.Name + ": clamped to " + std::to_string(c.Expected) + ", got " + std::to_string(value));
    CheckMessages(*setMessages, "", c.Warning, c.Name + " (setter)");
    setMessages->Reset();
    f->Update();
    DS_CHECK(
      setMessages->Errors == 0, c.Name + ": no error in the run, got: " + setMessages->ErrorText);
    dstest::CheckSurfaceInvariants(start, f->GetOutput(), c.Name);
    guard.Check(c.Name);
  }
}
} // namespace

int TestBadInputMatrix(int, char*[])
{
  for (const auto& rows : { ImageRows(), SurfaceRows(), ParameterRows() })
  {
    for (const Row& row : rows)
    {
      RunRow(row);
    }
  }
  ClampRows();
  GradientParameterRows();
  SeedRows();
  return dstest::Result("TestBadInputMatrix");
}

int main(int argc, char* argv[])
{
  return TestBadInputMatrix(argc, argv);
}
