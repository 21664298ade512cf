// SPDX-License-Identifier: BSD-3-Clause
// Time, peak memory and accuracy against the volume size: CT-like uint16 phantoms (a noisy ball
// of radius n/4 and a noisy cube of half side n/8, background 1000, object 2000, noise sigma
// 100) at 128^3 .. 1024^3, our whole solve (every default, from the box enclosing the volume)
// on two threads and, for the ball, on one and with the local edge normalisation, beside
// vtkFlyingEdges3D on the same volume in the same run. Every case runs in a child process of its
// own, so "peak RSS" is that case's high-water mark, phantom included. Before a case starts its
// peak is estimated from the largest size of the same method measured in this run (or a prior per
// voxel); a case whose estimate exceeds the memory available minus a reserve is skipped with the
// estimate printed. Then starts near the object on the ball+block scene (BenchVolumes.h NearScene):
// a sphere of radius 0.3 n around the ball, and one click at its centre (vtkDelaunaySeedSurface,
// RegionWeight 1), and a sphere 4 voxels around the ball (every default: sigma_0 a few voxels,
// so the first level is on the image's own grid), on two threads, beside vtkFlyingEdges3D at
// the ball's mid value. Last a ball filling most of the volume (radius 0.42 n, as the first
// ball otherwise) from a sphere 4 voxels around it, also with the local edge normalisation: its
// fine levels' boxes hold more than half the image, so their G_sigma * f (or the locally
// normalised P) is computed in slabs and kept near the surface (docs/METHOD.md §9.7).
// Usage: BenchScale [--time-limit CPU seconds (default 600)] [--reserve-gib G (default 2)]
//                   [--only TEXT (only the rows whose "phantom method" contains TEXT; repeat it
//                   to ask for every TEXT: --only ball --only "2 threads")]
//                   [sizes... (default 128 256 512 1024)]
#include "BenchRow.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  using namespace dsbench;
  double timeLimit = 600, reserve = 2 * GiB;
  std::vector<int> sizes;
  std::vector<std::string> only;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--time-limit" && i + 1 < argc)
      timeLimit = std::atof(argv[++i]);
    else if (a == "--reserve-gib" && i + 1 < argc)
      reserve = std::atof(argv[++i]) * GiB;
    else if (a == "--only" && i + 1 < argc)
      only.emplace_back(argv[++i]);
    else if (std::atoi(a.c_str()) > 0)
      sizes.push_back(std::atoi(a.c_str()));
    else
    {
      std::fprintf(stderr,
        "usage: BenchScale [--time-limit CPU s] [--reserve-gib G] [--only TEXT]... [sizes...]\n"
        "(see the comment at the top of Testing/Benchmarks/BenchScale.cxx)\n");
      return a == "--help" || a == "-h" ? 0 : 2;
    }
  }
  if (sizes.empty())
    sizes = { 128, 256, 512, 1024 };
  PrintHeader(" input GiB | estimate GiB |");
  // Priors of the peak per voxel, input included, until a smaller size was measured: ours
  // at most one level's field as large as the image, Potential and Force (4 floats), beside the
  // uint16 input, read in place (docs/METHOD.md §9.6); the iso-surface the input and a byte of
  // edge cases per voxel.
  CaseRunner runner(reserve, timeLimit);
  runner.SetOnly(only);
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
      ph.Name = (shape == Shape::Sphere ? "ball r" : "cube ") +
        std::to_string(static_cast<int>(ph.Size)) + " " + std::to_string(n) + "^3";
      std::vector<Method> methods = {
        { "ours, 2 threads", 18, [&](vtkImageData* im) { return RunOurs(im, ph, 2); } },
        { "vtkFlyingEdges3D", 4, [&](vtkImageData* im) { return RunFlyingEdges(im, ph); } },
      };
      if (shape == Shape::Sphere)
      {
        methods.insert(methods.begin() + 1,
          { "ours, 1 thread", 18, [&](vtkImageData* im) { return RunOurs(im, ph, 1); } });
        methods.insert(methods.begin() + 2,
          { "ours local edges, 2 threads", 18,
            [&](vtkImageData* im) { return RunOurs(im, ph, 2, LocalEdges); } });
      }
      for (const auto& m : methods)
        runner.Run(ph, m, true);
    }
  }
  for (int n : sizes)
  {
    const Phantom ph = NearScene(n);
    const std::vector<Method> methods = {
      { "ours near sphere, 2 threads", 18,
        [&](vtkImageData* im) { return RunOursNear(im, ph, 2); } },
      { "ours one click, 2 threads", 18,
        [&](vtkImageData* im) { return RunOursClick(im, ph, 2); } },
      { "ours tight sphere, 2 threads", 18,
        [&](vtkImageData* im) { return RunOursTightSphere(im, ph, 2, 4.0); } },
      { "vtkFlyingEdges3D", 4, [&](vtkImageData* im) { return RunFlyingEdges(im, ph); } },
    };
    for (const auto& m : methods)
      runner.Run(ph, m, true);
  }
  for (int n : sizes)
  {
    Phantom ph;
    ph.N = n;
    ph.Form = Shape::Sphere;
    ph.Size = 0.42 * n;
    ph.Noise = 0.1;
    ph.CT = true;
    ph.Name =
      "large ball r" + std::to_string(static_cast<int>(ph.Size)) + " " + std::to_string(n) + "^3";
    const std::vector<Method> methods = {
      { "ours tight sphere, 2 threads", 18,
        [&](vtkImageData* im) { return RunOursTightSphere(im, ph, 2, 4.0); } },
      { "ours tight sphere local edges, 2 threads", 18,
        [&](vtkImageData* im) { return RunOursTightSphere(im, ph, 2, 4.0, LocalEdges); } },
      { "vtkFlyingEdges3D", 4, [&](vtkImageData* im) { return RunFlyingEdges(im, ph); } },
    };
    for (const auto& m : methods)
      runner.Run(ph, m, true);
  }
  return 0;
}
