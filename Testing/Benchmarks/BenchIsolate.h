// One benchmark case in a child process of its own, so that each case's memory high-water mark
// (getrusage of the child: VmHWM) is its own, and a case that runs over its time budget is
// stopped instead of holding the whole run. The child writes one line of results to a pipe.
// Memory estimates are made before a case starts: a case whose estimate does not fit is never
// started (a system without swap would otherwise OOM-kill it, or a neighbour), nor one whose
// time estimate exceeds its time limit.
#ifndef BenchIsolate_h
#define BenchIsolate_h

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
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
  std::string Status; ///< how the child ended, for a failed case
};

/// Runs work() in a forked child; its return value is the result line. The parent must not
/// have started threads (fork copies only the calling thread): call this from main() only.
inline IsolatedResult RunIsolated(const std::function<std::string()>& work, double timeLimitSeconds)
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
  bool done = false;
  std::thread watchdog(
    [&]
    {
      const auto limit = t0 + std::chrono::duration<double>(timeLimitSeconds);
      while (!done && std::chrono::steady_clock::now() < limit)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
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
  r.WallSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.PeakBytes = 1024.0 * static_cast<double>(usage.ru_maxrss); // Linux: KiB
  r.Ok = !r.TimedOut && WIFEXITED(status) && WEXITSTATUS(status) == 0 && !r.Line.empty();
  if (r.TimedOut)
    r.Status = "stopped after the time limit of " + std::to_string(int(timeLimitSeconds)) + " s";
  else if (WIFSIGNALED(status))
    r.Status = std::string("killed by signal ") + strsignal(WTERMSIG(status));
  else if (!r.Ok)
    r.Status = "exit status " + std::to_string(WEXITSTATUS(status));
  return r;
}

/// MemAvailable of /proc/meminfo in bytes (0 if unknown).
inline double AvailableBytes()
{
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:")
      return kib * 1024.0;
  return 0;
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
  return AvailableBytes() - reserveBytes;
}
} // namespace dsbench

#endif
