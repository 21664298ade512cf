// SPDX-License-Identifier: BSD-3-Clause
// Time per solver sweep on the paper's test meshes: a cube surface subdivided 5 and 6
// times (12 288 and 49 152 triangles), 1 and 2 threads, without and with an external
// force field (trilinear sampling of a 128^3 field). The paper: 1.4 s and 5.9 s per
// sweep on a 175 MHz R10000. "cpu ms" is the process CPU time per sweep (all threads,
// spin-waiting included): on a busy machine the wall time of the 2-thread rows says
// little, but cpu(1 thread) / cpu(2 threads) still shows the parallel overhead.
// "call": Sweep() once per sweep (threads started per sweep by VTK 9.2's STDThread
// backend), Sweeps(20) (batches of 20 sweeps in one parallel region: what a filter
// reporting progress between batches would do) or Sweeps(all) (one region).
//   BenchSolver [sweeps] [subdivision level: 5 or 6; default both]
#include "../Cxx/TestSolverMeshes.h"

#include "dsScaleSpace.h"
#include "dsSolver.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

int main(int argc, char* argv[])
{
  const int sweeps = argc > 1 ? std::atoi(argv[1]) : 200;
  const int onlyLevel = argc > 2 ? std::atoi(argv[2]) : 0;
  // A force field pulling onto a sphere of radius 40 in a 128^3 grid (the values do not
  // matter for timing, only that every vertex samples it).
  dsurf::ForceField field;
  const int n = 128;
  for (int a = 0; a < 3; ++a)
  {
    field.Geometry.Dimensions[a] = n;
  }
  field.Sigma = 2;
  field.Potential.assign(static_cast<size_t>(n) * n * n, 0.0f);
  field.Force.resize(3 * field.Potential.size());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double d[3] = { i - 63.5, j - 63.5, k - 63.5 };
        const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-9;
        const size_t idx = i + static_cast<size_t>(n) * (j + static_cast<size_t>(n) * k);
        for (int a = 0; a < 3; ++a)
        {
          field.Force[3 * idx + a] = static_cast<float>(0.01 * (40 - r) * d[a] / r);
        }
      }

  std::printf("%-10s %-9s %-8s %-6s %-12s %-8s %-12s %-14s %-10s %-10s %-8s\n", "triangles",
    "vertices", "force", "threads", "call", "colours", "ms/sweep", "ns/vertex", "speed-up",
    "cpu ms", "paper s");
  for (int level : { 5, 6 })
  {
    if (onlyLevel != 0 && level != onlyLevel)
    {
      continue;
    }
    for (bool withForce : { false, true })
    {
      for (int batch : { 1, 20, sweeps })
      {
        double single = 0;
        for (int threads : { 1, 2 })
        {
          dsurf::TriangleMesh mesh = dstest::MakeCubeSurface(level, 30, { 63.5, 63.5, 63.5 });
          std::string err;
          mesh.BuildTopology(&err);
          dsurf::Solver solver;
          dsurf::SolverParameters p;
          p.NumberOfThreads = threads;
          solver.SetParameters(p);
          solver.SetMesh(&mesh);
          solver.SetForceField(withForce ? &field : nullptr, 1.0);
          for (int w = 0; w < 5; ++w)
          {
            solver.Sweep(); // warm-up
          }
          const std::clock_t c0 = std::clock();
          const auto t0 = std::chrono::steady_clock::now();
          for (int s = 0; s < sweeps; s += batch)
          {
            if (batch == 1)
            {
              solver.Sweep();
            }
            else
            {
              solver.Sweeps(
                std::min(batch, sweeps - s), [](const dsurf::SweepStatistics&) { return true; });
            }
          }
          const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
              .count() /
            sweeps;
          const double cpuMs = 1000.0 * (std::clock() - c0) / CLOCKS_PER_SEC / sweeps;
          if (threads == 1)
          {
            single = ms;
          }
          const char* call =
            batch == 1 ? "Sweep" : (batch == sweeps ? "Sweeps(all)" : "Sweeps(20)");
          std::printf("%-10d %-9d %-8s %-6d %-12s %-8d %-12.3f %-14.1f %-10.2f %-10.3f %-8s\n",
            mesh.NumberOfTriangles(), mesh.NumberOfPoints(), withForce ? "yes" : "no", threads,
            call, solver.NumberOfColors(), ms, 1e6 * ms / mesh.NumberOfPoints(), single / ms, cpuMs,
            level == 5 ? "1.4" : "5.9");
        }
      }
    }
  }
  return 0;
}
