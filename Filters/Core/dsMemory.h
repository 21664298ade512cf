// SPDX-License-Identifier: BSD-3-Clause
// What the machine can still give, so that a volume too large for it is refused with a message
// before anything is allocated, instead of the process being killed part-way (docs/METHOD.md §9).
// Plain C++.
#ifndef dsMemory_h
#define dsMemory_h

#include "DeformableSurfaceFiltersModule.h"

#include <string>

namespace dsurf
{
/// Bytes the system can give without swapping: MemAvailable of /proc/meminfo on Linux, the
/// free physical pages elsewhere; 0 when it cannot be told (then nothing is refused).
DEFORMABLESURFACEFILTERS_EXPORT double AvailableMemoryBytes();

/// Empty when `bytes` fit in `available` (AvailableMemoryBytes() when negative; an unknown
/// 0 always fits). Otherwise a user-facing message: `what` needs about so many GiB, so many are
/// available, and how to make the volume smaller.
DEFORMABLESURFACEFILTERS_EXPORT std::string MemoryShortfall(
  double bytes, const std::string& what, double available = -1.0);
} // namespace dsurf

#endif
