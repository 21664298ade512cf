// SPDX-License-Identifier: BSD-3-Clause
// The input read in its own type (dsImageView.h): a uint16 CT-like volume read in place gives
// exactly what its float copy gives (the same conversion, made as each value is read) in
// every reader -- the scale-space field, a box of the image, block means, trilinear samples,
// the region force's range, a whole solve -- and the filter gives the same surface for
// uint16, double, float and a non-contiguous (structure-of-arrays) uint16 array. IsConstant,
// the constant-image check, stops at the first other value.
#include "DSTestHelpers.h"
#include "TestSolverMeshes.h"

#include "dsFieldGrid.h"
#include "dsMultilevel.h"
#include "dsRegion.h"

#include "vtkDeformableSurfaceFilter.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSOADataArrayTemplate.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedShortArray.h"

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace dsurf;

namespace
{
constexpr int N = 40;

/// Background 1000, a ball of radius 10 at 2000 (its boundary voxels blended), noise s.d. 100.
std::vector<std::uint16_t> NoisyBall()
{
  std::vector<std::uint16_t> v(static_cast<std::size_t>(N) * N * N);
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 100.0);
  const double c = 0.5 * (N - 1);
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
      {
        const double d = std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c));
        const double inside = std::min(1.0, std::max(0.0, 10.5 - d));
        v[(static_cast<std::size_t>(k) * N + j) * N + i] =
          static_cast<std::uint16_t>(std::lround(1000.0 + 1000.0 * inside + noise(random)));
      }
  return v;
}

/// The largest |a - b| over two float arrays (infinite when their sizes differ).
double LargestDifference(const std::vector<float>& a, const std::vector<float>& b)
{
  if (a.size() != b.size())
  {
    return INFINITY;
  }
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    worst = std::max(worst, std::abs(static_cast<double>(a[i]) - b[i]));
  }
  return worst;
}

/// IsConstant: a constant image (NaN skipped) and its value; one other value anywhere is not.
void CheckConstant()
{
  ImageGeometry g;
  g.Dimensions[0] = g.Dimensions[1] = g.Dimensions[2] = 8;
  std::vector<float> v(512, 3.5f);
  v[0] = NAN;
  double value = 0;
  DS_CHECK(IsConstant(ImageView::Of(v.data(), g), value) && value == 3.5,
    "a constant image (one NaN skipped) and its value");
  v[511] = 3.25f;
  DS_CHECK(!IsConstant(ImageView::Of(v.data(), g), value), "the last voxel differs: not constant");
  std::fill(v.begin(), v.end(), NAN);
  DS_CHECK(!IsConstant(ImageView::Of(v.data(), g), value), "no number at all: not constant");
  const std::vector<std::uint16_t> u(512, 7);
  DS_CHECK(IsConstant(ImageView::Of(u.data(), g), value) && value == 7, "a constant uint16 image");
}

void CheckReaders(const ImageView& typed, const ImageView& asFloat)
{
  ScaleSpaceParameters p;
  p.Sigma = 2.0;
  ForceField a, b;
  std::string error;
  DS_CHECK(ComputeScaleSpaceForce(typed, p, a, &error), error);
  DS_CHECK(ComputeScaleSpaceForce(asFloat, p, b, &error), error);
  DS_CHECK(
    LargestDifference(a.Potential, b.Potential) == 0 && LargestDifference(a.Force, b.Force) == 0,
    "uint16 in place = its float copy: potential and force, bit for bit");

  VoxelBox box;
  for (int ax = 0; ax < 3; ++ax)
  {
    box.Begin[ax] = 5 + ax;
    box.End[ax] = 31 - ax;
  }
  DS_CHECK(ComputeForceAtScale(typed, box, p, a, &error), error);
  DS_CHECK(ComputeForceAtScale(asFloat, box, p, b, &error), error);
  DS_CHECK(a.Geometry.Dimensions[0] == 26 && LargestDifference(a.Force, b.Force) == 0,
    "a box of the image, read in place: the same field");
  const ImageView cut = typed.Box(box);
  const double x[3] = { 17.3, 12.6, 20.1 };
  bool in1 = false, in2 = false;
  DS_CHECK(SampleVolume(cut, x, &in1) == SampleVolume(asFloat, x, &in2) && in1 && in2,
    "a sample of the box's view = the image's at the same world point");

  std::vector<float> c1, c2;
  ImageGeometry g1, g2;
  BlockMeans(typed, 5, c1, g1, 2);
  BlockMeans(asFloat, 5, c2, g2, 2);
  DS_CHECK(LargestDifference(c1, c2) == 0, "block means of the uint16 view = of its float copy");

  const TriangleMesh sphere = dstest::MakeIcosphere(3, 13.0, Vec3{ 19.5, 19.5, 19.5 });
  RangeEstimate r1, r2;
  DS_CHECK(EstimateIntensityRange(typed, sphere, 1.0, r1, &error), error);
  DS_CHECK(EstimateIntensityRange(asFloat, sphere, 1.0, r2, &error), error);
  DS_CHECK(r1.Range[0] == r2.Range[0] && r1.Range[1] == r2.Range[1] && r1.Contrast,
    "the region force's range from the uint16 view = from its float copy");
  DS_CHECK(CountVoxelsInRange(typed, 1500, 2500) == CountVoxelsInRange(asFloat, 1500, 2500),
    "voxels in a range");
  // The solver's check that a range matches a voxel (it stops at the first).
  DS_CHECK(CountVoxelsInRange(typed, 1500, 2500) > 0 && AnyVoxelInRange(typed, 1500, 2500) &&
      AnyVoxelInRange(asFloat, 1500, 2500),
    "a range with voxels matches one, uint16 view and float copy");
  DS_CHECK(!AnyVoxelInRange(typed, 70000, 80000) && !AnyVoxelInRange(asFloat, 70000, 80000),
    "a range above every uint16 value matches none");

  MultilevelSolver s1, s2;
  TriangleMesh m1 = sphere, m2 = sphere;
  DS_CHECK(s1.Run(typed, m1, &error), error);
  DS_CHECK(s2.Run(asFloat, m2, &error), error);
  DS_CHECK(m1.Points == m2.Points && !m1.Points.empty(),
    "a whole solve (sigma_0 probe, region force) on the uint16 view = on its float copy");
}

/// The filter's output points on `array` (set as the image's scalars).
std::vector<double> Solve(vtkDataArray* array)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(N, N, N);
  array->SetName("CT");
  image->GetPointData()->SetScalars(array);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(19.5, 19.5, 19.5);
  sphere->SetRadius(13.0);
  vtkNew<vtkDeformableSurfaceFilter> filter;
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceConnection(sphere->GetOutputPort());
  filter->SetNumberOfThreads(2);
  filter->Update();
  std::vector<double> points;
  vtkPoints* p = filter->GetOutput()->GetPoints();
  for (vtkIdType i = 0; p && i < p->GetNumberOfPoints(); ++i)
  {
    const double* x = p->GetPoint(i);
    points.insert(points.end(), x, x + 3);
  }
  return points;
}

void CheckFilter(const std::vector<std::uint16_t>& values)
{
  const vtkIdType n = static_cast<vtkIdType>(values.size());
  vtkNew<vtkUnsignedShortArray> u16;
  vtkNew<vtkFloatArray> f32;
  vtkNew<vtkDoubleArray> f64;
  vtkNew<vtkSOADataArrayTemplate<unsigned short>> soa;
  for (auto* a : std::initializer_list<vtkDataArray*>{ u16, f32, f64, soa })
  {
    a->SetNumberOfTuples(n);
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    u16->SetValue(i, values[i]);
    f32->SetValue(i, values[i]);
    f64->SetValue(i, values[i]);
    soa->SetValue(i, values[i]);
  }
  const std::vector<double> reference = Solve(f32);
  DS_CHECK(reference.size() > 300, "the filter delivers a surface");
  DS_CHECK(Solve(u16) == reference, "the filter on uint16 = on float, bit for bit");
  DS_CHECK(Solve(f64) == reference, "the filter on double = on float, bit for bit");
  DS_CHECK(Solve(soa) == reference, "the filter on a structure-of-arrays uint16 array (copied)");
}
} // namespace

int TestImageView(int, char*[])
{
  const std::vector<std::uint16_t> values = NoisyBall();
  const std::vector<float> copy(values.begin(), values.end());
  ImageGeometry g;
  g.Dimensions[0] = g.Dimensions[1] = g.Dimensions[2] = N;
  CheckConstant();
  CheckReaders(ImageView::Of(values.data(), g), ImageView::Of(copy.data(), g));
  CheckFilter(values);
  return dstest::Result("TestImageView");
}

int main(int argc, char* argv[])
{
  return TestImageView(argc, argv);
}
