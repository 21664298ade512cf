// SPDX-License-Identifier: BSD-3-Clause
// Processes of a distributed solve emulated by threads of one test: Run(body) runs body(rank)
// on one thread per rank, and Sum / Max are the all-reduce calls between them (what
// vtkMultiProcessController::AllReduce does across MPI processes). A reduction waits until
// every rank made it, so a rank that skips one hangs the test (the ctest timeout catches it).
#ifndef EmulatedRanks_h
#define EmulatedRanks_h

#include <algorithm>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace dstest
{
class EmulatedRanks
{
public:
  explicit EmulatedRanks(int ranks)
    : Ranks(ranks)
    , Contributions(ranks)
  {
  }

  int Size() const { return this->Ranks; }

  /// body(rank) on one thread per rank; returns when all are done.
  void Run(const std::function<void(int)>& body)
  {
    std::vector<std::thread> threads;
    for (int r = 0; r < this->Ranks; ++r)
    {
      threads.emplace_back(body, r);
    }
    for (auto& t : threads)
    {
      t.join();
    }
  }

  /// Element-wise sum over the ranks (in rank order), in place.
  void Sum(int rank, std::vector<double>& values)
  {
    this->Reduce(rank, values, [](double a, double b) { return a + b; });
  }
  double Max(int rank, double value)
  {
    std::vector<double> v{ value };
    this->Reduce(rank, v, [](double a, double b) { return std::max(a, b); });
    return v[0];
  }
  /// Reductions whose ranks passed vectors of different sizes (a bug in the caller).
  int Mismatches() const { return this->SizeMismatches; }

private:
  template <typename Op>
  void Reduce(int rank, std::vector<double>& values, Op op)
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    this->Contributions[rank] = values;
    const long long generation = this->Generation;
    if (++this->Arrived < this->Ranks)
    {
      this->Done.wait(lock, [&] { return this->Generation != generation; });
      values = this->Result;
      return;
    }
    this->Result = this->Contributions[0];
    for (int r = 1; r < this->Ranks; ++r)
    {
      const std::vector<double>& c = this->Contributions[r];
      this->SizeMismatches += c.size() != this->Result.size();
      for (std::size_t i = 0; i < std::min(c.size(), this->Result.size()); ++i)
      {
        this->Result[i] = op(this->Result[i], c[i]);
      }
    }
    values = this->Result;
    this->Arrived = 0;
    ++this->Generation;
    this->Done.notify_all();
  }

  const int Ranks;
  std::mutex Mutex;
  std::condition_variable Done;
  int Arrived = 0;
  long long Generation = 0;
  int SizeMismatches = 0;
  std::vector<std::vector<double>> Contributions;
  std::vector<double> Result;
};
} // namespace dstest

#endif
