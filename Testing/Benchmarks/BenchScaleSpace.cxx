// SPDX-License-Identifier: BSD-3-Clause
// Benchmark (not a test): vtkImageScaleSpaceGradient on an N^3 float volume
// (default 256) at sigma = 42.7, 21.3, 10.7, 5.3, 2 voxels with 1 and 2 threads,
// beside vtkImageGaussianSmooth (radius factor 3, i.e. the kernel covers 3 sigma)
// + vtkImageGradient at the same sigma and thread count, and the peak memory.
//
//   BenchScaleSpace [N=256] [repetitions of ours=3] [repetitions of the VTK pair=1]
// (VTK pair repetitions 0 skips it: at 256^3 one pass of it takes 2-33 s.)
//
// Times are the best of the repetitions (wall clock, seconds).
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageGaussianSmooth.h"
#include "vtkImageGradient.h"
#include "vtkImageScaleSpaceGradient.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace
{
double PeakRSSMiB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0; // Linux: KiB
}

template <typename F>
double Best(int repetitions, F&& run)
{
  double best = 1e300;
  for (int r = 0; r < repetitions; ++r)
  {
    const auto t0 = std::chrono::steady_clock::now();
    run();
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
  }
  return best;
}
} // namespace

int main(int argc, char* argv[])
{
  const int N = argc > 1 ? std::atoi(argv[1]) : 256;
  const int repsOurs = argc > 2 ? std::atoi(argv[2]) : 3;
  const int repsVTK = argc > 3 ? std::atoi(argv[3]) : 1;
  const double sigmas[] = { 42.7, 21.3, 10.7, 5.3, 2.0 };
  const int threads[] = { 1, 2 };

  // A ball with a ripple, as float: the content does not change the cost.
  vtkNew<vtkImageData> image;
  image->SetDimensions(N, N, N);
  vtkNew<vtkFloatArray> f;
  f->SetName("f");
  f->SetNumberOfTuples(static_cast<vtkIdType>(N) * N * N);
  float* v = f->GetPointer(0);
  const double c = 0.5 * (N - 1), R = 0.3 * N;
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
      {
        const double r = std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c));
        *v++ = static_cast<float>((r < R ? 100.0 : 0.0) + 5.0 * std::sin(0.3 * i + 0.2 * j));
      }
  image->GetPointData()->SetScalars(f);
  const double baseRSS = PeakRSSMiB();
  std::printf("BenchScaleSpace: %d^3 float volume (%.0f MiB), peak RSS after setup %.0f MiB\n", N,
    4.0 * N * N * N / 1048576.0, baseRSS);
  std::printf("ours: best of %d; VTK pair (vtkImageGaussianSmooth radius factor 3 + "
              "vtkImageGradient): best of %d\n\n",
    repsOurs, repsVTK);

  double ours[5][2];
  {
    vtkNew<vtkImageScaleSpaceGradient> filter;
    filter->SetInputData(image);
    filter->SetSigma(2.0);
    filter->Update(); // warm-up: first-touch page faults would land on the first row
    for (int s = 0; s < 5; ++s)
    {
      for (int t = 0; t < 2; ++t)
      {
        filter->SetSigma(sigmas[s]);
        filter->SetNumberOfThreads(threads[t]);
        ours[s][t] = Best(repsOurs,
          [&]()
          {
            filter->Modified();
            filter->Update();
          });
        std::fflush(stdout);
      }
    }
  }
  const double oursRSS = PeakRSSMiB();

  double vtk[5][2] = {};
  for (int s = 0; s < 5 && repsVTK > 0; ++s)
  {
    for (int t = 0; t < 2; ++t)
    {
      vtkNew<vtkImageGaussianSmooth> smooth;
      smooth->SetInputData(image);
      smooth->SetDimensionality(3);
      smooth->SetStandardDeviations(sigmas[s], sigmas[s], sigmas[s]);
      smooth->SetRadiusFactors(3.0, 3.0, 3.0);
      smooth->SetNumberOfThreads(threads[t]);
      vtkNew<vtkImageGradient> gradient;
      gradient->SetInputConnection(smooth->GetOutputPort());
      gradient->SetDimensionality(3);
      gradient->HandleBoundariesOn();
      gradient->SetNumberOfThreads(threads[t]);
      vtk[s][t] = Best(repsVTK,
        [&]()
        {
          smooth->Modified();
          gradient->Update();
        });
      std::printf(
        "  (VTK pair sigma %.1f, %d thread(s): %.3f s)\n", sigmas[s], threads[t], vtk[s][t]);
      std::fflush(stdout);
    }
  }
  const double vtkRSS = PeakRSSMiB();

  std::printf("\n| sigma (voxels) | threads | ours (s) | VTK pair (s) | VTK / ours |\n");
  std::printf("|---:|---:|---:|---:|---:|\n");
  for (int s = 0; s < 5; ++s)
  {
    for (int t = 0; t < 2; ++t)
    {
      std::printf("| %.1f | %d | %.3f | %.3f | %.1fx |\n", sigmas[s], threads[t], ours[s][t],
        vtk[s][t], vtk[s][t] / ours[s][t]);
    }
  }
  for (int t = 0; t < 2; ++t)
  {
    std::printf("\nours, %d thread(s): cost(sigma 42.7) / cost(sigma 2) = %.2f (goal <= 1.5)\n",
      threads[t], ours[0][t] / ours[4][t]);
  }
  std::printf("\npeak RSS: after setup %.0f MiB; after ours %.0f MiB (+%.0f MiB = %.1f volumes); "
              "after the VTK pair %.0f MiB\n",
    baseRSS, oursRSS, oursRSS - baseRSS, (oursRSS - baseRSS) / (4.0 * N * N * N / 1048576.0),
    vtkRSS);
  return EXIT_SUCCESS;
}
