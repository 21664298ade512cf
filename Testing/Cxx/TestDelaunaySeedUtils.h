// SPDX-License-Identifier: BSD-3-Clause
// Checks shared by the TestDelaunaySeed* tests: is a triangle surface closed, consistently
// and outward oriented, what is its Euler characteristic and volume. They live in
// DSSurfaceInvariants.h (the checks every surface-producing test uses); these names keep the
// seed tests short.
#ifndef TestDelaunaySeedUtils_h
#define TestDelaunaySeedUtils_h

#include "DSSurfaceInvariants.h"

namespace dsseedtest
{
using dstest::CheckClosedManifold;
using dstest::Measure;
using dstest::MessageCounter;
using dstest::SurfaceFacts;
} // namespace dsseedtest

#endif
