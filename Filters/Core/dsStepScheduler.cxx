// SPDX-License-Identifier: BSD-3-Clause
#include "dsStepScheduler.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <thread>

namespace dsurf
{
namespace
{
/// Spin briefly, then give the core away: the other thread is usually microseconds
/// from done, but on a loaded machine it may be descheduled.
inline void WaitPause(int& spins)
{
  if (++spins < 256)
  {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  else
  {
    std::this_thread::yield();
  }
}

struct alignas(64) ThreadSlot
{
  std::atomic<long long> Next{ 0 };     ///< blocks of this region taken, over all steps
  std::atomic<long long> Finished{ 0 }; ///< blocks this thread completed, over all steps
};

/// The shared state of one Run().
struct RunState
{
  RunState(int threads, int perThread)
    : Threads(threads)
    , PerThread(perThread)
    , Blocks(threads * perThread)
    , Slots(new ThreadSlot[threads])
  {
  }

  /// The next untaken block of `region` in `step`, or -1.
  int Take(int region, long long step)
  {
    ThreadSlot& slot = this->Slots[region];
    long long k = slot.Next.load(std::memory_order_relaxed);
    while (k < (step + 1) * this->PerThread)
    {
      if (slot.Next.compare_exchange_weak(k, k + 1, std::memory_order_acquire))
      {
        return region * this->PerThread + static_cast<int>(k - step * this->PerThread);
      }
    }
    return -1;
  }

  /// Waits until every block of steps 0 .. step is finished.
  void WaitForStep(long long step) const
  {
    const long long target = (step + 1) * this->Blocks;
    int spins = 0;
    for (;;)
    {
      long long finished = 0;
      for (int r = 0; r < this->Threads; ++r)
      {
        finished += this->Slots[r].Finished.load(std::memory_order_acquire);
      }
      if (finished >= target)
      {
        return;
      }
      WaitPause(spins);
    }
  }

  const int Threads, PerThread, Blocks;
  std::unique_ptr<ThreadSlot[]> Slots;
  alignas(64) std::atomic<long long> EndBlocks{ 0 }; ///< blocks completed in steps with an end
  std::atomic<bool> LastStepNext{ false };
  long long Steps = 0; ///< written by the thread that ends the last step, before the final one
};

/// Thread t's part of a Run(): every step, until the one after the step that asked to stop.
void RunThread(int t, RunState& state, StepScheduler::Job& job)
{
  ThreadSlot& mine = state.Slots[t];
  long long endedSteps = 0; // steps with an end seen so far by this thread
  bool last = false;
  for (long long step = 0;; ++step)
  {
    const bool hasEnd = !last && job.HasEnd(step);
    endedSteps += hasEnd ? 1 : 0;
    for (int r = 0; r < state.Threads; ++r)
    {
      const int region = (t + r) % state.Threads;
      for (int b = state.Take(region, step); b >= 0; b = state.Take(region, step))
      {
        job.RunBlock(step, b);
        // The last block of a step with an end counts only after EndStep(), so no
        // thread goes on before it returned.
        if (hasEnd &&
          state.EndBlocks.fetch_add(1, std::memory_order_acq_rel) + 1 ==
            endedSteps * state.Blocks &&
          job.EndStep(step))
        {
          state.Steps = step + 2;
          state.LastStepNext.store(true, std::memory_order_relaxed);
        }
        mine.Finished.fetch_add(1, std::memory_order_release);
      }
    }
    if (last)
    {
      return; // the For returns when every block is done
    }
    state.WaitForStep(step);
    last = state.LastStepNext.load(std::memory_order_relaxed);
  }
}
} // namespace

StepScheduler::StepScheduler(int numberOfThreads, int blocksPerThread)
  : Threads(std::max(1, numberOfThreads))
  , BlocksPerThread(std::max(1, blocksPerThread))
{
}

long long StepScheduler::Run(Job& job) const
{
  RunState state(this->Threads, this->BlocksPerThread);
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ this->Threads, "STDThread", false },
    [&]()
    {
      vtkSMPTools::For(0, this->Threads, 1,
        [&](vtkIdType begin, vtkIdType end)
        {
          for (vtkIdType t = begin; t < end; ++t)
          {
            RunThread(static_cast<int>(t), state, job);
          }
        });
    });
  return state.Steps;
}
} // namespace dsurf
