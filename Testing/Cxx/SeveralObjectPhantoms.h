// SPDX-License-Identifier: BSD-3-Clause
// The phantoms of several objects in one run (docs/METHOD.md §9.9), shared by TestSeveralObjects
// and BenchObjects; rendered like the one-click phantoms (ObjectPhantoms.h: partial volume at
// every edge, Gaussian noise per voxel). Each returns the image a user sees, the label reference
// (only ever used to score) and one click per object, placed from the generator's geometry (what
// the user sees), never read off the labels.
//
// Assembly (industrial CT, float "CT", 1 mm, 64 x 48 x 48 voxels, origin 0): two blocks of the
// same material, 100, x in [10, 31.5) and [32.5, 54), y and z in [10.3, 38.3), joined by a glue
// line one voxel thick (x in [31.5, 32.5)) 30 % darker, 70, in air 0; noise s.d. 5 (seed 2501).
// Labels 1 and 2: the blocks (the glue line is 0).
//
// Engine (industrial CT, float "CT", 1 mm, 72 x 56 x 48 voxels, origin 0): a block of 100, x in
// [8.3, 64.3), y in [8.3, 48.3), z in [8.3, 40.3), with two bores along z of radius 9 through it,
// centred at (22.3, 28.3) and (50.3, 28.3); in each a piston of 100 and radius 8 (one voxel of
// air around it), z in [12.3, 36.3); air 0; noise s.d. 5 (seed 2502). Labels 1 the block, 2 and
// 3 the pistons.
//
// Tube and slab (MRI-like, float "T1", 1 mm, 144 x 112 x 64 voxels, origin 0): a dark ball (20) of
// radius 7 at (26.3, 20.3, 32.3) with a tube three voxels wide along +y reaching 22 voxels beyond
// the ball's surface (a rounded tip), and a bright slab (120) filling x from 48.3 on, cut by the
// image's faces; in a surround of 70; noise s.d. 4 (seed 2503). Labels 1 the ball and tube, 2
// the slab.
#ifndef SeveralObjectPhantoms_h
#define SeveralObjectPhantoms_h

#include "ObjectPhantoms.h"

#include <vector>

namespace dsobjects
{
/// A phantom of several objects: ObjectPhantom with one click per object (Clicks[i] clicks label
/// Labels[i]).
struct SeveralPhantom
{
  ObjectPhantom Phantom;
  std::vector<Point3> Clicks;
  std::vector<int> Labels;
};

namespace assembly
{
constexpr int Dims[3] = { 64, 48, 48 };
constexpr double Spacing[3] = { 1.0, 1.0, 1.0 };
constexpr double Left[2] = { 10.0, 31.5 }, Right[2] = { 32.5, 54.0 }, Side[2] = { 10.3, 38.3 };
constexpr double Material = 100, Glue = 70, Air = 0, Noise = 5;
constexpr unsigned Seed = 2501;

inline bool Within(double v, const double range[2])
{
  return v >= range[0] && v < range[1];
}

inline Sample At(double x, double y, double z)
{
  if (!Within(y, Side) || !Within(z, Side) || x < Left[0] || x >= Right[1])
    return { Air, 0, 0 };
  if (Within(x, Left))
    return { Material, 1, 1 };
  if (Within(x, Right))
    return { Material, 2, 1 };
  return { Glue, 0, 2 };
}
} // namespace assembly

/// The assembly phantom; a click in the middle of each block.
inline SeveralPhantom AssemblyPhantom()
{
  SeveralPhantom s;
  s.Phantom = RenderPhantom<vtkFloatArray>("assembly", "CT", assembly::Dims, assembly::Spacing,
    assembly::At, assembly::Noise, assembly::Seed);
  const double mid = 0.5 * (assembly::Side[0] + assembly::Side[1]);
  s.Clicks = { { 0.5 * (assembly::Left[0] + assembly::Left[1]), mid, mid },
    { 0.5 * (assembly::Right[0] + assembly::Right[1]), mid, mid } };
  s.Labels = { 1, 2 };
  return s;
}

namespace engine
{
constexpr int Dims[3] = { 72, 56, 48 };
constexpr double Spacing[3] = { 1.0, 1.0, 1.0 };
constexpr double Low[3] = { 8.3, 8.3, 8.3 }, High[3] = { 64.3, 48.3, 40.3 };
constexpr double BoreX[2] = { 22.3, 50.3 }, BoreY = 28.3, BoreRadius = 9.0;
constexpr double PistonRadius = 8.0, PistonLow = 12.3, PistonHigh = 36.3;
constexpr double Material = 100, Air = 0, Noise = 5;
constexpr unsigned Seed = 2502;

inline Sample At(double x, double y, double z)
{
  for (int b = 0; b < 2; ++b)
  {
    const double r = std::hypot(x - BoreX[b], y - BoreY);
    if (r < PistonRadius && z >= PistonLow && z < PistonHigh)
      return { Material, 2 + b, 1 };
    if (r < BoreRadius)
      return { Air, 0, 0 };
  }
  const bool block =
    x >= Low[0] && x < High[0] && y >= Low[1] && y < High[1] && z >= Low[2] && z < High[2];
  return block ? Sample{ Material, 1, 1 } : Sample{ Air, 0, 0 };
}
} // namespace engine

/// The engine phantom; Clicks[0] is unused (the block is seeded from picks), a click in the
/// middle of each piston.
inline SeveralPhantom EnginePhantom()
{
  SeveralPhantom s;
  s.Phantom = RenderPhantom<vtkFloatArray>(
    "engine", "CT", engine::Dims, engine::Spacing, engine::At, engine::Noise, engine::Seed);
  const double midZ = 0.5 * (engine::PistonLow + engine::PistonHigh);
  s.Clicks = { { 0, 0, 0 }, { engine::BoreX[0], engine::BoreY, midZ },
    { engine::BoreX[1], engine::BoreY, midZ } };
  s.Labels = { 1, 2, 3 };
  return s;
}

/// The picks a user makes for the engine's block: its eight corners, and eight points around
/// each bore's rim on the top and bottom faces (on the bore's wall): ObjectId 1.
inline std::vector<Point3> EngineBlockPicks()
{
  std::vector<Point3> picks;
  for (int c = 0; c < 8; ++c)
    picks.push_back({ c & 1 ? engine::High[0] : engine::Low[0],
      c & 2 ? engine::High[1] : engine::Low[1], c & 4 ? engine::High[2] : engine::Low[2] });
  for (int b = 0; b < 2; ++b)
    for (double z : { engine::Low[2], engine::High[2] })
      for (int k = 0; k < 8; ++k)
        picks.push_back({ engine::BoreX[b] + engine::BoreRadius * std::cos(k * M_PI / 4),
          engine::BoreY + engine::BoreRadius * std::sin(k * M_PI / 4), z });
  return picks;
}

namespace tubeslab
{
constexpr int Dims[3] = { 144, 112, 64 };
constexpr double Spacing[3] = { 1.0, 1.0, 1.0 };
constexpr Point3 Centre = { 26.3, 20.3, 32.3 }; ///< the ball's
constexpr double Radius = 7.0;
constexpr double TubeWidth = 3.0, TubeLength = 22.0; ///< voxels; its length beyond the ball
constexpr double SlabX = 48.3;
constexpr double Dark = 20, Surround = 70, Bright = 120, Noise = 4;
constexpr unsigned Seed = 2503;

/// Distance of p from the tube's axis segment, from the ball's centre along +y to its tip less
/// the radius (the rounded tip reaches TubeLength beyond the ball's surface).
inline double TubeAxisDistance(const Point3& p)
{
  const double tip = Centre[1] + Radius + TubeLength - 0.5 * TubeWidth;
  const double y = std::min(tip, std::max(Centre[1], p[1]));
  return std::sqrt((p[0] - Centre[0]) * (p[0] - Centre[0]) + (p[1] - y) * (p[1] - y) +
    (p[2] - Centre[2]) * (p[2] - Centre[2]));
}

inline Sample At(double x, double y, double z)
{
  const Point3 p = { x, y, z };
  if (TubeAxisDistance(p) < 0.5 * TubeWidth ||
    std::hypot(x - Centre[0], y - Centre[1], z - Centre[2]) < Radius)
    return { Dark, 1, 1 };
  return x >= SlabX ? Sample{ Bright, 2, 2 } : Sample{ Surround, 0, 0 };
}
} // namespace tubeslab

/// The tube and slab phantom; a click at the ball's centre and one in the slab, ten voxels from
/// its face.
inline SeveralPhantom TubeSlabPhantom()
{
  SeveralPhantom s;
  s.Phantom = RenderPhantom<vtkFloatArray>("tube and slab", "T1", tubeslab::Dims, tubeslab::Spacing,
    tubeslab::At, tubeslab::Noise, tubeslab::Seed);
  s.Clicks = { tubeslab::Centre, { tubeslab::SlabX + 10.0, 56.3, tubeslab::Centre[2] } };
  s.Labels = { 1, 2 };
  return s;
}

/// The spine phantom (ObjectPhantoms.h) with a click in the middle of vertebrae 2, 3 and 4.
inline SeveralPhantom SpineThreeClicks()
{
  SeveralPhantom s;
  s.Phantom = SpinePhantom();
  for (int v = 2; v <= 4; ++v)
  {
    s.Clicks.push_back(
      { spine::CentreX, spine::CentreY, spine::BodyBottom(v) + 0.5 * spine::Height });
    s.Labels.push_back(v);
  }
  return s;
}
} // namespace dsobjects

#endif
