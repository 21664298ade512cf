// SPDX-License-Identifier: BSD-3-Clause
// End to end: picked points -> vtkDelaunaySeedSurface -> vtkDeformableSurfaceFilter.
//
// 1. Torus phantom 128^3 (R = 32, r = 12.8 voxels, a one-voxel partial-volume ramp so the
//    edge sits on the true surface). A user picks 40 points on its boundary on four slices
//    through the torus axis (every 45 degrees, so 8 tube cross-sections, 5 picks on each, a
//    little jitter, just inside the visible edge). The Delaunay complex fills the hole; the
//    image (IntensityRange) removes the hole's tetrahedra; TargetEdgeLength gives a few
//    thousand vertices. The deformed surface must lie on the torus: mean |distance| <= 0.3
//    voxel, genus 1 (closed, manifold, Euler characteristic 0), no self-intersections.
// 2. The torus from picks 3 voxels outside its tube, every default (sigma_0 follows the start;
//    the region force estimates its range from the seed).
// 3. Two objects in one volume (a ball and a cube), picks around the ball only: only the ball
//    is extracted (every vertex within 1 voxel of the ball's boundary, none near the cube).
#include "TestDelaunaySeedUtils.h"
#include "vtkDeformableSurfaceFilter.h"
#include "vtkDelaunaySeedSurface.h"

#include "vtkCell.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>

namespace
{
const int N = 128;
const double centre[3] = { 64.0, 64.0, 64.0 };
const double R = 32.0, r = 12.8;

// Deterministic jitter in [-0.5, 0.5).
double Jitter(std::uint32_t& state)
{
  state = state * 1664525u + 1013904223u;
  return (state >> 8) / double(1u << 24) - 0.5;
}

double TorusSignedDistance(const double x[3])
{
  const double dx = x[0] - centre[0], dy = x[1] - centre[1], dz = x[2] - centre[2];
  const double rho = std::sqrt(dx * dx + dy * dy);
  return std::sqrt((rho - R) * (rho - R) + dz * dz) - r;
}

/// Value 1 inside, 0 outside, linear over one voxel across the surface (partial volume).
vtkSmartPointer<vtkImageData> Phantom(const std::function<double(const double*)>& signedDistance)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(N, N, N);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(static_cast<vtkIdType>(N) * N * N);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    double x[3];
    image->GetPoint(i, x);
    values->SetValue(i, static_cast<float>(std::min(1.0, std::max(0.0, 0.5 - signedDistance(x)))));
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

struct Deformed
{
  vtkSmartPointer<vtkPolyData> Surface;
  int Sweeps = 0;
  int SelfIntersections = -1;
  double Seconds = 0;
};

Deformed Deform(vtkImageData* image, vtkPolyData* seed)
{
  vtkNew<vtkDeformableSurfaceFilter> filter;
  vtkNew<dsseedtest::MessageCounter> messages;
  filter->AddObserver(vtkCommand::ErrorEvent, messages);
  filter->SetInputData(0, image);
  filter->SetInitialSurfaceData(seed);
  filter->SetSigma(2.0);
  filter->SetMaxLevels(0); // single level, constant sigma, also once the hierarchy exists
  filter->SetMaxSweepsPerLevel(3000);
  filter->SetConvergenceTolerance(1e-4);
  const auto t0 = std::chrono::steady_clock::now();
  dstest::UpdateAndCheckSurface(filter, "deformable surface from the seed");
  Deformed d;
  d.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  d.Surface = filter->GetOutput();
  DS_CHECK(messages->Errors == 0, "deformable surface: no errors");
  vtkFieldData* fd = d.Surface->GetFieldData();
  if (fd->GetArray("Sweeps") && fd->GetArray("SelfIntersections"))
  {
    d.Sweeps = static_cast<int>(fd->GetArray("Sweeps")->GetTuple1(0));
    d.SelfIntersections = static_cast<int>(fd->GetArray("SelfIntersections")->GetTuple1(0));
  }
  std::cout << "  deformed: " << d.Surface->GetNumberOfPoints() << " vertices, " << d.Sweeps
            << " sweeps, " << d.Seconds << " s, " << d.SelfIntersections << " self-intersections"
            << std::endl;
  return d;
}

struct DistanceStats
{
  double Mean = 0, Max = 0, MeanSigned = 0;
};

DistanceStats Distances(
  vtkPolyData* surface, const std::function<double(const double*)>& signedDistance)
{
  DistanceStats s;
  const vtkIdType n = surface->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double x[3];
    surface->GetPoint(i, x);
    const double d = signedDistance(x);
    s.Mean += std::abs(d);
    s.MeanSigned += d;
    s.Max = std::max(s.Max, std::abs(d));
  }
  s.Mean /= std::max<vtkIdType>(n, 1);
  s.MeanSigned /= std::max<vtkIdType>(n, 1);
  return s;
}

void TorusCase()
{
  std::cout << "Torus R = " << R << ", r = " << r << " voxels, 128^3:" << std::endl;
  auto image = Phantom(TorusSignedDistance);

  // Four slices through the axis, every 45 degrees: 8 cross-sections of the tube, 5 picks
  // each (rotated from section to section, as a user would not pick the same angles), 0.3
  // voxel inside the edge with +-0.25 voxel jitter.
  vtkNew<vtkPoints> picks;
  std::uint32_t state = 2024u;
  for (int section = 0; section < 8; ++section)
  {
    const double u = 2.0 * vtkMath::Pi() * section / 8 + 0.02 * Jitter(state);
    for (int k = 0; k < 5; ++k)
    {
      const double v = 2.0 * vtkMath::Pi() * (k + 0.5 * (section % 2) + 0.2 * Jitter(state)) / 5;
      const double rr = r - 0.3 + 0.5 * Jitter(state);
      picks->InsertNextPoint(centre[0] + (R + rr * std::cos(v)) * std::cos(u),
        centre[1] + (R + rr * std::cos(v)) * std::sin(u), centre[2] + rr * std::sin(v));
    }
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(picks);

  vtkNew<vtkDelaunaySeedSurface> seed;
  vtkNew<dsseedtest::MessageCounter> messages;
  seed->AddObserver(vtkCommand::ErrorEvent, messages);
  seed->AddObserver(vtkCommand::WarningEvent, messages);
  seed->SetInputData(cloud);
  seed->SetImageData(image);
  seed->UseIntensityRangeOn();
  seed->SetIntensityRange(0.5, 10.0); // keep tetrahedra whose centroid is inside the object
  seed->SetTargetEdgeLength(2.5);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  std::cout << "  " << picks->GetNumberOfPoints() << " picks; seed:" << std::endl;
  const auto seedFacts = dsseedtest::Measure(seed->GetOutput());
  dsseedtest::CheckClosedManifold(seedFacts, seed->GetOutput()->GetNumberOfPoints(), 0);
  const DistanceStats before = Distances(seed->GetOutput(), TorusSignedDistance);
  std::cout << "  seed distance to the torus: mean |d| " << before.Mean << ", max " << before.Max
            << std::endl;
  DS_CHECK(messages->Errors == 0, "seed: no errors");
  DS_CHECK_GE(seed->GetOutput()->GetNumberOfPoints(), 1000, "seed vertices after TargetEdgeLength");

  const Deformed result = Deform(image, seed->GetOutput());
  const auto facts = dsseedtest::Measure(result.Surface);
  dsseedtest::CheckClosedManifold(facts, result.Surface->GetNumberOfPoints(), 0);
  const DistanceStats after = Distances(result.Surface, TorusSignedDistance);
  std::cout << "  distance to the torus: mean |d| " << after.Mean << " voxel, max " << after.Max
            << ", mean signed " << after.MeanSigned << std::endl;
  DS_CHECK_LE(after.Mean, 0.3, "torus: mean |distance| to the true torus (voxels)");
  DS_CHECK_LE(after.Max, 1.5, "torus: max |distance| to the true torus (voxels)");
  DS_CHECK(result.SelfIntersections == 0, "torus: 0 self-intersections");
}

// The torus from close picks with the defaults (issue: the paper's first sigma, 1/6 of the
// extent, spans the hole): 96 picks 3 voxels outside the tube on six slices through the axis
// (12 cross-sections of 8 picks, +-0.5 voxel jitter); the user deletes the tetrahedra lying in
// the hole (their centroid inside the hole's cylinder, as seen on the slices). Deformable
// Surface with every default must keep the hole and land on the tube; the paper's sigma_0 for
// comparison does not.
void TorusClosePicksCase()
{
  std::cout << "Torus from picks 3 voxels outside the tube, defaults:" << std::endl;
  auto image = Phantom(TorusSignedDistance);
  vtkNew<vtkPoints> picks;
  std::uint32_t state = 99u;
  for (int plane = 0; plane < 6; ++plane)
  {
    const double u = vtkMath::Pi() * plane / 6;
    for (int side : { 1, -1 })
    {
      for (int k = 0; k < 8; ++k)
      {
        const double v = 2.0 * vtkMath::Pi() * (k + 0.5 * (side > 0)) / 8, rr = r + 3.0;
        const double rho = R + rr * std::cos(v);
        // Drawn in sequence (z, y, x: the order gcc evaluated the arguments in, so the picks
        // stay the same): the order of a call's arguments is unspecified, and clang took the
        // other one, giving other picks.
        const double jz = Jitter(state), jy = Jitter(state), jx = Jitter(state);
        picks->InsertNextPoint(centre[0] + side * rho * std::cos(u) + jx,
          centre[1] + side * rho * std::sin(u) + jy, centre[2] + rr * std::sin(v) + jz);
      }
    }
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(picks);
  vtkNew<vtkDelaunaySeedSurface> seed;
  seed->SetInputData(cloud);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  vtkUnstructuredGrid* tets = seed->GetTetrahedra();
  vtkDataArray* ids = tets->GetCellData()->GetArray("TetraId");
  for (vtkIdType t = 0; t < tets->GetNumberOfCells(); ++t)
  {
    double c[3] = { 0, 0, 0 };
    vtkIdList* corners = tets->GetCell(t)->GetPointIds();
    for (vtkIdType k = 0; k < corners->GetNumberOfIds(); ++k)
    {
      double p[3];
      tets->GetPoint(corners->GetId(k), p);
      for (int d = 0; d < 3; ++d)
      {
        c[d] += 0.25 * p[d];
      }
    }
    if (std::hypot(c[0] - centre[0], c[1] - centre[1]) < R - r)
    {
      seed->AddRemovedTetrahedron(static_cast<vtkIdType>(ids->GetTuple1(t)));
    }
  }
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  const auto seedFacts = dsseedtest::Measure(seed->GetOutput());
  DS_CHECK(seedFacts.Euler == 0, "close picks: the seed has the torus's genus");
  const DistanceStats before = Distances(seed->GetOutput(), TorusSignedDistance);
  std::cout << "  " << picks->GetNumberOfPoints() << " picks; seed mean |d| " << before.Mean
            << std::endl;

  for (const bool paper : { false, true })
  {
    vtkNew<vtkDeformableSurfaceFilter> filter;
    filter->SetInputData(0, image);
    filter->SetInitialSurfaceConnection(seed->GetOutputPort());
    if (paper)
    {
      // The paper's method: sigma_0 = extent / 6 and the edge force alone.
      filter->SetSigmaFraction(1.0 / 6.0);
      filter->SetRegionWeight(0.0);
    }
    // The paper's sigma_0 is the failure this case shows: it spans the hole, and the inner
    // wall it squeezes folds (how far depends on the compiler's rounding: gcc -O3 squeezes the
    // torus below half a voxel of volume at its second level, which fails the run as a
    // collapse; before that check it ended 3.6 voxels off with ~600 intersecting pairs; clang
    // -O1 0.83 voxel with 4), so only its inputs and failure are checked; the defaults must keep
    // every invariant.
    if (paper)
    {
      vtkNew<dstest::MessageCounter> messages;
      messages->Watch(filter);
      dstest::UpdateWithInputsUnchanged(filter, "close picks, the paper's sigma_0");
      if (filter->GetOutput()->GetNumberOfPoints() == 0)
      {
        // Squeezed flat (gcc -O3: under half a voxel enclosed at its second level), the run
        // fails as a collapse rather than deliver the folded surface.
        DS_CHECK(
          messages->Errors == 1 && messages->ErrorText.find("collapsed") != std::string::npos,
          "close picks, the paper's sigma_0: refused as a collapse");
        continue;
      }
    }
    else
    {
      dstest::UpdateAndCheckSurface(filter, "close picks, defaults");
    }
    vtkPolyData* out = filter->GetOutput();
    const auto facts = dsseedtest::Measure(out);
    const DistanceStats after = Distances(out, TorusSignedDistance);
    const double sigma0 = out->GetFieldData()->GetArray("InitialSigma")->GetTuple1(0);
    const int selfx =
      static_cast<int>(out->GetFieldData()->GetArray("SelfIntersections")->GetTuple1(0));
    std::cout << "  " << (paper ? "paper's sigma_0: " : "defaults: ") << "sigma_0 " << sigma0
              << ", mean |d| " << after.Mean << ", max " << after.Max << ", Euler " << facts.Euler
              << ", " << selfx << " self-intersections" << std::endl;
    if (!paper)
    {
      // The default region force is on for a start that does not span the image: the range it
      // estimated is in the field data.
      vtkDataArray* range = out->GetFieldData()->GetArray("IntensityRange");
      DS_CHECK(range != nullptr, "close picks, defaults: the region force estimated a range");
      if (range)
      {
        std::cout << "  region force range [" << range->GetComponent(0, 0) << ", "
                  << range->GetComponent(0, 1) << "]" << std::endl;
        DS_CHECK_LE(std::abs(range->GetComponent(0, 0) - 0.5), 0.05,
          "close picks: range low end at the half level");
      }
      DS_CHECK_LE(after.Mean, 0.3, "close picks, defaults: mean |distance| to the torus (voxels)");
      DS_CHECK(facts.Euler == 0, "close picks, defaults: Euler characteristic 0 (the hole kept)");
      DS_CHECK(selfx == 0, "close picks, defaults: 0 self-intersections");
      DS_CHECK_LE(sigma0, 8.0, "close picks: sigma_0 follows the start (voxels)");
    }
    else
    {
      // At least ten times the defaults' distance (0.03-0.05 voxel).
      DS_CHECK_GE(
        after.Mean, 0.5, "close picks, the paper's sigma_0: spans the hole (mean |d| voxels)");
    }
  }
}

void TwoObjectsCase()
{
  const double ballCentre[3] = { 42.0, 64.0, 64.0 }, ballRadius = 16.0;
  const double cubeCentre[3] = { 92.0, 63.0, 65.0 },
               cubeHalf = 14.0; // faces 18 voxels from the ball
  auto ballDistance = [&](const double* x)
  { return std::sqrt(vtkMath::Distance2BetweenPoints(x, ballCentre)) - ballRadius; };
  auto cubeDistance = [&](const double* x)
  {
    double outside = 0, inside = -1e300;
    for (int d = 0; d < 3; ++d)
    {
      const double q = std::abs(x[d] - cubeCentre[d]) - cubeHalf;
      outside += q > 0 ? q * q : 0;
      inside = std::max(inside, q);
    }
    return outside > 0 ? std::sqrt(outside) : inside;
  };
  std::cout << "Ball (radius " << ballRadius << ") and cube (half side " << cubeHalf
            << "), picks around the ball:" << std::endl;
  auto image = Phantom([&](const double* x) { return std::min(ballDistance(x), cubeDistance(x)); });

  // 24 picks roughly around the ball, 2-4 voxels outside it (Fibonacci sphere, jittered).
  vtkNew<vtkPoints> picks;
  std::uint32_t state = 77u;
  const int n = 24;
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - (2.0 * i + 1.0) / n, rho = std::sqrt(1.0 - z * z);
    const double phi = i * vtkMath::Pi() * (3.0 - std::sqrt(5.0));
    const double rr = ballRadius + 3.0 + 2.0 * Jitter(state);
    picks->InsertNextPoint(ballCentre[0] + rr * rho * std::cos(phi),
      ballCentre[1] + rr * rho * std::sin(phi), ballCentre[2] + rr * z);
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(picks);
  vtkNew<vtkDelaunaySeedSurface> seed;
  seed->SetInputData(cloud);
  seed->SetTargetEdgeLength(2.5);
  dstest::UpdateWithInputsUnchanged(seed, "seed");
  const auto seedFacts = dsseedtest::Measure(seed->GetOutput());
  dsseedtest::CheckClosedManifold(seedFacts, seed->GetOutput()->GetNumberOfPoints(), 2);

  const Deformed result = Deform(image, seed->GetOutput());
  const auto facts = dsseedtest::Measure(result.Surface);
  dsseedtest::CheckClosedManifold(facts, result.Surface->GetNumberOfPoints(), 2);
  const DistanceStats toBall = Distances(result.Surface, ballDistance);
  double nearestToCube = 1e300, centroid[3] = { 0, 0, 0 };
  const vtkIdType nv = result.Surface->GetNumberOfPoints();
  for (vtkIdType i = 0; i < nv; ++i)
  {
    double x[3];
    result.Surface->GetPoint(i, x);
    nearestToCube = std::min(nearestToCube, cubeDistance(x));
    for (int d = 0; d < 3; ++d)
    {
      centroid[d] += x[d] / std::max<vtkIdType>(nv, 1);
    }
  }
  const double centroidOff = std::sqrt(vtkMath::Distance2BetweenPoints(centroid, ballCentre));
  std::cout << "  distance to the ball: mean |d| " << toBall.Mean << ", max " << toBall.Max
            << "; centroid " << centroidOff
            << " voxel from the ball centre; nearest vertex to the cube " << nearestToCube
            << " voxels" << std::endl;
  DS_CHECK_LE(toBall.Max, 1.0, "two objects: every vertex within 1 voxel of the ball's boundary");
  DS_CHECK_LE(centroidOff, 0.5, "two objects: vertex centroid at the ball centre (voxels)");
  DS_CHECK_GE(nearestToCube, 10.0, "two objects: no vertex near the cube (voxels)");
  DS_CHECK(result.SelfIntersections == 0, "two objects: 0 self-intersections");
}
} // namespace

int main()
{
  const auto t0 = std::chrono::steady_clock::now();
  TorusCase();
  TorusClosePicksCase();
  TwoObjectsCase();
  std::cout << "total "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s"
            << std::endl;
  return dstest::Result("TestDelaunaySeedEndToEnd");
}
