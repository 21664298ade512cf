// SPDX-License-Identifier: BSD-3-Clause
// The self-intersection rule of docs/METHOD.md §5 (paper §5): the external force is not
// normal to the surface and could fold it, so only its projection onto one direction is
// applied: onto the umbrella vector U(p) when F . U > 0, otherwise onto the vertex normal.
// Moving only along the normal everywhere grows pockets near steep slopes; moving along
// the umbrella when F . U <= 0 makes existing anomalies worse. The count of intersecting
// triangle pairs that remain (reported, not prevented) is dsSelfIntersectionCount.h.
#ifndef dsSelfIntersectionRule_h
#define dsSelfIntersectionRule_h

#include "dsTriangleMesh.h"

namespace dsurf
{
/// The force applied at a vertex by the docs/METHOD.md §5 rule: the projection of `force`
/// onto `umbrella` when they point the same way (F . U > 0), else onto the normal that
/// `normal()` returns (any length; called only then, the normal costs a fan of cross
/// products). Zero when that normal is zero.
template <class NormalFunction>
inline Vec3 SelfIntersectionRule(
  const Vec3& force, const Vec3& umbrella, const NormalFunction& normal)
{
  const double fu = Dot(force, umbrella);
  if (fu > 0)
  {
    return (fu / Dot(umbrella, umbrella)) * umbrella;
  }
  const Vec3 n = normal();
  const double nn = Dot(n, n);
  if (nn > 0)
  {
    return (Dot(force, n) / nn) * n;
  }
  return { 0, 0, 0 };
}

/// The same with the normal given.
inline Vec3 SelfIntersectionRule(const Vec3& force, const Vec3& umbrella, const Vec3& normal)
{
  return SelfIntersectionRule(force, umbrella, [&normal]() { return normal; });
}
} // namespace dsurf

#endif
