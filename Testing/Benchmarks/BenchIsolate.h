// SPDX-License-Identifier: BSD-3-Clause
// One benchmark case in a child process of its own, so that each case's memory high-water mark
// (getrusage of the child: VmHWM) is its own, and a case that runs over its time budget is
// stopped instead of holding the whole run. The budget is CPU time (all the child's threads),
// not wall time, so that a case is run or skipped alike on a quiet and on a shared machine. The
// child writes one line of results to a pipe. Memory estimates are made before a case starts: a
// case whose estimate does not fit is never started (a system without swap would otherwise OOM-kill
// it, or a neighbour), nor one whose time estimate exceeds its time limit.
#ifndef BenchIsolate_h
#define BenchIsolate_h

#include "dsMemory.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <thread>

namespace dsbench
{
constexpr double GiB = 1024.0 * 1024.0 * 1024.0;

struct IsolatedResult
{
  bool Ok = false;       ///< the child exited 0 and wrote its line
  bool TimedOut = false; ///< killed after the time limit
  std::string Line;      ///< what the child wrote (its result, or its error message)
  double PeakBytes = 0;  ///< the child's maximum resident set size
  double WallSeconds = 0;
  double CpuSeconds = 0; ///< user + system time of the child, all threads
  std::string Status;    ///< how the child ended, for a failed case
};

/// CPU seconds (user + system, all threads) a running process has used so far; 0 if unknown.
/// Read with C stdio: the process may be reaped while its /proc file is read, and a read error
/// there makes libstdc++'s filebuf throw (which ended a run with std::terminate).
inline double ProcessCpuSeconds(pid_t pid)
{
  std::string stat;
  if (FILE* in = std::fopen(("/proc/" + std::to_string(pid) + "/stat").c_str(), "r"))
  {
    char chunk[512];
    size_t got;
    while ((got = std::fread(chunk, 1, sizeof chunk, in)) > 0)
      stat.append(chunk, got);
    std::fclose(in);
  }
  const size_t close = stat.rfind(')'); // the command name may hold spaces
  if (close == std::string::npos)
    return 0;
  std::istringstream fields(stat.substr(close + 2));
  std::string skip;
  for (int f = 3; f < 14; ++f) // fields 3..13, then utime (14) and stime (15)
    fields >> skip;
  double utime = 0, stime = 0;
  fields >> utime >> stime;
  return (utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

/// Runs work() in a forked child; its return value is the result line. The child is killed
/// when it has used cpuLimitSeconds of CPU (or after ten times that in wall time). The parent must
/// not have started threads (fork copies only the calling thread): call this from main() only.
inline IsolatedResult RunIsolated(const std::function<std::string()>& work, double cpuLimitSeconds)
{
  IsolatedResult r;
  int fds[2];
  if (pipe(fds) != 0)
  {
    r.Status = std::string("pipe: ") + std::strerror(errno);
    return r;
  }
  std::fflush(stdout);
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0)
  {
    close(fds[0]);
    const std::string line = work();
    ssize_t off = 0;
    while (off < static_cast<ssize_t>(line.size()))
    {
      const ssize_t w = write(fds[1], line.data() + off, line.size() - off);
      if (w <= 0)
        break;
      off += w;
    }
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  if (pid < 0)
  {
    close(fds[0]);
    r.Status = std::string("fork: ") + std::strerror(errno);
    return r;
  }
  // Read until the child closes the pipe (it ends or dies); a watchdog kills it at the limit.
  std::atomic<bool> done{ false };
  std::thread watchdog(
    [&]
    {
      // A child that waits instead of computing (a hang) uses no CPU: a wall limit of ten
      // times the CPU limit stops it too.
      const auto wallLimit = t0 + std::chrono::duration<double>(10 * cpuLimitSeconds);
      while (!done && ProcessCpuSeconds(pid) < cpuLimitSeconds &&
        std::chrono::steady_clock::now() < wallLimit)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (!done)
      {
        r.TimedOut = true;
        kill(pid, SIGKILL);
      }
    });
  char buf[4096];
  ssize_t got;
  while ((got = read(fds[0], buf, sizeof buf)) > 0)
    r.Line.append(buf, static_cast<size_t>(got));
  close(fds[0]);
  int status = 0;
  struct rusage usage;
  std::memset(&usage, 0, sizeof usage);
  wait4(pid, &status, 0, &usage);
  done = true;
  watchdog.join();
  r.WallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.PeakBytes = 1024.0 * static_cast<double>(usage.ru_maxrss); // Linux: KiB
  r.CpuSeconds = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
    1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  r.Ok = !r.TimedOut && WIFEXITED(status) && WEXITSTATUS(status) == 0 && !r.Line.empty();
  if (r.TimedOut)
  {
    char why[96];
    std::snprintf(why, sizeof why,
      "stopped at the limit of %.3g s of CPU (or 10x that of wall time)", cpuLimitSeconds);
    r.Status = why;
  }
  else if (WIFSIGNALED(status))
    r.Status = std::string("killed by signal ") + strsignal(WTERMSIG(status));
  else if (!r.Ok)
    r.Status = "exit status " + std::to_string(WEXITSTATUS(status));
  return r;
}

/// What the system can give, as the filters estimate it (0 if unknown).
inline double AvailableBytes()
{
  return dsurf::AvailableMemoryBytes();
}

/// A quantity that grows with the voxels (peak memory, time), learned by method from the cases
/// already run: the next, larger, volume is estimated from the largest one measured (linear in
/// the voxels; a fixed part only makes the estimate high), or from a prior per voxel before any
/// was measured.
class PerVoxelModel
{
public:
  void Record(const std::string& method, double voxels, double value)
  {
    auto& m = this->Measured[method];
    if (voxels >= m.first)
      m = { voxels, value };
  }
  double Estimate(const std::string& method, double voxels, double priorPerVoxel) const
  {
    auto it = this->Measured.find(method);
    if (it == this->Measured.end())
      return priorPerVoxel * voxels;
    return it->second.second * voxels / it->second.first;
  }

private:
  std::map<std::string, std::pair<double, double>> Measured; // method -> (voxels, value)
};

/// The memory a case may use: what is available now minus a reserve left to everything else.
inline double MemoryBudget(double reserveBytes)
{
  return std::max(0.0, AvailableBytes() - reserveBytes);
}
} // namespace dsbench

#endif
