// SPDX-License-Identifier: BSD-3-Clause
// What the object benchmarks (BenchObjects, BenchSeveralObjects, BenchNearFace) share: the Colin27
// cases' reading (Colin27Cases.h) and choosing cases by name.
#ifndef BenchCases_h
#define BenchCases_h

#include "../Cxx/Colin27Cases.h"

#include <string>
#include <vector>

namespace dsobjects
{
/// Whether the case `name` is asked for: no filters, or one that is part of the name.
inline bool Wanted(const std::vector<std::string>& filters, const std::string& name)
{
  if (filters.empty())
    return true;
  for (const std::string& f : filters)
    if (name.find(f) != std::string::npos)
      return true;
  return false;
}
} // namespace dsobjects

#endif
