// Time, peak memory and accuracy against the volume size: CT-like uint16 phantoms (a noisy ball
// of radius n/4 and a noisy cube of half side n/8, background 1000, object 2000, noise sigma
// 100) at 128^3 .. 1024^3, our whole solve (every default, from the box enclosing the volume)
// on two threads and, for the ball, on one, beside vtkFlyingEdges3D on the same volume in the
// same run. Every case runs in a child process of its own, so "peak RSS" is that case's
// high-water mark, phantom included. Before a case starts its peak is estimated from the
// largest size of the same method measured in this run (or a prior per voxel); a case whose
// estimate exceeds the memory available minus a reserve is skipped with the estimate printed.
// Usage: BenchScale [--time-limit CPU seconds (default 600)] [--reserve-gib G (default 2)]
//                   [sizes... (default 128 256 512 1024)]
#include "BenchRow.h"

#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  using namespace dsbench;
  double timeLimit = 600, reserve = 2 * GiB;
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--time-limit" && i + 1 < argc)
      timeLimit = std::atof(argv[++i]);
    else if (a == "--reserve-gib" && i + 1 < argc)
      reserve = std::atof(argv[++i]) * GiB;
    else
      sizes.push_back(std::atoi(a.c_str()));
  }
  if (sizes.empty())
    sizes = { 128, 256, 512, 1024 };
  PrintHeader(" input GiB | estimate GiB |");
  // Priors (bytes per voxel, input included) until a smaller size was measured: ours holds a
  // float copy, Potential and Force (4 floats) per voxel beside the uint16 input; the
  // iso-surface the input and a byte of edge cases per voxel.
  PerVoxelModel memory, time;
  for (int n : sizes)
  {
    for (Shape shape : { Shape::Sphere, Shape::Cube })
    {
      Phantom ph;
      ph.N = n;
      ph.Form = shape;
      ph.Size = shape == Shape::Sphere ? n / 4.0 : n / 8.0;
      ph.Noise = 0.1;
      ph.CT = true;
      ph.Name = (shape == Shape::Sphere ? "ball r" : "cube ") + std::to_string(n / (shape ==
        Shape::Sphere ? 4 : 8)) + " " + std::to_string(n) + "^3";
      struct Method
      {
        std::string Name;
        double Prior;
        std::function<std::string(vtkImageData*)> Run;
      };
      std::vector<Method> methods = {
        { "ours, 2 threads", 24, [&](vtkImageData* im) { return RunOurs(im, ph, 2); } },
        { "vtkFlyingEdges3D", 4, [&](vtkImageData* im) { return RunFlyingEdges(im, ph); } },
      };
      if (shape == Shape::Sphere)
        methods.insert(methods.begin() + 1,
          { "ours, 1 thread", 24, [&](vtkImageData* im) { return RunOurs(im, ph, 1); } });
      for (const auto& m : methods)
      {
        RowLimits limits;
        limits.EstimateBytes = memory.Estimate(m.Name, ph.Voxels(), m.Prior);
        limits.BudgetBytes = MemoryBudget(reserve);
        limits.EstimateSeconds = time.Estimate(m.Name, ph.Voxels(), 0.0);
        limits.TimeLimit = timeLimit;
        char extra[64];
        std::snprintf(extra, sizeof extra, " %.3f | %.2f |", ph.InputBytes() / GiB,
          limits.EstimateBytes / GiB);
        const IsolatedResult r = RunRow(ph, m.Name, limits, m.Run, extra);
        if (r.Ok)
        {
          memory.Record(m.Name, ph.Voxels(), r.PeakBytes);
          time.Record(m.Name, ph.Voxels(), r.CpuSeconds);
        }
      }
    }
  }
  return 0;
}
