// SPDX-License-Identifier: BSD-3-Clause
// Unit test of the docs/METHOD.md §5 self-intersection rule (dsSelfIntersectionRule.h): the
// applied force is the projection of F onto the umbrella U when F . U > 0, else onto the
// normal n; hand-computed cases, the normal only evaluated when needed, a zero normal, and
// on 1000 random cases the projection properties (the result is parallel to U or n, the
// remainder F - result is orthogonal to it, so |result| <= |F|).
#include "DSTestHelpers.h"

#include "dsSelfIntersectionRule.h"

#include <random>
#include <string>

using namespace dsurf;

namespace
{
double Distance(const Vec3& a, const Vec3& b)
{
  return Norm(a - b);
}

void CheckVector(const Vec3& got, const Vec3& want, const std::string& what)
{
  DS_CHECK(Distance(got, want) <= 1e-14,
    what + ": got (" + std::to_string(got[0]) + ", " + std::to_string(got[1]) + ", " +
      std::to_string(got[2]) + ")");
}
} // namespace

int TestSelfIntersectionRule(int, char*[])
{
  // F . U = 4 > 0: along U, the tangential x part dropped.
  CheckVector(
    SelfIntersectionRule({ 1, 2, 0 }, { 0, 2, 0 }, Vec3{ 0, 0, 1 }), { 0, 2, 0 }, "F.U > 0");
  // F . U = -4 < 0: along n = (0, 1, 1): (F . n / n . n) n = (-2 / 2) n.
  CheckVector(
    SelfIntersectionRule({ 1, -2, 0 }, { 0, 2, 0 }, Vec3{ 0, 1, 1 }), { 0, -1, -1 }, "F.U < 0");
  // F . U = 0 counts as not positive: along n.
  CheckVector(
    SelfIntersectionRule({ 1, 0, 0 }, { 0, 1, 0 }, Vec3{ 2, 0, 0 }), { 1, 0, 0 }, "F.U = 0");
  // The normal's length does not matter.
  CheckVector(SelfIntersectionRule({ 0.3, -0.7, 0.2 }, { 0, 1, 0 }, Vec3{ 5, 5, 0 }),
    SelfIntersectionRule({ 0.3, -0.7, 0.2 }, { 0, 1, 0 }, Vec3{ 1, 1, 0 }), "normal length");
  // No normal (a degenerate fan) and F . U <= 0: nothing is applied.
  CheckVector(
    SelfIntersectionRule({ 1, -2, 3 }, { 0, 2, 0 }, Vec3{ 0, 0, 0 }), { 0, 0, 0 }, "zero normal");
  // No force: nothing is applied.
  CheckVector(
    SelfIntersectionRule({ 0, 0, 0 }, { 0, 2, 0 }, Vec3{ 0, 0, 1 }), { 0, 0, 0 }, "zero force");

  // The normal is computed only when the umbrella does not take the force.
  int normalCalls = 0;
  const auto countingNormal = [&normalCalls]()
  {
    ++normalCalls;
    return Vec3{ 0, 0, 1 };
  };
  SelfIntersectionRule({ 1, 2, 0 }, { 0, 2, 0 }, countingNormal);
  DS_CHECK(normalCalls == 0, "normal evaluated although F.U > 0");
  SelfIntersectionRule({ 1, -2, 0 }, { 0, 2, 0 }, countingNormal);
  DS_CHECK(
    normalCalls == 1, "normal not evaluated once for F.U < 0: " + std::to_string(normalCalls));

  // Projection properties on random cases.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const auto random = [&]() { return Vec3{ uni(rng), uni(rng), uni(rng) }; };
  int notParallel = 0, notOrthogonal = 0, longer = 0, alongUmbrella = 0;
  for (int i = 0; i < 1000; ++i)
  {
    const Vec3 f = random(), u = random(), n = random();
    const Vec3 applied = SelfIntersectionRule(f, u, n);
    const Vec3 dir = Dot(f, u) > 0 ? u : n;
    alongUmbrella += Dot(f, u) > 0 ? 1 : 0;
    notParallel += Norm(Cross(applied, dir)) <= 1e-12 * Norm(dir) * (Norm(applied) + 1) ? 0 : 1;
    notOrthogonal += std::abs(Dot(f - applied, dir)) <= 1e-12 * Norm(dir) ? 0 : 1;
    longer += Norm(applied) <= Norm(f) * (1 + 1e-12) ? 0 : 1;
  }
  std::cout << "  random cases along the umbrella: " << alongUmbrella << " of 1000" << std::endl;
  DS_CHECK(alongUmbrella > 300 && alongUmbrella < 700, "random cases should take both branches");
  DS_CHECK(notParallel == 0, std::to_string(notParallel) + " results not parallel to U or n");
  DS_CHECK(
    notOrthogonal == 0, std::to_string(notOrthogonal) + " remainders not orthogonal to U or n");
  DS_CHECK(longer == 0, std::to_string(longer) + " results longer than F");
  return dstest::Result("TestSelfIntersectionRule");
}

int main(int argc, char* argv[])
{
  return TestSelfIntersectionRule(argc, argv);
}
