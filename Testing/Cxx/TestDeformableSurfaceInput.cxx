// SPDX-License-Identifier: BSD-3-Clause
// vtkDeformableSurfaceFilter input handling: ParaView's Box (24 points, faces apart)
// is merged into a closed cube, triangle strips are accepted, the input is never
// modified, an open surface keeps its boundary, two disjoint surfaces both evolve,
// a non-manifold edge and a missing surface give an error and an empty output,
// Gamma is clamped, vertices outside the image are warned about.
#include "DSSurfaceInvariants.h"

#include "TestSolverMeshes.h"
#include <cmath>

#include "vtkDeformableSurfaceFilter.h"

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkStripper.h"
#include "vtkTable.h"
#include "vtkTriangleFilter.h"

namespace
{
class EventCounter : public vtkCommand
{
public:
  static EventCounter* New() { return new EventCounter; }
  void Execute(vtkObject*, unsigned long, void*) override { ++this->Count; }
  int Count = 0;
};

/// Two soft balls of radius 8 around (20,32,32) and (44,32,32) in a 64^3 image.
vtkSmartPointer<vtkImageData> TwoBalls()
{
  const int n = 64;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfTuples(n * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        double v = 0;
        for (double cx : { 20.0, 44.0 })
        {
          const double r =
            std::sqrt((i - cx) * (i - cx) + (j - 32.0) * (j - 32.0) + (k - 32.0) * (k - 32.0));
          v = std::max(v, 1.0 / (1.0 + std::exp(3.0 * (r - 8.0))));
        }
        values->SetValue(i + n * (j + n * k), static_cast<float>(v));
      }
  image->GetPointData()->SetScalars(values);
  return image;
}

vtkSmartPointer<vtkPolyData> Sphere(double cx, double r, double endPhi = 180)
{
  vtkNew<vtkSphereSource> s;
  s->SetCenter(cx, 32, 32);
  s->SetRadius(r);
  s->SetThetaResolution(24);
  s->SetPhiResolution(24);
  s->SetEndPhi(endPhi);
  s->Update();
  return s->GetOutput();
}

struct Result
{
  vtkSmartPointer<vtkPolyData> Surface;
  int Errors = 0, Warnings = 0;
};

// Input handling is checked on one level (MaxLevels 0); the open cap is also run
// through the hierarchy, where refinement must keep the boundary where it was.
Result Deform(vtkImageData* image, vtkDataObject* surface, int sweeps = 300, double gamma = 0.07,
  int levels = 0, bool subdivide = false)
{
  vtkNew<vtkDeformableSurfaceFilter> filter;
  vtkNew<EventCounter> errors, warnings;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->AddObserver(vtkCommand::WarningEvent, warnings);
  filter->SetInputData(0, image);
  if (surface)
  {
    filter->SetInitialSurfaceData(surface);
  }
  filter->SetGamma(gamma);
  filter->SetSigma(1.5);
  filter->SetMaxSweepsPerLevel(sweeps);
  filter->SetMaxLevels(levels);
  filter->SetSubdivideInitialSurface(subdivide);
  const std::string label = std::string("Deform, ") + std::to_string(levels) + " level(s)";
  dstest::UpdateWithInputsUnchanged(filter, label);
  Result r;
  r.Surface = filter->GetOutput();
  if (r.Surface->GetNumberOfPoints() > 0) // the bad-input cases below assert their empty output
  {
    dstest::CheckSurfaceInvariants(vtkPolyData::SafeDownCast(surface), r.Surface, label);
  }
  r.Errors = errors->Count;
  r.Warnings = warnings->Count;
  return r;
}

double MeanDistance(vtkPolyData* pd, double cx, double r, vtkIdType begin, vtkIdType end)
{
  double sum = 0;
  for (vtkIdType i = begin; i < end; ++i)
  {
    double x[3];
    pd->GetPoint(i, x);
    sum += std::abs(
      std::sqrt((x[0] - cx) * (x[0] - cx) + (x[1] - 32) * (x[1] - 32) + (x[2] - 32) * (x[2] - 32)) -
      r);
  }
  return sum / std::max<vtkIdType>(end - begin, 1);
}
} // namespace

int TestDeformableSurfaceInput(int, char*[])
{
  auto image = TwoBalls();

  // --- ParaView's Box: 24 points (each face separate) merge into a closed cube ---
  {
    vtkNew<vtkCubeSource> box;
    box->SetCenter(20, 32, 32);
    box->SetXLength(24);
    box->SetYLength(24);
    box->SetZLength(24);
    box->Update();
    const Result r = Deform(image, box->GetOutput(), 20);
    std::cout << "Box: " << box->GetOutput()->GetNumberOfPoints() << " input points -> "
              << r.Surface->GetNumberOfPoints() << " output points, "
              << r.Surface->GetNumberOfPolys() << " triangles" << std::endl;
    DS_CHECK(r.Surface->GetNumberOfPoints() == 8, "the Box's 24 points merge into 8");
    DS_CHECK(r.Surface->GetNumberOfPolys() == 12, "the Box's 6 quads become 12 triangles");

    // A polygon of one repeated point beside it is no part of the surface: no stray output point.
    vtkNew<vtkPolyData> boxAndDot;
    boxAndDot->DeepCopy(box->GetOutput());
    const vtkIdType dot = boxAndDot->GetPoints()->InsertNextPoint(20, 32, 32);
    const vtkIdType ids[3] = { dot, dot, dot };
    boxAndDot->GetPolys()->InsertNextCell(3, ids);
    const Result d = Deform(image, boxAndDot, 20);
    std::cout << "Box and a one-point polygon: " << d.Surface->GetNumberOfPoints()
              << " output points" << std::endl;
    DS_CHECK(
      d.Errors == 0 && d.Surface->GetNumberOfPoints() == 8 && d.Surface->GetNumberOfPolys() == 12,
      "a one-point polygon leaves no point outside the surface: the cube's 8 points, 12 triangles");
    DS_CHECK(r.Errors == 0, "no error for the Box");

    // With SubdivideInitialSurface (the default) the merged cube (mean edge 27.3) is split
    // 1 -> 4 to the mean edge nearest 4 sigma = 6 (within sqrt 2): twice, 8 -> 26 -> 98 points
    // (mean edge 6.8; a third split would give 3.4).
    const Result sub = Deform(image, box->GetOutput(), 20, 0.07, 0, true);
    vtkDataArray* count = sub.Surface->GetFieldData()->GetArray("InitialSubdivisions");
    std::cout << "Box, subdivided: " << sub.Surface->GetNumberOfPoints() << " points, "
              << sub.Surface->GetNumberOfPolys() << " triangles" << std::endl;
    DS_CHECK(count && count->GetTuple1(0) == 2, "two initial subdivisions");
    DS_CHECK(sub.Surface->GetNumberOfPoints() == 98, "98 points after two subdivisions");
    DS_CHECK(sub.Surface->GetNumberOfPolys() == 192, "192 triangles after two subdivisions");

    // A sigma far below the voxel size must not subdivide the start without end: the
    // subdivision stops at a mean edge of two voxels (27.3 -> 1.7: four times, 1538 points).
    vtkNew<vtkDeformableSurfaceFilter> tiny;
    tiny->SetInputData(0, image);
    tiny->SetInitialSurfaceData(box->GetOutput());
    tiny->SetSigma(1e-9);
    tiny->SetMaxLevels(0);
    tiny->SetMaxSweepsPerLevel(5);
    dstest::UpdateAndCheckSurface(tiny, "Box, sigma 1e-9");
    std::cout << "Box, sigma 1e-9: " << tiny->GetOutput()->GetNumberOfPoints() << " points"
              << std::endl;
    DS_CHECK(tiny->GetOutput()->GetNumberOfPoints() == 1538, "subdivision floored at two voxels");
  }

  // --- the input is not modified; strips give the same result as triangles ---
  {
    auto sphere = Sphere(20, 11);
    vtkNew<vtkPolyData> before;
    before->DeepCopy(sphere);
    const vtkMTimeType mtime = sphere->GetMTime();
    const Result tris = Deform(image, sphere);
    int changed = 0;
    for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      sphere->GetPoint(i, a);
      before->GetPoint(i, b);
      changed += (a[0] != b[0] || a[1] != b[1] || a[2] != b[2]);
    }
    DS_CHECK_LE(changed, 0, "input points changed by the filter");
    DS_CHECK(sphere->GetMTime() == mtime, "input MTime unchanged");
    const double d = MeanDistance(tris.Surface, 20, 8, 0, tris.Surface->GetNumberOfPoints());
    DS_CHECK_LE(d, 0.4, "sphere onto ball 1: mean |d|");

    vtkNew<vtkStripper> stripper;
    stripper->SetInputData(sphere);
    stripper->Update();
    DS_CHECK(stripper->GetOutput()->GetNumberOfStrips() > 0, "the stripper made strips");
    const Result strips = Deform(image, stripper->GetOutput());
    const double ds = MeanDistance(strips.Surface, 20, 8, 0, strips.Surface->GetNumberOfPoints());
    std::cout << "strips: " << strips.Surface->GetNumberOfPolys() << " triangles" << std::endl;
    DS_CHECK(strips.Surface->GetNumberOfPolys() == tris.Surface->GetNumberOfPolys(),
      "strips: same triangle count");
    DS_CHECK_LE(ds, 0.4, "strips onto ball 1: mean |d|");
  }

  // --- two disjoint surfaces at once: both evolve onto their ball ---
  {
    vtkNew<vtkAppendPolyData> append;
    append->AddInputData(Sphere(20, 11));
    append->AddInputData(Sphere(44, 11));
    append->Update();
    const Result r = Deform(image, append->GetOutput());
    const vtkIdType half = r.Surface->GetNumberOfPoints() / 2;
    const double d1 = MeanDistance(r.Surface, 20, 8, 0, half);
    const double d2 = MeanDistance(r.Surface, 44, 8, half, 2 * half);
    DS_CHECK_LE(d1, 0.4, "two surfaces: mean |d| to ball 1");
    DS_CHECK_LE(d2, 0.4, "two surfaces: mean |d| to ball 2");
    const int selfx = r.Surface->GetFieldData()->GetArray("SelfIntersections")->GetTuple1(0);
    DS_CHECK_LE(selfx, 0, "two surfaces: self-intersections");
  }

  // --- an open cap keeps its boundary ---
  {
    auto cap = Sphere(20, 11, 60);
    vtkNew<vtkTriangleFilter> tri;
    tri->SetInputData(cap);
    tri->Update();
    for (int levels : { 0, 2 })
    {
      const Result r = Deform(image, cap, 300, 0.07, levels);
      dsurf::TriangleMesh m = dstest::FromPolyData(r.Surface);
      std::string err;
      DS_CHECK(m.BuildTopology(&err), err);
      // Every output boundary vertex must be an input point, unmoved.
      int boundary = 0, moved = 0;
      for (int v = 0; v < m.NumberOfPoints(); ++v)
      {
        if (!m.BoundaryVertex[v])
        {
          continue;
        }
        ++boundary;
        double best = 1e300;
        for (vtkIdType i = 0; i < cap->GetNumberOfPoints(); ++i)
        {
          double x[3];
          cap->GetPoint(i, x);
          best = std::min(best,
            std::abs(x[0] - m.Points[v][0]) + std::abs(x[1] - m.Points[v][1]) +
              std::abs(x[2] - m.Points[v][2]));
        }
        moved += best > 0;
      }
      std::cout << "open cap, " << levels << " levels: " << boundary << " boundary vertices, "
                << moved << " not on an input point" << std::endl;
      if (levels == 0)
      {
        DS_CHECK(boundary == 24, "the cap's boundary ring has 24 vertices");
        DS_CHECK_LE(moved, 0, "boundary vertices that moved");
      }
      else
      {
        // New boundary vertices come from refinement; the 24 input ones must stay put.
        DS_CHECK_GE(boundary, 24, "refinement keeps the boundary ring");
        DS_CHECK_GE(boundary - moved, 24, "input boundary vertices still at their input position");
      }
    }
  }

  // --- bad input: a non-manifold edge, no surface, no polygons ---
  {
    auto fin = dstest::MakeFin({ 30, 30, 30 });
    std::cout << "(an error message about a non-manifold edge is expected next)" << std::endl;
    const Result r = Deform(image, fin);
    DS_CHECK(r.Errors == 1, "non-manifold edge: one error");
    DS_CHECK(r.Surface->GetNumberOfPoints() == 0, "non-manifold edge: empty output");

    vtkNew<vtkPolyData> pointsOnly;
    pointsOnly->SetPoints(fin->GetPoints());
    std::cout << "(an error message about a surface without polygons is expected next)"
              << std::endl;
    const Result e = Deform(image, pointsOnly);
    DS_CHECK(
      e.Errors == 1 && e.Surface->GetNumberOfPoints() == 0, "no polygons: error, empty output");
  }

  // --- an inconsistently oriented start (one triangle reversed) is mended with a warning,
  // and the hierarchy's topology checks then pass ---
  {
    vtkNew<vtkTriangleFilter> tri;
    tri->SetInputData(Sphere(20, 11));
    tri->Update();
    vtkNew<vtkPolyData> oneFlipped;
    oneFlipped->DeepCopy(tri->GetOutput());
    vtkNew<vtkCellArray> polys;
    vtkCellArray* in = oneFlipped->GetPolys();
    in->InitTraversal();
    vtkIdType npts;
    const vtkIdType* ids;
    bool first = true;
    while (in->GetNextCell(npts, ids))
    {
      const vtkIdType reversed[3] = { ids[0], ids[2], ids[1] };
      polys->InsertNextCell(3, first ? reversed : ids);
      first = false;
    }
    oneFlipped->SetPolys(polys);
    vtkNew<vtkDeformableSurfaceFilter> filter;
    vtkNew<EventCounter> errors, warnings;
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
    filter->AddObserver(vtkCommand::WarningEvent, warnings);
    filter->SetInputData(0, image);
    filter->SetInitialSurfaceData(oneFlipped);
    filter->SetMaxLevels(1);
    filter->SetCheckTopology(true);
    dstest::UpdateAndCheckSurface(filter, "one reversed triangle");
    std::cout << "one reversed triangle: " << errors->Count << " error(s), " << warnings->Count
              << " warning(s), " << filter->GetOutput()->GetNumberOfPoints() << " points"
              << std::endl;
    DS_CHECK(errors->Count == 0 && filter->GetOutput()->GetNumberOfPoints() > 0,
      "one reversed triangle: no error, a surface");
    DS_CHECK(warnings->Count >= 1, "one reversed triangle: a warning says it was mended");
  }

  // --- bad images: one NaN voxel, a constant image, a sheared direction matrix ---
  {
    auto sphere = Sphere(20, 11);
    vtkNew<vtkImageData> nan;
    nan->DeepCopy(image);
    vtkDataArray* values = nan->GetPointData()->GetScalars();
    values->SetTuple1(values->GetNumberOfTuples() / 3, std::nan(""));
    std::cout << "(an error message about non-finite values is expected next)" << std::endl;
    const Result a = Deform(nan, sphere);
    DS_CHECK(
      a.Errors == 1 && a.Surface->GetNumberOfPoints() == 0, "a NaN voxel: error, empty output");

    vtkNew<vtkImageData> flat;
    flat->DeepCopy(image);
    flat->GetPointData()->GetScalars()->Fill(7.0);
    std::cout << "(an error message about a constant image is expected next)" << std::endl;
    const Result b = Deform(flat, sphere);
    DS_CHECK(b.Errors == 1 && b.Surface->GetNumberOfPoints() == 0,
      "a constant image: error, empty output");

    vtkNew<vtkImageData> sheared;
    sheared->DeepCopy(image);
    sheared->SetDirectionMatrix(1, 0.5, 0, 0, 1, 0, 0, 0, 1);
    std::cout << "(an error message about the direction matrix is expected next)" << std::endl;
    const Result c = Deform(sheared, sphere);
    DS_CHECK(c.Errors == 1 && c.Surface->GetNumberOfPoints() == 0,
      "a sheared direction: error, empty output");
  }

  // --- Gamma clamped with a warning; vertices outside the image warned about once ---
  {
    vtkNew<vtkDeformableSurfaceFilter> f;
    vtkNew<EventCounter> warnings;
    f->AddObserver(vtkCommand::WarningEvent, warnings);
    f->SetGamma(3.0);
    DS_CHECK(f->GetGamma() == 0.5 && warnings->Count == 1, "Gamma 3 clamped to 0.5 with a warning");
    const Result r = Deform(image, Sphere(60, 10), 5);
    DS_CHECK(r.Warnings == 1, "a surface partly outside the image: one warning");
  }

  return dstest::Result("TestDeformableSurfaceInput");
}

int main(int argc, char* argv[])
{
  return TestDeformableSurfaceInput(argc, argv);
}
