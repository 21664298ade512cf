// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkDelaunaySeedSurface on random point sets.
//
// 0 to 40 points, mostly on a coarse lattice (so duplicates, collinear and coplanar sets, grids
// with cospherical neighbours and hence flat tetrahedra and pinches come often), sometimes NaN,
// inf or any double; random Alpha, removed tetrahedron IDs (valid or not), Tolerance, SeedRadius,
// TargetEdgeLength (bounded so the subdivision stays small) and the intensity rule on a tiny
// image. The class's promises (its header comment): no crash; either an empty surface with an
// error or a warning, or a closed, 2-manifold, consistently and outward-oriented (a positive
// enclosed volume) triangle surface with finite points and a SeedPointId per point indexing the
// input (or -1); the tetrahedra output carries TetraId and Removed per cell; the input is
// unchanged.
#include "FuzzVTK.h"
#include "vtkDelaunaySeedSurface.h"

#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>

namespace
{
constexpr double Step = 2.0; // lattice step of the input points (world units)
constexpr int Cells = 4;     // lattice cells per axis: points in [0, 8]^3

/// A 5^3 image over the lattice, bright in its middle (for the intensity rule).
vtkImageData* TinyImage()
{
  static vtkImageData* image = []
  {
    auto* im = vtkImageData::New();
    im->SetDimensions(5, 5, 5);
    im->SetSpacing(Step, Step, Step);
    vtkNew<vtkFloatArray> values;
    values->SetName("Intensity");
    values->SetNumberOfTuples(125);
    for (int i = 0; i < 125; ++i)
    {
      const int x = i % 5, y = (i / 5) % 5, z = i / 25;
      values->SetValue(
        i, static_cast<float>(12 - (x - 2) * (x - 2) - (y - 2) * (y - 2) - (z - 2) * (z - 2)));
    }
    im->GetPointData()->SetScalars(values);
    return im;
  }();
  return image;
}

void Configure(vtkDelaunaySeedSurface* seed, FuzzedDataProvider& in)
{
  static const double alphas[] = { 0, 0, 1, 3, 6, 100 };
  seed->SetAlpha(alphas[in.ConsumeIntegralInRange(0, 5)]);
  const int removed = in.ConsumeIntegralInRange(0, 3);
  for (int i = 0; i < removed; ++i)
  {
    seed->AddRemovedTetrahedron(in.ConsumeIntegralInRange<vtkIdType>(-2, 60));
  }
  static const double tolerances[] = { 0.001, 0, 0.1 };
  seed->SetTolerance(tolerances[in.ConsumeIntegralInRange(0, 2)]);
  static const double radii[] = { 5, 0.5, 1e-3 };
  seed->SetSeedRadius(radii[in.ConsumeIntegralInRange(0, 2)]);
  // At least an eighth of the lattice's extent: a few subdivisions at most.
  seed->SetTargetEdgeLength(
    in.ConsumeBool() ? 0.0 : Step * Cells * (0.125 + in.ConsumeProbability<double>()));
  if (in.ConsumeBool())
  {
    seed->SetUseIntensityRange(true);
    if (in.ConsumeBool())
    {
      seed->SetImageData(TinyImage());
    }
    seed->SetIntensityRange(in.ConsumeIntegralInRange(0, 12), in.ConsumeIntegralInRange(0, 12));
  }
}

void CheckSurface(vtkDelaunaySeedSurface* seed, vtkIdType nInput)
{
  vtkPolyData* out = seed->GetOutput();
  dsurf::TriangleMesh mesh;
  FUZZ_CHECK(fuzzvtk::ToMesh(out, mesh), "the surface has triangles only");
  const std::string problem = fuzzcheck::SurfaceProblem(mesh, true);
  FUZZ_CHECK(problem.empty(), "a closed, oriented 2-manifold with finite points: " + problem);
  // Outward from the kept tetrahedra: a cavity's piece faces into the cavity (its own volume is
  // negative), so only the whole encloses a positive volume.
  FUZZ_CHECK(mesh.SignedVolume() > 0, "oriented outward: the surface encloses a positive volume");

  vtkDataArray* ids = out->GetPointData()->GetArray("SeedPointId");
  FUZZ_CHECK(
    ids && ids->GetNumberOfTuples() == out->GetNumberOfPoints(), "a SeedPointId per point");
  for (vtkIdType i = 0; i < ids->GetNumberOfTuples(); ++i)
  {
    const double id = ids->GetTuple1(i);
    FUZZ_CHECK(id >= -1 && id < nInput, "SeedPointId indexes the input or is -1");
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzedDataProvider in(data, size);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const int n = in.ConsumeIntegralInRange(0, 40);
  for (int i = 0; i < n; ++i)
  {
    double x[3];
    if (i > 0 && in.ConsumeIntegralInRange(0, 7) == 0)
    {
      points->GetPoint(in.ConsumeIntegralInRange(0, i - 1), x); // an exact duplicate
    }
    else
    {
      for (double& c : x)
      {
        c = fuzzvtk::Coordinate(in, Step, Cells);
      }
    }
    points->InsertNextPoint(x);
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  const std::vector<unsigned char> before = fuzzvtk::Fingerprint(cloud);

  vtkNew<vtkDelaunaySeedSurface> seed;
  seed->SetController(nullptr);
  Configure(seed, in);
  vtkNew<fuzzvtk::MessageCounter> messages;
  seed->AddObserver(vtkCommand::ErrorEvent, messages);
  seed->AddObserver(vtkCommand::WarningEvent, messages);
  seed->SetInputData(cloud);
  fuzzvtk::PrintPoints("input", cloud);
  seed->Update();
  fuzzvtk::PrintPoints("surface", seed->GetOutput());
  fuzzvtk::PrintCells("surface", seed->GetOutput());

  FUZZ_CHECK(fuzzvtk::Fingerprint(cloud) == before, "the input points are unchanged");
  if (seed->GetOutput()->GetNumberOfCells() == 0)
  {
    FUZZ_CHECK(messages->Errors + messages->Warnings > 0,
      "an empty surface comes with an error or a warning");
  }
  else
  {
    CheckSurface(seed, n);
  }
  vtkUnstructuredGrid* tets = seed->GetTetrahedra();
  const vtkIdType nTets = tets->GetNumberOfCells();
  for (const char* name : { "TetraId", "Removed" })
  {
    vtkDataArray* a = tets->GetCellData()->GetArray(name);
    FUZZ_CHECK(nTets == 0 || (a && a->GetNumberOfTuples() == nTets),
      std::string("one ") + name + " per tetrahedron");
  }
  return 0;
}
