// SPDX-License-Identifier: BSD-3-Clause
// Unit test of the contact bounds (dsContact.h): steps that would carry triangles through each
// other, shortened by ContactStepScale within the bounds ContactLimiter makes every few sweeps,
// never do, while the surfaces come as near as the clearance allows.
// - ContactStepScale on a ball and a plane by hand;
// - two balls 0.5 apart, each pushed toward the other with jitter, as two objects and as one
//   kept off itself (the two sides of a gap a surface grows around): no crossing pair, no two
//   triangles nearer than the clearance, and they close in to within three clearances; without
//   the bounds they pass into each other (the test can fail).
#include "DSTestHelpers.h"
#include "TestSolverMeshes.h"

#include "dsContact.h"
#include "dsSelfIntersectionCount.h"
#include "dsTriangleDistance.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace dsurf;

namespace
{
constexpr double Clearance = 0.1;

/// The least distance between a triangle of the first `split` points and one of the rest, by
/// brute force.
double LeastGap(const TriangleMesh& mesh, int split)
{
  double least = std::numeric_limits<double>::infinity();
  const auto& p = mesh.Points;
  for (const auto& a : mesh.Triangles)
  {
    for (const auto& b : mesh.Triangles)
    {
      if (a[0] < split && b[0] >= split)
      {
        least =
          std::min(least, TriangleDistance(p[a[0]], p[a[1]], p[a[2]], p[b[0]], p[b[1]], p[b[2]]));
      }
    }
  }
  return least;
}

/// Sweeps of `push` (a step per vertex, jittered) in batches of four, each batch within the
/// bounds made before it (or none: `bounded` false). Vertices move one after the other, as the
/// solver's do.
void Press(
  TriangleMesh& mesh, bool self, bool bounded, int sweeps, const std::function<Vec3(int)>& push)
{
  ContactLimiter limiter;
  ContactBounds bounds;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  const double budget = 8 * 0.2;
  for (int sweep = 0; sweep < sweeps; ++sweep)
  {
    if (bounded && sweep % 4 == 0)
    {
      limiter.Limits(mesh, Clearance, budget, self, bounds);
    }
    for (int v = 0; v < mesh.NumberOfPoints(); ++v)
    {
      const Vec3 step = push(v) + Vec3{ jitter(random), jitter(random), jitter(random) };
      const double scale = bounded ? ContactStepScale(bounds, v, mesh.Points[v], step) : 1.0;
      mesh.Points[v] = mesh.Points[v] + scale * step;
    }
  }
}

void TestScaleByHand()
{
  ContactBounds b;
  b.Anchors = { Vec3{ 0, 0, 0 } };
  b.Radii = { 1.0 };
  b.Offsets = { 0, 1 };
  b.Normals = { Vec3{ 0, 0, 1 } };
  b.Limits = { 0.25 };
  const Vec3 here{ 0, 0, 0 };
  DS_CHECK(std::abs(ContactStepScale(b, 0, here, Vec3{ 2, 0, 0 }) - 0.5) < 1e-12,
    "the ball halves a step of 2");
  DS_CHECK(std::abs(ContactStepScale(b, 0, here, Vec3{ 0, 0, 1 }) - 0.25) < 1e-12,
    "the plane at 0.25 quarters a step of 1 along its normal");
  DS_CHECK(ContactStepScale(b, 0, here, Vec3{ 0, 0, -0.5 }) == 1.0,
    "a step away from the plane, inside the ball, is whole");
  DS_CHECK(ContactStepScale(b, 0, Vec3{ 0, 0, 0.25 }, Vec3{ 0.1, 0, 0.1 }) == 0.0,
    "a vertex on its plane does not step across it");
}

/// Two balls of radius 1, 0.5 apart, one `object` each or both of object 0.
TriangleMesh TwoBalls(bool oneObject)
{
  TriangleMesh a = dstest::MakeIcosphere(2, 1.0, Vec3{ -1.25, 0, 0 });
  TriangleMesh b = dstest::MakeIcosphere(2, 1.0, Vec3{ 1.25, 0, 0 });
  const int na = a.NumberOfPoints();
  TriangleMesh mesh = a;
  for (const Vec3& p : b.Points)
  {
    mesh.Points.push_back(p);
  }
  for (auto t : b.Triangles)
  {
    mesh.Triangles.push_back({ t[0] + na, t[1] + na, t[2] + na });
  }
  mesh.Objects.assign(mesh.NumberOfPoints(), 0);
  std::fill(mesh.Objects.begin() + na, mesh.Objects.end(), oneObject ? 0 : 1);
  DS_CHECK(mesh.BuildTopology(nullptr), "the mesh is valid");
  return mesh;
}

/// Each ball pushed toward the other for eight sweeps of 0.2 (they would overlap by 1.1).
void TestTwoBalls(bool oneObject)
{
  const std::string which = oneObject ? "one object, kept off itself: " : "two objects: ";
  TriangleMesh mesh = TwoBalls(oneObject);
  const int na = mesh.NumberOfPoints() / 2;
  const auto push = [&](int v) { return Vec3{ v < na ? 0.2 : -0.2, 0, 0 }; };
  const auto crossing = [&](const TriangleMesh& m)
  { return oneObject ? CountSelfIntersections(m) : CountCrossingPairs(m); };
  TriangleMesh free = mesh;
  Press(free, oneObject, false, 8, push);
  DS_CHECK(crossing(free) > 0, which + "without the bounds the balls pass into each other");
  Press(mesh, oneObject, true, 8, push);
  const double gap = LeastGap(mesh, na);
  DS_CHECK(crossing(mesh) == 0, which + "no pair of triangles crosses");
  DS_CHECK_GE(gap, Clearance * (1 - 1e-9), which + "the balls' least distance (the clearance)");
  DS_CHECK_LE(gap, 3 * Clearance, which + "the balls' least distance: they met");
}
} // namespace

int main()
{
  TestScaleByHand();
  TestTwoBalls(false);
  TestTwoBalls(true);
  return dstest::Result("TestContactBounds");
}
