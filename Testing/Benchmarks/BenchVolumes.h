// SPDX-License-Identifier: BSD-3-Clause
// The benchmark phantoms as vtkImageData (unit spacing, origin 0, n^3, centre (n-1)/2 on every
// axis), each with its analytic distance: a sphere anti-aliased by 4^3 supersampling of the
// boundary voxels and an axis-aligned cube whose faces lie halfway between voxels, as float
// (background 0, object 1) or as a CT-like uint16 volume (background 1000, object 2000); either
// with optional Gaussian noise. The noise is a hash of the voxel index (no generator state),
// so the volume is the same for any thread count and run; filled in parallel (1024^3 in seconds).
// The near-start scene (NearScene) is a CT-like ball (value 1100) beside a darker
// block (700, half side n/10 at (c + 0.36 n, c + 0.36 n, c)) on background 100, noise s.d. 60.
#ifndef BenchVolumes_h
#define BenchVolumes_h

#include "../Cxx/HierarchyPhantoms.h"
#include "BenchMeasure.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedShortArray.h"

#include <cmath>
#include <cstdint>
#include <string>

namespace dsbench
{
enum class Shape
{
  Sphere,
  Cube
};

struct Phantom
{
  std::string Name;
  int N = 128;
  Shape Form = Shape::Sphere;
  double Size = 32; ///< sphere radius or cube half side, voxels
  double Noise = 0; ///< noise standard deviation as a fraction of the contrast
  bool CT = false;  ///< uint16 1000/2000 instead of float 0/1
  /// CT only: the background and the object's value above it, and a second, darker object (a
  /// block of half side BlockSize at (c + 0.36 n, c + 0.36 n, c), BlockContrast above the
  /// background; none when 0); the noise's seed.
  double CTBackground = 1000, CTContrast = 1000;
  double BlockSize = 0, BlockContrast = 0;
  std::uint64_t Seed = 12345;
  double Voxels() const { return double(N) * N * N; }
  double Background() const { return CT ? CTBackground : 0.0; }
  double Contrast() const { return CT ? CTContrast : 1.0; }
  /// The iso-value halfway between background and object (vtkFlyingEdges3D's level).
  double MidValue() const { return Background() + 0.5 * Contrast(); }
  double InputBytes() const { return Voxels() * (CT ? 2.0 : 4.0); }
};

/// A standard normal variate from the voxel index and a seed: splitmix64 then Box-Muller.
inline double HashNormal(std::uint64_t index, std::uint64_t seed = 12345)
{
  auto mix = [](std::uint64_t z)
  {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  const std::uint64_t a = mix(index * 2 + seed), b = mix(index * 2 + 1 + seed);
  const double u1 = (double(a >> 11) + 0.5) / 9007199254740992.0; // (0, 1)
  const double u2 = double(b >> 11) / 9007199254740992.0;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

/// Fraction (0..1) of the voxel at offset (x, y, z) from the centre inside the object.
inline double InsideFraction(const Phantom& ph, double x, double y, double z)
{
  if (ph.Form == Shape::Cube) // faces halfway between voxels: exactly 0 or 1
    return std::abs(x) < ph.Size && std::abs(y) < ph.Size && std::abs(z) < ph.Size ? 1.0 : 0.0;
  return dsphantom::SphereInsideFraction(x, y, z, ph.Size);
}

/// The phantom's value at offset (x, y, z) from the centre, before noise.
inline double CleanValue(const Phantom& ph, double x, double y, double z)
{
  double v = ph.Background() + ph.Contrast() * InsideFraction(ph, x, y, z);
  const double off = 0.36 * ph.N, b = ph.BlockSize;
  if (b > 0 && std::abs(x - off) < b && std::abs(y - off) < b && std::abs(z) < b)
    v += ph.BlockContrast;
  return v;
}

/// The near-start scene at n^3 (see the file's comment).
inline Phantom NearScene(int n)
{
  Phantom ph;
  ph.N = n;
  ph.Form = Shape::Sphere;
  ph.Size = n / 4.0;
  ph.CT = true;
  ph.CTBackground = 100;
  ph.CTContrast = 1000;
  ph.BlockSize = n / 10.0;
  ph.BlockContrast = 600;
  ph.Noise = 60.0 / ph.CTContrast;
  ph.Seed = 5;
  ph.Name = "ball+block " + std::to_string(n) + "^3";
  return ph;
}

template <typename T>
void FillPhantom(const Phantom& ph, T* out)
{
  const int n = ph.N;
  const double c = 0.5 * (n - 1);
  vtkSMPTools::For(0, static_cast<vtkIdType>(n) * n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType row = begin; row < end; ++row)
      {
        const int j = static_cast<int>(row % n), k = static_cast<int>(row / n);
        for (int i = 0; i < n; ++i)
        {
          const std::uint64_t index = static_cast<std::uint64_t>(row) * n + i;
          double v = CleanValue(ph, i - c, j - c, k - c);
          if (ph.Noise > 0)
            v += ph.Noise * ph.Contrast() * HashNormal(index, ph.Seed);
          if (ph.CT)
            v = std::round(std::min(65535.0, std::max(0.0, v)));
          out[index] = static_cast<T>(v);
        }
      }
    });
}

/// The phantom as an image with the point array "density" as active scalars.
inline vtkSmartPointer<vtkImageData> MakeImage(const Phantom& ph)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(ph.N, ph.N, ph.N);
  vtkSmartPointer<vtkDataArray> values;
  const vtkIdType count = static_cast<vtkIdType>(ph.Voxels());
  if (ph.CT)
  {
    auto a = vtkSmartPointer<vtkUnsignedShortArray>::New();
    a->SetNumberOfTuples(count);
    FillPhantom(ph, a->GetPointer(0));
    values = a;
  }
  else
  {
    auto a = vtkSmartPointer<vtkFloatArray>::New();
    a->SetNumberOfTuples(count);
    FillPhantom(ph, a->GetPointer(0));
    values = a;
  }
  values->SetName("density");
  image->GetPointData()->SetScalars(values);
  return image;
}

/// Analytic |distance| to the phantom's boundary.
inline DistanceFunction Distance(const Phantom& ph)
{
  const int n = ph.N;
  const double s = ph.Size;
  if (ph.Form == Shape::Sphere)
    return [n, s](const Point& p) { return dsphantom::SphereDistance(p, n, s); };
  return [n, s](const Point& p) { return dsphantom::CubeDistance(p, n, s); };
}
} // namespace dsbench

#endif
