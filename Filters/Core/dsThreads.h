// SPDX-License-Identifier: BSD-3-Clause
// The number of threads the core uses: the one asked for, or the machine's (0 = all cores).
// Plain C++; the one place both the scale space and the solver take it from.
#ifndef dsThreads_h
#define dsThreads_h

#include <thread>

namespace dsurf
{
inline int ResolveThreads(int requested)
{
  if (requested > 0)
  {
    return requested;
  }
  const unsigned hc = std::thread::hardware_concurrency();
  return hc > 0 ? static_cast<int>(hc) : 1;
}
} // namespace dsurf

#endif
