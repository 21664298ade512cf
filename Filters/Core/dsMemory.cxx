// SPDX-License-Identifier: BSD-3-Clause
#include "dsMemory.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace dsurf
{
double AvailableMemoryBytes()
{
  // MemAvailable counts the page cache the kernel would drop for us; the free pages alone
  // would refuse work that fits on any machine that has read a few files.
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line))
  {
    double kib = 0;
    if (std::sscanf(line.c_str(), "MemAvailable: %lf kB", &kib) == 1)
    {
      return kib * 1024.0;
    }
  }
#if defined(_SC_AVPHYS_PAGES) && defined(_SC_PAGESIZE)
  const long pages = sysconf(_SC_AVPHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  if (pages > 0 && size > 0)
  {
    return static_cast<double>(pages) * static_cast<double>(size);
  }
#endif
  return 0.0;
}

std::string MemoryShortfall(double bytes, const std::string& what, double available)
{
  if (available < 0)
  {
    available = AvailableMemoryBytes();
  }
  if (!(available > 0) || bytes <= available)
  {
    return std::string();
  }
  constexpr double GiB = 1024.0 * 1024.0 * 1024.0;
  std::ostringstream message;
  message.precision(3);
  message << what << " needs about " << bytes / GiB << " GiB, and only " << available / GiB
          << " GiB of memory are available: make the volume smaller first (crop it to the "
             "object with Extract Subset / vtkExtractVOI, or resample it with vtkImageResample)";
  return message.str();
}
} // namespace dsurf
