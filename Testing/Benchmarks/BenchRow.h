// SPDX-License-Identifier: BSD-3-Clause
// One table row of the accuracy and scale benchmarks: a method on a phantom, run in its own
// child process (BenchIsolate.h) after a memory estimate, printed with the child's peak RSS.
// A case whose estimate exceeds the memory budget is not started; the row says so and why.
#ifndef BenchRow_h
#define BenchRow_h

#include "BenchIsolate.h"
#include "BenchMethods.h"

#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace dsbench
{
/// The columns every row has; a program may append its own after "peak RSS GiB" (`extra`:
/// " name | name |").
inline void PrintHeader(const std::string& extra = "")
{
  std::string rule = "|---|---|---|---|---|---|---|---|---|---|---|";
  for (char c : extra)
    rule += c == '|' ? "---|" : "";
  std::printf(
    "| phantom | method | time s (cpu s) | triangles | pieces | min angle: min / p5 / median "
    "| < 20 deg | mean d | max d | notes | peak RSS GiB |%s\n%s\n",
    extra.c_str(), rule.c_str());
}

struct RowLimits
{
  double EstimateBytes = 0;   ///< the case's estimated peak
  double BudgetBytes = 0;     ///< what it may use
  double EstimateSeconds = 0; ///< CPU seconds
  double TimeLimit = 600;     ///< CPU seconds, then the child is stopped
};

/// Runs `method` (building the phantom's image first, in the child) and prints the row.
/// Returns the child's result; Ok is false for a skipped, failed or stopped case.
inline IsolatedResult RunRow(const Phantom& ph, const std::string& method, const RowLimits& limits,
  const std::function<std::string(vtkImageData*)>& run, const std::string& extraCells = "")
{
  IsolatedResult r;
  char why[160] = "";
  if (limits.EstimateBytes > limits.BudgetBytes)
    std::snprintf(why, sizeof why, "skipped: needs ~%.1f GiB (estimate), %.1f GiB may be used",
      limits.EstimateBytes / GiB, limits.BudgetBytes / GiB);
  else if (limits.EstimateSeconds > limits.TimeLimit)
    std::snprintf(why, sizeof why, "skipped: needs ~%.3g s of CPU (estimate), limit %.3g s",
      limits.EstimateSeconds, limits.TimeLimit);
  if (*why)
  {
    std::printf(
      "| %s | %s | %s |||||||| - |%s\n", ph.Name.c_str(), method.c_str(), why, extraCells.c_str());
    r.Status = why;
    return r;
  }
  r = RunIsolated([&] { return run(MakeImage(ph)); }, limits.TimeLimit);
  if (r.Ok && r.Line.rfind("failed", 0) != 0)
    std::printf("| %s | %s | %s | %.2f |%s\n", ph.Name.c_str(), method.c_str(), r.Line.c_str(),
      r.PeakBytes / GiB, extraCells.c_str());
  else
  {
    r.Ok = false;
    std::printf("| %s | %s | %s |||||||| %.2f |%s\n", ph.Name.c_str(), method.c_str(),
      r.Line.empty() ? r.Status.c_str() : r.Line.c_str(), r.PeakBytes / GiB, extraCells.c_str());
  }
  std::fflush(stdout);
  return r;
}
/// A method of a table: its name, a prior peak per voxel (input included) used until a smaller
/// case of it was measured in the run, and the work the child does on the phantom's image.
struct Method
{
  std::string Name;
  double PriorBytesPerVoxel;
  std::function<std::string(vtkImageData*)> Run;
};

/// Runs the rows of a table: estimates each case from the cases of its method measured so far
/// (memory and CPU time, linear in the voxels), runs or skips it, and learns from it.
class CaseRunner
{
public:
  CaseRunner(double reserveBytes, double cpuLimitSeconds)
    : Reserve(reserveBytes)
    , CpuLimit(cpuLimitSeconds)
  {
  }
  /// Only the rows whose "phantom method" contains every one of `texts` run (all when empty).
  void SetOnly(std::vector<std::string> texts) { this->Only = std::move(texts); }
  bool Chosen(const Phantom& ph, const Method& m) const
  {
    const std::string row = ph.Name + " " + m.Name;
    for (const std::string& text : this->Only)
      if (row.find(text) == std::string::npos)
        return false;
    return true;
  }
  /// `sizeCells`: append the input size and the memory estimate as two more cells. A row not
  /// chosen (SetOnly) is left out without a line.
  IsolatedResult Run(const Phantom& ph, const Method& m, bool sizeCells)
  {
    if (!this->Chosen(ph, m))
      return IsolatedResult();
    RowLimits limits;
    limits.EstimateBytes = this->Memory.Estimate(m.Name, ph.Voxels(), m.PriorBytesPerVoxel);
    limits.BudgetBytes = MemoryBudget(this->Reserve);
    limits.EstimateSeconds = this->Time.Estimate(m.Name, ph.Voxels(), 0.0);
    limits.TimeLimit = this->CpuLimit;
    char extra[64] = "";
    if (sizeCells)
      std::snprintf(
        extra, sizeof extra, " %.3f | %.2f |", ph.InputBytes() / GiB, limits.EstimateBytes / GiB);
    const IsolatedResult r = RunRow(ph, m.Name, limits, m.Run, extra);
    if (r.Ok)
    {
      this->Memory.Record(m.Name, ph.Voxels(), r.PeakBytes);
      this->Time.Record(m.Name, ph.Voxels(), r.CpuSeconds);
    }
    return r;
  }

private:
  double Reserve, CpuLimit;
  std::vector<std::string> Only;
  PerVoxelModel Memory, Time;
};
} // namespace dsbench

#endif
