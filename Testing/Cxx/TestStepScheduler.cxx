// SPDX-License-Identifier: BSD-3-Clause
// Unit test of the solver's step scheduler (dsStepScheduler): with 1 to 5 threads, one and
// eight blocks per thread, every block of every step runs exactly once; no block of a step
// starts before every block of the step before it finished; EndStep runs once per step
// that has one, after that step's blocks and before the next step's; Run stops one step
// after the EndStep that returned true; BlockRange cuts a range into contiguous pieces.
#include "DSTestHelpers.h"

#include "dsStepScheduler.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

using namespace dsurf;

namespace
{
/// Every third step (2, 5, 8, ...) ends with EndStep; the fourth EndStep asks to stop, so
/// steps 0 .. 11 run and step 12 is the last one.
constexpr int EndEvery = 3;
constexpr int StopAfterEnds = 4;
constexpr int ExpectedSteps = EndEvery * StopAfterEnds + 1;

class RecordingJob : public StepScheduler::Job
{
public:
  explicit RecordingJob(int blocks)
    : Blocks(blocks)
    , Runs(static_cast<size_t>(ExpectedSteps + 2) * blocks)
    , Start(Runs.size(), -1)
    , End(Runs.size(), -1)
    , EndTick(ExpectedSteps + 2, -1)
  {
    for (auto& r : this->Runs)
    {
      r.store(0);
    }
  }

  void RunBlock(long long step, int block) override
  {
    if (step >= ExpectedSteps + 2 || block < 0 || block >= this->Blocks)
    {
      this->OutOfRange.store(true);
      return;
    }
    const size_t slot = static_cast<size_t>(step) * this->Blocks + block;
    this->Start[slot] = this->Clock.fetch_add(1);
    this->Runs[slot].fetch_add(1);
    // Long enough that the other threads take blocks too, instead of one thread running
    // every step alone before they start.
    std::this_thread::sleep_for(std::chrono::microseconds(50));
    this->End[slot] = this->Clock.fetch_add(1);
  }
  bool HasEnd(long long step) const override { return step % EndEvery == EndEvery - 1; }
  bool EndStep(long long step) override
  {
    if (step < ExpectedSteps + 2)
    {
      this->EndTick[step] = this->Clock.fetch_add(1);
    }
    ++this->EndCalls;
    return this->EndCalls == StopAfterEnds;
  }

  const int Blocks;
  std::atomic<long long> Clock{ 0 };
  std::atomic<bool> OutOfRange{ false };
  std::vector<std::atomic<int>> Runs;
  std::vector<long long> Start, End, EndTick;
  int EndCalls = 0;
};

void CheckRun(int threads, int blocksPerThread)
{
  const StepScheduler scheduler(threads, blocksPerThread);
  const int blocks = scheduler.NumberOfBlocks();
  const std::string what =
    std::to_string(threads) + " threads, " + std::to_string(blocksPerThread) + " blocks each";
  DS_CHECK(blocks == threads * blocksPerThread, what);
  RecordingJob job(blocks);
  const long long steps = scheduler.Run(job);
  DS_CHECK(steps == ExpectedSteps, what + ": steps run " + std::to_string(steps));
  DS_CHECK(!job.OutOfRange.load(), what + ": a block outside the steps or blocks ran");
  DS_CHECK(job.EndCalls == StopAfterEnds, what + ": EndStep calls " + std::to_string(job.EndCalls));
  int wrongCounts = 0, overlaps = 0, endsOutOfOrder = 0;
  for (int s = 0; s < ExpectedSteps + 2; ++s)
  {
    long long firstStart = -1, lastEnd = -1;
    for (int b = 0; b < blocks; ++b)
    {
      const size_t slot = static_cast<size_t>(s) * blocks + b;
      wrongCounts += job.Runs[slot].load() != (s < ExpectedSteps ? 1 : 0) ? 1 : 0;
      firstStart = firstStart < 0 ? job.Start[slot] : std::min(firstStart, job.Start[slot]);
      lastEnd = std::max(lastEnd, job.End[slot]);
    }
    if (s + 1 < ExpectedSteps)
    {
      long long nextStart = -1;
      for (int b = 0; b < blocks; ++b)
      {
        const long long st = job.Start[static_cast<size_t>(s + 1) * blocks + b];
        nextStart = nextStart < 0 ? st : std::min(nextStart, st);
      }
      overlaps += lastEnd < nextStart ? 0 : 1;
      if (job.HasEnd(s))
      {
        endsOutOfOrder += (job.EndTick[s] > lastEnd && job.EndTick[s] < nextStart) ? 0 : 1;
      }
      else
      {
        endsOutOfOrder += job.EndTick[s] == -1 ? 0 : 1;
      }
    }
  }
  DS_CHECK(
    wrongCounts == 0, what + ": blocks not run exactly once: " + std::to_string(wrongCounts));
  DS_CHECK(overlaps == 0,
    what + ": steps that started before the previous one finished: " + std::to_string(overlaps));
  DS_CHECK(
    endsOutOfOrder == 0, what + ": EndStep calls out of place: " + std::to_string(endsOutOfOrder));
}

void CheckBlockRange()
{
  for (long long count : { 0LL, 1LL, 7LL, 1000LL })
  {
    for (int blocks : { 1, 3, 16 })
    {
      int expectedFirst = 0;
      bool contiguous = true;
      for (int b = 0; b < blocks; ++b)
      {
        int first = -1, last = -1;
        StepScheduler::BlockRange(count, b, blocks, first, last);
        contiguous = contiguous && first == expectedFirst && last >= first;
        expectedFirst = last;
      }
      DS_CHECK(contiguous && expectedFirst == count,
        std::to_string(count) + " items in " + std::to_string(blocks) +
          " blocks: not cut into contiguous pieces");
    }
  }
}
} // namespace

int TestStepScheduler(int, char*[])
{
  for (int threads = 1; threads <= 5; ++threads)
  {
    for (int blocksPerThread : { 1, 8 })
    {
      CheckRun(threads, blocksPerThread);
    }
  }
  CheckBlockRange();
  return dstest::Result("TestStepScheduler");
}

int main(int argc, char* argv[])
{
  return TestStepScheduler(argc, argv);
}
