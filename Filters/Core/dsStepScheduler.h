// SPDX-License-Identifier: BSD-3-Clause
// A lock-free scheduler for a sequence of parallel steps in one parallel region, used by
// the solver's Gauss-Seidel sweeps (dsSolver.h): one step per colour, one for the
// statistics, per sweep. Plain C++ (vtkSMPTools runs the threads).
//
// Why: VTK 9.2's STDThread backend starts its threads on every vtkSMPTools::For, which
// costs about as much as a quarter of a sweep of 12 288 triangles; one region for all
// the sweeps starts them once.
//
// How: each step is cut into NumberOfBlocks() blocks, `blocksPerThread` consecutive ones
// per thread (its region). Thread t first takes the blocks of its own region (the same
// part of the data in every step, so what it touches stays in its cache), then blocks
// left in the other regions, then waits until every block of the step is done. A thread
// waits only for blocks a running thread has taken, so this cannot deadlock even if the
// backend ran the jobs one after another, and the share of a thread descheduled on a
// busy machine is taken over. Counters live on their own cache lines: a thread touches
// another's only to take over its work or to see whether the step is done.
#ifndef dsStepScheduler_h
#define dsStepScheduler_h

#include "DeformableSurfaceFiltersModule.h" // for export macro

namespace dsurf
{
class DEFORMABLESURFACEFILTERS_EXPORT StepScheduler
{
public:
  /// What the scheduler runs. Steps are numbered 0, 1, 2, ...
  class Job
  {
  public:
    virtual ~Job() = default;
    /// Runs block `block` (0 <= block < NumberOfBlocks()) of step `step`. Called
    /// concurrently for the blocks of one step, never for blocks of different steps.
    virtual void RunBlock(long long step, int block) = 0;
    /// Whether step `step` ends with EndStep().
    virtual bool HasEnd(long long step) const = 0;
    /// Called once for a step with HasEnd(), on the thread that completed its last block,
    /// after every block of the step and before any block of the next. Returns true when
    /// the next step is the last one.
    virtual bool EndStep(long long step) = 0;
  };

  /// numberOfThreads >= 1 threads (run through vtkSMPTools' STDThread backend).
  explicit StepScheduler(int numberOfThreads, int blocksPerThread = 8);

  int NumberOfThreads() const { return this->Threads; }
  int NumberOfBlocks() const { return this->Threads * this->BlocksPerThread; }

  /// Runs steps 0, 1, ... until an EndStep() returns true, then the one step after it.
  /// Returns the number of steps run.
  long long Run(Job& job) const;

  /// The range [first, last) of block `block` when `count` items are cut into blocks.
  static void BlockRange(long long count, int block, int blocks, int& first, int& last)
  {
    first = static_cast<int>(count * block / blocks);
    last = static_cast<int>(count * (block + 1) / blocks);
  }

private:
  int Threads;
  int BlocksPerThread;
};
} // namespace dsurf

#endif
