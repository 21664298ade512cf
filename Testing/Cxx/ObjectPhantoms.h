// SPDX-License-Identifier: BSD-3-Clause
// The one-click phantoms (docs/METHOD.md §9.3): homogeneous objects that are not a
// brain, shared by TestObjectPhantoms, TestOneClickObjects and BenchObjects. Each generator
// returns the image a user sees (a named scalar array: ParaView crashes on unnamed ones), the
// per-voxel label reference (only ever used to score) and the click a user would make (computed
// from the generator's geometry: what the user sees, never read off the label).
//
// Partial volume: a voxel on an edge is the mean of samples spread over it (4 per smallest
// spacing along each axis); its label is the object holding at least half of them (Render). Noise
// is added per voxel afterwards (white, Gaussian: Box-Muller on std::mt19937, which the C++
// standard fixes bit for bit).
//
// Spine (CT, int16 HU "CT", 3 mm isotropic voxels as an abdominal CT, 32 x 28 x 62
// voxels, origin 0): five vertebral bodies stacked along z, elliptic cylinders of semi-axes
// 21 x 16 mm and 27 mm (9 slices) high, one above the other every 33 mm, separated by discs of
// 80 HU 6 mm (2 slices) thick (ellipse 22 x 17 mm: a slight bulge); discs also fill the 10.8 and
// 14.7 mm beyond the outer two. A body: a cortical rim of 600 HU one voxel (3 mm) thick at the
// sides, top and bottom, cancellous interior 275 + 125 t HU with t a smooth texture in [-1, 1]
// (150-400). Around it: fat -100 HU in front (y < 34 mm), soft tissue 50 HU elsewhere. Noise
// s.d. 60 HU on every voxel (seed 2401). The stack starts 0.1 slice off the voxel grid (0.3 mm:
// a disc is then one voxel of 80 and one of 132 HU, ~10 % endplate) and the bodies' axis 0.12
// voxel off it in x and y (48.35, 42.35 mm), so every edge has partial volume. Labels 1-5:
// the vertebrae from the bottom; the middle one (3) is the object clicked.
//
// Horned (MRI-like, float "T1", 1 mm, 128 x 128 x 64 voxels, origin 0): a dark ventricle-like
// body (ellipsoid of semi-axes 7 x 12 x 6 mm) of value 20 with four horns, tubes of widths 4,
// 3, 2 and 3 voxels reaching 30, 25, 40 and 35 voxels beyond the body's surface in four
// oblique directions, in a surround of 70; noise s.d. 4 (seed 2402). Label 1: body and horns.
#ifndef ObjectPhantoms_h
#define ObjectPhantoms_h

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

namespace dsobjects
{
using Point3 = std::array<double, 3>;

/// A phantom: the image, its label reference (same grid, unsigned char "Label", 0 = none), the
/// label of the object a user clicks, and the click (world coordinates).
struct ObjectPhantom
{
  std::string Name;
  vtkSmartPointer<vtkImageData> Image;
  vtkSmartPointer<vtkImageData> Label;
  int ObjectLabel = 1;
  Point3 Click = { 0, 0, 0 };
};

/// What one sample point holds: its intensity, its label (0 = background) and its material
/// (two samples of one material and label lie in the same smooth region).
struct Sample
{
  double Value = 0;
  int Label = 0;
  int Material = 0;
};
using SampleFunction = std::function<Sample(double x, double y, double z)>;

/// Gaussian noise, reproducible everywhere: Box-Muller on mt19937 (fixed by the standard;
/// std::normal_distribution is not).
class GaussianNoise
{
public:
  explicit GaussianNoise(unsigned seed)
    : Engine(seed)
  {
  }
  double Next(double sd)
  {
    const double u1 = (Engine() + 1.0) / 4294967297.0, u2 = Engine() / 4294967296.0;
    return sd * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

private:
  std::mt19937 Engine;
};

/// True when the 3 x 3 x 3 points spanning voxel (i, j, k) (its centre, face centres, edges and
/// corners, half a voxel apart) hold one material and label: no feature of the phantoms is
/// thinner than half a voxel, so none can pass between them, and the voxel is pure.
inline bool PureVoxel(int i, int j, int k, const double spacing[3], const SampleFunction& sample)
{
  const Sample centre = sample(i * spacing[0], j * spacing[1], k * spacing[2]);
  for (int c = -1; c <= 1; ++c)
    for (int b = -1; b <= 1; ++b)
      for (int a = -1; a <= 1; ++a)
      {
        const Sample s = sample(
          (i + 0.5 * a) * spacing[0], (j + 0.5 * b) * spacing[1], (k + 0.5 * c) * spacing[2]);
        if (s.Label != centre.Label || s.Material != centre.Material)
          return false;
      }
  return true;
}

/// Renders sample() over the grid with partial volume and labels, then adds noise of s.d.
/// noiseSd (one draw per voxel, i fastest). A voxel straddling an edge is the mean of 4 samples
/// per smallest spacing along each axis (4 x 4 x 12 on 1 x 1 x 3 mm voxels) and has the label
/// of at least half of them (else 0); a pure voxel (PureVoxel) is its centre's value and label
/// (the phantoms' values vary smoothly within a material).
inline void Render(const int dims[3], const double spacing[3], const SampleFunction& sample,
  double noiseSd, unsigned seed, std::vector<double>& values, std::vector<unsigned char>& labels)
{
  const double finest = std::min({ spacing[0], spacing[1], spacing[2] });
  int S[3];
  for (int a = 0; a < 3; ++a)
    S[a] = 4 * static_cast<int>(std::lround(spacing[a] / finest));
  const int total = S[0] * S[1] * S[2];
  const size_t n = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  values.assign(n, 0.0);
  labels.assign(n, 0);
  GaussianNoise noise(seed);
  std::vector<int> votes(256);
  size_t v = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i, ++v)
      {
        if (PureVoxel(i, j, k, spacing, sample))
        {
          const Sample s = sample(i * spacing[0], j * spacing[1], k * spacing[2]);
          values[v] = s.Value + noise.Next(noiseSd);
          labels[v] = static_cast<unsigned char>(s.Label);
          continue;
        }
        std::fill(votes.begin(), votes.end(), 0);
        double sum = 0;
        for (int c = 0; c < S[2]; ++c)
          for (int b = 0; b < S[1]; ++b)
            for (int a = 0; a < S[0]; ++a)
            {
              const Sample s = sample((i + (a + 0.5) / S[0] - 0.5) * spacing[0],
                (j + (b + 0.5) / S[1] - 0.5) * spacing[1],
                (k + (c + 0.5) / S[2] - 0.5) * spacing[2]);
              sum += s.Value;
              ++votes[s.Label];
            }
        values[v] = sum / total + noise.Next(noiseSd);
        for (int l = 1; l < 256; ++l)
          if (2 * votes[l] >= total)
            labels[v] = static_cast<unsigned char>(l);
      }
}

inline vtkSmartPointer<vtkImageData> MakeGrid(const int dims[3], const double spacing[3])
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims[0], dims[1], dims[2]);
  image->SetSpacing(spacing[0], spacing[1], spacing[2]);
  image->SetOrigin(0, 0, 0);
  return image;
}

inline vtkSmartPointer<vtkImageData> LabelImage(
  const int dims[3], const double spacing[3], const std::vector<unsigned char>& labels)
{
  auto image = MakeGrid(dims, spacing);
  vtkSmartPointer<vtkUnsignedCharArray> a = vtkSmartPointer<vtkUnsignedCharArray>::New();
  a->SetName("Label");
  a->SetNumberOfTuples(static_cast<vtkIdType>(labels.size()));
  std::copy(labels.begin(), labels.end(), a->GetPointer(0));
  image->GetPointData()->SetScalars(a);
  return image;
}

//------------------------------------------------------------------------------
// Spine
namespace spine
{
constexpr int Dims[3] = { 32, 28, 62 };
constexpr double Spacing[3] = { 3.0, 3.0, 3.0 };
constexpr double CentreX = 48.35, CentreY = 42.35; ///< the bodies' axis, mm
constexpr double SemiX = 21.0, SemiY = 16.0;       ///< a body's ellipse, mm
constexpr double DiscBulge = 1.0;                  ///< a disc's ellipse: the body's + this, mm
constexpr double Rim = 3.0, Endplate = 3.0;        ///< cortical thickness at sides / top, mm
constexpr double Height = 27.0, Disc = 6.0;        ///< a body's height, a disc's thickness, mm
constexpr double Bottom = 10.5 + 0.3; ///< the lowest body's bottom: 0.3 mm above slice 4's face
constexpr int Vertebrae = 5, Middle = 3;
constexpr double CorticalHU = 600, DiscHU = 80, SoftHU = 50, FatHU = -100;
constexpr double CancellousMeanHU = 275, CancellousSpreadHU = 125, NoiseHU = 60;
constexpr double FatFront = 34.0; ///< fat where y < this, mm
constexpr unsigned Seed = 2401;

inline double BodyBottom(int vertebra) // 1-based
{
  return Bottom + (vertebra - 1) * (Height + Disc);
}

/// The cancellous texture: smooth, in [-1, 1].
inline double Texture(double x, double y, double z)
{
  return 0.5 * std::sin(2 * M_PI * x / 17.0) * std::cos(2 * M_PI * y / 13.0) +
    0.5 * std::sin(2 * M_PI * z / 23.0 + 1.0);
}

inline double EllipseRadius(double x, double y, double a, double b)
{
  const double u = (x - CentreX) / a, w = (y - CentreY) / b;
  return std::sqrt(u * u + w * w);
}

inline Sample At(double x, double y, double z)
{
  const double outside = y < FatFront ? FatHU : SoftHU;
  for (int v = 1; v <= Vertebrae; ++v)
  {
    const double z0 = BodyBottom(v), z1 = z0 + Height;
    if (z >= z0 && z < z1 && EllipseRadius(x, y, SemiX, SemiY) < 1.0)
    {
      const bool cortical = z < z0 + Endplate || z >= z1 - Endplate ||
        EllipseRadius(x, y, SemiX - Rim, SemiY - Rim) >= 1.0;
      const double hu =
        cortical ? CorticalHU : CancellousMeanHU + CancellousSpreadHU * Texture(x, y, z);
      return { hu, v, cortical ? 3 : 4 };
    }
  }
  // Between and beyond the bodies: disc wherever inside the (slightly wider) disc ellipse.
  if (EllipseRadius(x, y, SemiX + DiscBulge, SemiY + DiscBulge) < 1.0)
    return { DiscHU, 0, 2 };
  return { outside, 0, y < FatFront ? 0 : 1 };
}
} // namespace spine

/// A phantom rendered by Render, its values stored in an array of type ArrayT named name
/// (integer types: rounded to the nearest), with its labels.
template <typename ArrayT, typename SampleT>
ObjectPhantom RenderPhantom(const std::string& name, const char* arrayName, const int dims[3],
  const double spacing[3], SampleT sample, double noiseSd, unsigned seed)
{
  std::vector<double> values;
  std::vector<unsigned char> labels;
  Render(dims, spacing, sample, noiseSd, seed, values, labels);
  ObjectPhantom p;
  p.Name = name;
  p.Image = MakeGrid(dims, spacing);
  vtkSmartPointer<ArrayT> a = vtkSmartPointer<ArrayT>::New();
  a->SetName(arrayName);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  using T = typename ArrayT::ValueType;
  for (size_t v = 0; v < values.size(); ++v)
    a->SetValue(static_cast<vtkIdType>(v),
      std::is_integral<T>::value ? static_cast<T>(std::lround(values[v]))
                                 : static_cast<T>(values[v]));
  p.Image->GetPointData()->SetScalars(a);
  p.Label = LabelImage(dims, spacing, labels);
  return p;
}

/// The spine phantom (see the file comment); the click: the middle of the middle body.
inline ObjectPhantom SpinePhantom()
{
  ObjectPhantom p = RenderPhantom<vtkShortArray>(
    "spine", "CT", spine::Dims, spine::Spacing, spine::At, spine::NoiseHU, spine::Seed);
  p.ObjectLabel = spine::Middle;
  p.Click = { spine::CentreX, spine::CentreY,
    spine::BodyBottom(spine::Middle) + 0.5 * spine::Height };
  return p;
}

//------------------------------------------------------------------------------
// Horned
namespace horned
{
constexpr int Dims[3] = { 128, 128, 64 };
constexpr double Spacing[3] = { 1.0, 1.0, 1.0 };
constexpr Point3 Centre = { 64.3, 60.3, 32.3 };
constexpr Point3 Semi = { 7.0, 12.0, 6.0 };
constexpr double BodyValue = 20, SurroundValue = 70, Noise = 4;
constexpr unsigned Seed = 2402;
constexpr double Inset = 3.0; ///< a horn's axis starts this far inside the body's surface

/// A horn: its direction from the body's centre (not normalised), width and the length it
/// reaches beyond the body's surface, in voxels.
struct Horn
{
  Point3 Direction;
  double Width, Length;
};
constexpr int Horns = 4;
constexpr Horn HornList[Horns] = { { { 0.35, 1.0, 0.15 }, 4.0, 30.0 },
  { { -0.35, 1.0, 0.15 }, 3.0, 25.0 }, { { 0.5, -1.0, -0.2 }, 2.0, 40.0 },
  { { -0.5, -1.0, -0.2 }, 3.0, 35.0 } };

inline Point3 UnitDirection(int h)
{
  const Point3& d = HornList[h].Direction;
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  return { d[0] / n, d[1] / n, d[2] / n };
}

/// Distance from the body's centre to its surface along horn h's direction.
inline double SurfaceDistance(int h)
{
  const Point3 d = UnitDirection(h);
  double s = 0;
  for (int a = 0; a < 3; ++a)
    s += (d[a] / Semi[a]) * (d[a] / Semi[a]);
  return 1.0 / std::sqrt(s);
}

/// The horn's axis segment [t0, t1] along its direction from the centre: from Inset inside the
/// surface to its tip less the radius (the rounded tip reaches Length beyond the surface).
inline void AxisSegment(int h, double& t0, double& t1)
{
  t0 = SurfaceDistance(h) - Inset;
  t1 = SurfaceDistance(h) + HornList[h].Length - 0.5 * HornList[h].Width;
}

/// Distance of p from horn h's axis segment, and (t) where along it the nearest point lies.
inline double AxisDistance(int h, const Point3& p, double* t = nullptr)
{
  const Point3 d = UnitDirection(h);
  double t0, t1;
  AxisSegment(h, t0, t1);
  double along = 0;
  for (int a = 0; a < 3; ++a)
    along += (p[a] - Centre[a]) * d[a];
  const double c = std::min(t1, std::max(t0, along));
  if (t)
    *t = along;
  double s = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double q = p[a] - Centre[a] - c * d[a];
    s += q * q;
  }
  return std::sqrt(s);
}

inline Sample At(double x, double y, double z)
{
  const Point3 p = { x, y, z };
  double e = 0;
  for (int a = 0; a < 3; ++a)
    e += ((p[a] - Centre[a]) / Semi[a]) * ((p[a] - Centre[a]) / Semi[a]);
  bool inside = e < 1.0;
  for (int h = 0; h < Horns && !inside; ++h)
    inside = AxisDistance(h, p) < 0.5 * HornList[h].Width;
  return inside ? Sample{ BodyValue, 1, 1 } : Sample{ SurroundValue, 0, 0 };
}
} // namespace horned

/// The horned phantom (see the file comment); the click: the body's centre.
inline ObjectPhantom HornedPhantom()
{
  ObjectPhantom p = RenderPhantom<vtkFloatArray>(
    "horned", "T1", horned::Dims, horned::Spacing, horned::At, horned::Noise, horned::Seed);
  p.ObjectLabel = 1;
  p.Click = horned::Centre;
  return p;
}

//------------------------------------------------------------------------------
// Bright ball (MRI-like, float "T1", 1 mm, 64^3 voxels, origin 0): a ball of radius 16 and value
// 120 centred off the grid at (32.3, 32.2, 32.1) in a surround of 70, noise s.d. 4 (seed 2601).
// Label 1: the ball. Clicked d voxels inside its face along +x (BenchNearFace, TestNearFaceClick).
namespace brightball
{
constexpr int Dims[3] = { 64, 64, 64 };
constexpr double Spacing[3] = { 1.0, 1.0, 1.0 };
constexpr Point3 Centre = { 32.3, 32.2, 32.1 };
constexpr double Radius = 16.0, Bright = 120, Surround = 70, Noise = 4;
constexpr unsigned Seed = 2601;

inline Sample At(double x, double y, double z)
{
  const bool in = std::hypot(x - Centre[0], y - Centre[1], z - Centre[2]) < Radius;
  return in ? Sample{ Bright, 1, 1 } : Sample{ Surround, 0, 0 };
}
} // namespace brightball

/// The bright ball; the click: d voxels inside its face along +x.
inline ObjectPhantom BrightBall(double d)
{
  ObjectPhantom p = RenderPhantom<vtkFloatArray>("ball", "T1", brightball::Dims,
    brightball::Spacing, brightball::At, brightball::Noise, brightball::Seed);
  p.ObjectLabel = 1;
  p.Click = { brightball::Centre[0] + brightball::Radius - d, brightball::Centre[1],
    brightball::Centre[2] };
  return p;
}
} // namespace dsobjects

#endif
