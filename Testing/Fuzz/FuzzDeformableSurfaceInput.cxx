// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the initial-surface input of vtkDeformableSurfaceFilter.
//
// The surface is a random vtkPolyData: points on a coarse lattice over a 10^3 image of a soft
// ball (coincident points come often), sometimes NaN, inf or any double; optionally the 24
// points and 6 quads of a box around the ball first; then cells of every kind a vtkPolyData
// holds: vertices, lines and polylines, triangles, quads, polygons (degenerate ones too: repeated
// points), triangle strips, so edges with three or more faces, open pieces and pinched vertices
// come often. A few sweeps on one or two levels, one thread, at most 3000 vertices: an
// execution takes milliseconds. The filter's promises: no crash; the inputs unchanged; either
// an empty surface with an error, or a surface of finite points that is a consistently
// oriented 2-manifold with the topology it was given (the triangles and strips of the input
// with coincident points merged): closed when that was closed, the same Euler characteristic.
#include "FuzzVTK.h"
#include "vtkDeformableSurfaceFilter.h"

#include "vtkCleanPolyData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkTriangleFilter.h"

#include <algorithm>

namespace
{
constexpr double Step = 1.5; // lattice step of the input points (voxels of the image)
constexpr int Cells = 6;     // lattice cells per axis: points in [0, 9]^3, the image's extent

/// A soft ball of radius 3 in the middle of a 10^3 image (built once, never modified).
vtkImageData* Ball()
{
  static vtkImageData* image = []
  {
    auto* im = vtkImageData::New();
    im->SetDimensions(10, 10, 10);
    vtkNew<vtkFloatArray> values;
    values->SetName("Ball");
    values->SetNumberOfTuples(1000);
    for (int i = 0; i < 1000; ++i)
    {
      const double x = i % 10 - 4.5, y = (i / 10) % 10 - 4.5, z = i / 100 - 4.5;
      values->SetValue(i,
        static_cast<float>(1.0 / (1.0 + std::exp(2.0 * (std::sqrt(x * x + y * y + z * z) - 3.0)))));
    }
    im->GetPointData()->SetScalars(values);
    return im;
  }();
  return image;
}

/// ParaView's Box around the ball: 24 points, each face a quad of its own.
void AddBox(vtkPoints* points, vtkCellArray* polys)
{
  static const int faces[6][4][3] = { { { 0, 0, 0 }, { 0, 1, 0 }, { 0, 1, 1 }, { 0, 0, 1 } },
    { { 1, 0, 0 }, { 1, 0, 1 }, { 1, 1, 1 }, { 1, 1, 0 } },
    { { 0, 0, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 0, 0 } },
    { { 0, 1, 0 }, { 1, 1, 0 }, { 1, 1, 1 }, { 0, 1, 1 } },
    { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } },
    { { 0, 0, 1 }, { 0, 1, 1 }, { 1, 1, 1 }, { 1, 0, 1 } } };
  for (const auto& face : faces)
  {
    vtkIdType ids[4];
    for (int k = 0; k < 4; ++k)
    {
      ids[k] = points->InsertNextPoint(1 + 7 * face[k][0], 1 + 7 * face[k][1], 1 + 7 * face[k][2]);
    }
    polys->InsertNextCell(4, ids);
  }
}

vtkSmartPointer<vtkPolyData> RandomSurface(FuzzedDataProvider& in)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  if (in.ConsumeBool())
  {
    AddBox(points, polys);
  }
  const int n = in.ConsumeIntegralInRange(0, 24);
  for (int i = 0; i < n; ++i)
  {
    points->InsertNextPoint(fuzzvtk::Coordinate(in, Step, Cells),
      fuzzvtk::Coordinate(in, Step, Cells), fuzzvtk::Coordinate(in, Step, Cells));
  }
  const vtkIdType nPoints = points->GetNumberOfPoints();
  const int nCells = nPoints > 0 ? in.ConsumeIntegralInRange(0, 24) : 0;
  for (int c = 0; c < nCells; ++c)
  {
    const int kind =
      in.ConsumeIntegralInRange(0, 5); // vertex, line, triangle, quad, polygon, strip
    static const int minSize[6] = { 1, 2, 3, 4, 5, 3 }, maxSize[6] = { 2, 4, 3, 4, 7, 7 };
    const int k = in.ConsumeIntegralInRange(minSize[kind], maxSize[kind]);
    std::vector<vtkIdType> ids(k);
    for (auto& id : ids)
    {
      id = in.ConsumeIntegralInRange<vtkIdType>(0, nPoints - 1);
    }
    vtkCellArray* cells = kind == 0 ? verts.Get()
      : kind == 1                   ? lines.Get()
      : kind == 5                   ? strips.Get()
                                    : polys.Get();
    cells->InsertNextCell(k, ids.data());
  }
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(points);
  surface->SetVerts(verts);
  surface->SetLines(lines);
  surface->SetPolys(polys);
  surface->SetStrips(strips);
  return surface;
}

/// The topology the filter is given: the input's polygons and strips as triangles with
/// coincident points merged (as the class documents), as a mesh (points of degenerate cells may
/// stay unused); false when that is not a finite manifold triangle mesh (the filter must then
/// refuse it).
bool GivenTopology(vtkPolyData* surface, dsurf::TriangleMesh& given)
{
  vtkNew<vtkPolyData> copy;
  copy->ShallowCopy(surface);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(copy);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  vtkNew<vtkCleanPolyData> merged;
  merged->SetInputConnection(triangles->GetOutputPort());
  merged->PointMergingOn();
  merged->ToleranceIsAbsoluteOff();
  merged->SetTolerance(1e-6);
  merged->ConvertLinesToPointsOff();
  merged->ConvertPolysToLinesOff();
  merged->ConvertStripsToPolysOff();
  merged->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  merged->Update();
  std::string error;
  return fuzzvtk::ToMesh(merged->GetOutput(), given) && !given.Triangles.empty() &&
    given.BuildTopology(&error) && fuzzcheck::AllFinite(given) &&
    given.CountNonManifoldVertices() == 0;
}

void Configure(vtkDeformableSurfaceFilter* filter, FuzzedDataProvider& in)
{
  filter->SetSigma(1.0);
  filter->SetMaxLevels(in.ConsumeIntegralInRange(0, 1));
  filter->SetMaxSweepsPerLevel(in.ConsumeIntegralInRange(1, 4));
  filter->SetSubdivideInitialSurface(in.ConsumeBool());
  filter->SetUniformRefinement(in.ConsumeBool());
  filter->SetRegionWeight(in.ConsumeBool() ? 0.0 : 0.5);
  filter->SetMaxVertices(3000);
  filter->SetNumberOfThreads(1);
  filter->SetController(nullptr);
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzedDataProvider in(data, size);
  vtkSmartPointer<vtkPolyData> surface = RandomSurface(in);
  const std::vector<unsigned char> before = fuzzvtk::Fingerprint(surface);
  vtkImageData* image = Ball();
  const vtkMTimeType imageTime = image->GetMTime();

  vtkNew<vtkDeformableSurfaceFilter> filter;
  Configure(filter, in);
  vtkNew<fuzzvtk::MessageCounter> messages;
  filter->AddObserver(vtkCommand::ErrorEvent, messages);
  filter->AddObserver(vtkCommand::WarningEvent, messages);
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceData(surface);
  fuzzvtk::PrintPoints("input", surface);
  fuzzvtk::PrintCells("input", surface);
  filter->Update();
  fuzzvtk::PrintPoints("surface", filter->GetOutput());
  fuzzvtk::PrintCells("surface", filter->GetOutput());

  FUZZ_CHECK(fuzzvtk::Fingerprint(surface) == before, "the input surface is unchanged");
  FUZZ_CHECK(image->GetMTime() == imageTime, "the image is unchanged");
  vtkPolyData* out = filter->GetOutput();
  if (out->GetNumberOfCells() == 0)
  {
    FUZZ_CHECK(messages->Errors > 0, "an empty surface comes with an error");
    return 0;
  }
  dsurf::TriangleMesh given;
  FUZZ_CHECK(GivenTopology(surface, given), "only a finite manifold triangle surface is accepted");
  dsurf::TriangleMesh result;
  FUZZ_CHECK(fuzzvtk::ToMesh(out, result), "the surface has triangles only");
  const bool closed = given.IsClosed();
  const std::string problem = fuzzcheck::SurfaceProblem(result, closed);
  FUZZ_CHECK(problem.empty(), "a finite, oriented 2-manifold: " + problem);
  FUZZ_CHECK(result.EulerCharacteristic() == fuzzcheck::SurfaceEuler(given),
    "the Euler characteristic of the given surface: " +
      std::to_string(result.EulerCharacteristic()) +
      " != " + std::to_string(fuzzcheck::SurfaceEuler(given)));
  return 0;
}
