// SPDX-License-Identifier: BSD-3-Clause
// A fine level's field kept only in bricks around the surface (dsFieldBricks.h): at the
// surface's vertices, within its reach and across brick seams it equals the field over the
// whole box bit for bit (tolerance 0: a brick computes every value exactly as the box does);
// it holds less memory than the box's field (the share falls as the surface grows against a
// brick); a point in a brick not computed yet feels no
// force and is counted as a miss, not as outside the image, until Cover computes its brick; a
// point outside the level's box but inside the image is not outside the image; a whole solve
// of a phantom never samples a missing brick, nor does a seed that the region force grows far
// on a first level in bricks; the bricks a travelling surface left behind are dropped once the
// whole field's size is reached, and equal it when computed again; G_sigma * f smoothed in slabs
// and kept in tiles near the surface equals the whole field's bit for bit, and is smoothed again
// when the surface moves past its tiles; so does the locally normalised P kept in tiles.
#include "DSTestHelpers.h"
#include "ScaleSpaceTestUtils.h"
#include "TestSolverMeshes.h"

#include "dsFieldBricks.h"
#include "dsFieldGrid.h"
#include "dsMultilevel.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

using namespace dsurf;

namespace
{
/// The largest |F_a - F_b| and |P_a - P_b| over the points.
double LargestDifference(const ForceField& a, const ForceField& b, const std::vector<Vec3>& points)
{
  double worst = 0;
  for (const Vec3& p : points)
  {
    double fa[3], fb[3];
    a.SampleForce(p.data(), fa);
    b.SampleForce(p.data(), fb);
    for (int k = 0; k < 3; ++k)
    {
      worst = std::max(worst, std::abs(fa[k] - fb[k]));
    }
    worst = std::max(worst, std::abs(a.SamplePotential(p.data()) - b.SamplePotential(p.data())));
  }
  return worst;
}

/// The vertices of `surface` moved by -reach .. +reach along the radius from c, and (seams) the
/// points of a line through several brick seams that lie within the reach of a vertex.
std::vector<Vec3> PointsWithinReach(
  const TriangleMesh& surface, const Vec3& c, double reach, bool seams = true)
{
  std::vector<Vec3> points;
  for (const Vec3& p : surface.Points)
  {
    const Vec3 u = (1.0 / Norm(p - c)) * (p - c);
    for (double t = -reach; t <= reach + 1e-9; t += 0.37)
    {
      points.push_back(p + t * u);
    }
  }
  // The line crosses x = 48, 64, ... seams; Cover promises the field only within the reach.
  for (double x = c[0] - 30.0; seams && x <= c[0] + 30.0; x += 0.1)
  {
    const Vec3 q{ x, c[1] + 21.0, c[2] + 0.3 };
    const bool near = std::any_of(surface.Points.begin(), surface.Points.end(),
      [&](const Vec3& v) { return Norm(q - v) <= reach; });
    if (near)
    {
      points.push_back(q);
    }
  }
  return points;
}

/// The field at sigma (two threads) over the surface's neighbourhood box, whole and in bricks
/// around the surface; returns the box.
VoxelBox WholeAndBricked(const ImageView& view, const TriangleMesh& surface, double sigma,
  ForceField& whole, ForceField& bricked)
{
  ScaleSpaceParameters p;
  p.Sigma = sigma;
  p.NumberOfThreads = 2;
  const VoxelBox box = SurfaceNeighbourhood(surface, view.Geometry, NeighbourhoodSigmas * sigma);
  std::string error;
  DS_CHECK(ComputeForceAtScale(view, box, p, whole, &error), error);
  DS_CHECK(ComputeForceAtScale(view, box, p, bricked, &error, &surface), error);
  return box;
}

/// On an anisotropic grid turned about x (a direction matrix: every term of the gradient's map
/// to world), the bricks equal the whole box's field bit for bit within the reach.
void TurnedGrid()
{
  ImageGeometry g;
  g.Dimensions[0] = g.Dimensions[1] = g.Dimensions[2] = 96;
  g.Spacing[1] = 1.1;
  g.Spacing[2] = 0.9;
  const double c = std::cos(0.5), s = std::sin(0.5);
  const double rotation[9] = { 1, 0, 0, 0, c, -s, 0, s, c };
  std::copy(rotation, rotation + 9, g.Direction);
  const double middle[3] = { 47.5, 47.5, 47.5 };
  double w[3];
  g.IndexToWorld(middle, w);
  const Vec3 centre{ w[0], w[1], w[2] };
  const std::vector<float> image = sstest::SoftBall(g, centre.data(), 25.0);
  const TriangleMesh surface = dstest::MakeIcosphere(3, 26.0, centre);
  const double sigma = 1.5;
  ForceField whole, bricked;
  WholeAndBricked(ImageView::Of(image.data(), g), surface, sigma, whole, bricked);
  std::vector<Vec3> points; // the vertices moved within the reach along the radius
  for (const Vec3& v : surface.Points)
  {
    const Vec3 u = (1.0 / Norm(v - centre)) * (v - centre);
    for (double t = -BrickReachSigmas * sigma; t <= BrickReachSigmas * sigma; t += 0.37)
    {
      points.push_back(v + t * u);
    }
  }
  DS_CHECK(bricked.Bricks && LargestDifference(bricked, whole, points) == 0.0 &&
      bricked.Bricks->Misses() == 0,
    "a turned anisotropic grid: bricked = whole-box field bit for bit within the reach");
}
/// The field at sigma (two threads) over the whole image, and in bricks whose G_sigma * f is
/// smoothed in slabs of coreSlices and kept in tiles near `surface` (`threads`); returns the
/// bricks.
std::shared_ptr<FieldBricks> WholeAndInSlabs(const ImageView& view, double sigma,
  const TriangleMesh& surface, int coreSlices, ForceField& whole, ForceField& slabs,
  int threads = 2, EdgeNormalization normalization = EdgeNormalization::GlobalMaximum)
{
  ScaleSpaceParameters p;
  p.Sigma = sigma;
  p.EdgeNormalization = normalization;
  p.NumberOfThreads = 2;
  std::string error;
  DS_CHECK(ComputeScaleSpaceForce(view, p, whole, &error), error);
  p.NumberOfThreads = threads;
  auto bricks = std::make_shared<FieldBricks>();
  DS_CHECK(
    bricks->InitializeInSlabs(view, p, BrickReachSigmas * sigma, surface, coreSlices, &error),
    error);
  bricks->Cover(surface);
  slabs.Geometry = view.Geometry;
  slabs.Sigma = sigma;
  slabs.Bricks = bricks;
  return bricks;
}

/// A soft ball of radius 25 in 90 x 84 x 70 voxels with z spacing 1.4, as floats and as uint16
/// (1000 + 800 f), and a sphere 1.5 outside it.
struct SlabScene
{
  ImageGeometry Geometry;
  Vec3 Centre{ 44.0, 41.5, 48.0 };
  std::vector<float> Ball;
  std::vector<unsigned short> Counts;
  TriangleMesh Surface;
  SlabScene()
  {
    this->Geometry.Dimensions[0] = 90;
    this->Geometry.Dimensions[1] = 84;
    this->Geometry.Dimensions[2] = 70;
    this->Geometry.Spacing[2] = 1.4;
    this->Ball = sstest::SoftBall(this->Geometry, this->Centre.data(), 25.0);
    for (float f : this->Ball)
    {
      this->Counts.push_back(static_cast<unsigned short>(std::lround(1000.0 + 800.0 * f)));
    }
    this->Surface = dstest::MakeIcosphere(3, 26.5, this->Centre);
  }
};

/// G_sigma * f smoothed in slabs and kept in tiles near the surface (FieldBricks::
/// InitializeInSlabs) against the whole image's field: bit for bit within the reach, with the
/// sampled and the recursive Gaussian along z, slabs of a few slices and the default, a float and
/// a uint16 image, an anisotropic grid; less memory than the box's G_sigma * f alone; a surface
/// moved past the tiles smooths the image again and still equals the whole field.
void InSlabs()
{
  const SlabScene scene;
  const ImageGeometry& g = scene.Geometry;
  const Vec3& c = scene.Centre;
  const std::vector<float>& ball = scene.Ball;
  const std::vector<unsigned short>& counts = scene.Counts;
  const TriangleMesh& surface = scene.Surface;
  // sigma 2: sampled along every axis; 3.5: recursive along x and y, sampled along z (2.5
  // voxels); 5: recursive along every axis.
  for (const double sigma : { 2.0, 3.5, 5.0 })
    for (const int core : { 5, 0 })
      for (const bool integers : { false, true })
      {
        const ImageView view =
          integers ? ImageView::Of(counts.data(), g) : ImageView::Of(ball.data(), g);
        ForceField whole, slabs;
        const auto bricks = WholeAndInSlabs(view, sigma, surface, core, whole, slabs);
        const double reach = BrickReachSigmas * sigma;
        const std::string what = "sigma " + std::to_string(sigma) + ", slabs of " +
          std::to_string(core) + (integers ? " slices, uint16" : " slices, float");
        DS_CHECK(LargestDifference(slabs, whole, PointsWithinReach(surface, c, reach)) == 0.0 &&
            bricks->Misses() == 0,
          what + ": in slabs = the whole field bit for bit within the reach");
      }

  // A box cut from the image (a view that is not contiguous: converted slab by slab), one thread
  // against the whole field's two; an image of 4 slices in slabs of 2, sigma recursive along
  // every axis; a piece's hooks refused.
  VoxelBox cut = VoxelBox::Whole(g);
  cut.Begin[0] = 7;
  cut.End[0] = 83;
  cut.Begin[2] = 3;
  cut.End[2] = 66;
  {
    const ImageView part = ImageView::Of(counts.data(), g).Box(cut);
    ForceField whole, slabs;
    const auto bricks = WholeAndInSlabs(part, 3.5, surface, 6, whole, slabs, 1);
    DS_CHECK(
      LargestDifference(slabs, whole, PointsWithinReach(surface, c, BrickReachSigmas * 3.5)) == 0.0,
      "a box cut from a uint16 image, one thread: in slabs = the whole field bit for bit");
  }
  {
    ImageGeometry thin;
    thin.Dimensions[0] = 40;
    thin.Dimensions[1] = 36;
    thin.Dimensions[2] = 4;
    const Vec3 t{ 19.0, 17.5, 1.5 };
    const std::vector<float> disc = sstest::SoftBall(thin, t.data(), 12.0);
    const TriangleMesh ring = dstest::MakeIcosphere(2, 12.5, t);
    ForceField whole, slabs;
    WholeAndInSlabs(ImageView::Of(disc.data(), thin), 3.5, ring, 2, whole, slabs);
    DS_CHECK(LargestDifference(
               slabs, whole, PointsWithinReach(ring, t, BrickReachSigmas * 3.5, false)) == 0.0,
      "4 slices in slabs of 2: in slabs = the whole field bit for bit");
  }
  {
    ScaleSpaceParameters hooked;
    hooked.Sigma = 2.0;
    hooked.Smooth = [](float*, const double*) {};
    std::string error;
    FieldBricks refused;
    DS_CHECK(
      !refused.InitializeInSlabs(ImageView::Of(ball.data(), g), hooked, 4.0, surface, 0, &error) &&
        !error.empty(),
      "a piece's Smooth hook is not smoothed in slabs: " + error);
  }

  // A larger ball against its image, sigma 1.5 voxels (reach 1.5): the tiles kept (the bricks of
  // the surface's points grown by two reaches, half a brick and a voxel, and a brick more) hold
  // 0.58 of the image's G_sigma * f; the surface moved 20 voxels, past them, smooths the image
  // again and still equals the whole field.
  ImageGeometry big;
  big.Dimensions[0] = big.Dimensions[1] = big.Dimensions[2] = 150;
  const Vec3 m{ 70.0, 74.5, 74.5 };
  const std::vector<float> image = sstest::SoftBall(big, m.data(), 50.0);
  const ImageView view = ImageView::Of(image.data(), big);
  const TriangleMesh sphere = dstest::MakeIcosphere(4, 50.5, m);
  ForceField whole, slabs;
  const double sigma = 1.5, reach = BrickReachSigmas * sigma;
  const auto bricks = WholeAndInSlabs(view, sigma, sphere, 0, whole, slabs);
  const double tiles = bricks->Bytes() -
    4.0 * sizeof(float) * std::pow(FieldBricks::BrickSize + 1.0, 3) * bricks->ComputedBricks();
  DS_CHECK_LE(tiles / (sizeof(float) * big.NumberOfVoxels()), 0.7,
    "G_sigma * f held in tiles near a ball of radius 50, against the image's");
  DS_CHECK(LargestDifference(slabs, whole, PointsWithinReach(sphere, m, reach)) == 0.0 &&
      bricks->Misses() == 0,
    "in slabs = the whole field bit for bit within the reach of a larger ball");
  const Vec3 moved = m + Vec3{ 20.0, 0.0, 0.0 };
  const TriangleMesh away = dstest::MakeIcosphere(4, 50.5, moved);
  bricks->Cover(away);
  DS_CHECK(bricks->SlabSmoothings() == 2 &&
      LargestDifference(slabs, whole, PointsWithinReach(away, moved, reach, false)) == 0.0 &&
      bricks->Misses() == 0,
    "a surface moved past the tiles smooths again, and equals the whole field");

  // A piece's maximum (dsPieceField.h) is asked for by the first smoothing only: the gains it
  // gave are kept when the tiles are smoothed again (here the image's own maximum, so the field
  // is still the whole one).
  ScaleSpaceParameters hooked;
  hooked.Sigma = sigma;
  hooked.NumberOfThreads = 2;
  for (int a = 0; a < 3; ++a)
  {
    hooked.MaximumEnd[a] = big.Dimensions[a];
  }
  int asked = 0;
  hooked.GradientMaximum = [&asked](double m)
  {
    ++asked;
    return m;
  };
  auto piece = std::make_shared<FieldBricks>();
  std::string error;
  DS_CHECK(piece->InitializeInSlabs(view, hooked, reach, sphere, 0, &error), error);
  piece->Cover(sphere);
  piece->Cover(away);
  ForceField pieceField;
  pieceField.Geometry = big;
  pieceField.Sigma = sigma;
  pieceField.Bricks = piece;
  DS_CHECK(asked == 1 && piece->SlabSmoothings() == 2 &&
      LargestDifference(pieceField, whole, PointsWithinReach(away, moved, reach, false)) == 0.0,
    "a piece's maximum asked for once over two smoothings in slabs, the field the whole one");
}
/// The locally normalised field (EdgeNormalization::Local) in bricks whose tiles hold P
/// (LocalPotentialAt at their voxels) against the whole image's: bit for bit within the reach,
/// both Gaussians sampled along z (sigma 1 and 2; the second recursive along x and y at 2), the
/// second recursive along z (3.5), both (5), slabs of a few slices and the default or one pass
/// over the box (a box of at most half the image), float and uint16, z spacing 1.4; a surface moved
/// past the tiles computes them again and still equals the whole field; a level's field around a
/// surface (ComputeForceAtScale) is kept in bricks with this normalisation too and equals the box's
/// whole field, and the memory count covers it.
void LocallyNormalisedTiles()
{
  const SlabScene scene;
  for (const double sigma : { 1.0, 2.0, 3.5, 5.0 })
    for (const int core : { 5, 0, -1 })
      for (const bool integers : { false, true })
      {
        const ImageView view = integers ? ImageView::Of(scene.Counts.data(), scene.Geometry)
                                        : ImageView::Of(scene.Ball.data(), scene.Geometry);
        ForceField whole, tiles;
        const auto bricks = WholeAndInSlabs(
          view, sigma, scene.Surface, core, whole, tiles, 2, EdgeNormalization::Local);
        const std::string what = "local normalisation, sigma " + std::to_string(sigma) +
          (core < 0 ? ", one pass" : ", slabs of " + std::to_string(core) + " slices") +
          (integers ? ", uint16" : ", float");
        DS_CHECK(
          LargestDifference(tiles, whole,
            PointsWithinReach(scene.Surface, scene.Centre, BrickReachSigmas * sigma)) == 0.0 &&
            bricks->Misses() == 0,
          what + ": P in tiles = the whole field bit for bit within the reach");
      }

  // A ball of radius 50 in a larger image (sigma 1): the tiles hold P near it; the scene.Surface
  // moved 20 voxels, past them, computes them again and still equals the whole field.
  {
    ImageGeometry big;
    big.Dimensions[0] = big.Dimensions[1] = big.Dimensions[2] = 150;
    const Vec3 m{ 70.0, 74.5, 74.5 };
    const std::vector<float> image = sstest::SoftBall(big, m.data(), 50.0);
    const TriangleMesh sphere = dstest::MakeIcosphere(4, 50.5, m);
    const double reach = BrickReachSigmas * 1.0;
    ForceField whole, tiles;
    const auto bricks = WholeAndInSlabs(
      ImageView::Of(image.data(), big), 1.0, sphere, 0, whole, tiles, 1, EdgeNormalization::Local);
    const double share = (bricks->Bytes() - FieldBricks::BrickBytes * bricks->ComputedBricks()) /
      (sizeof(float) * static_cast<double>(big.NumberOfVoxels()));
    std::cout << "local normalisation: P held in tiles near a ball of radius 50, " << share
              << " of one float a voxel of the image" << std::endl;
    const Vec3 moved = m + Vec3{ 20.0, 0.0, 0.0 };
    const TriangleMesh away = dstest::MakeIcosphere(4, 50.5, moved);
    bricks->Cover(away);
    DS_CHECK(bricks->SlabSmoothings() == 2 &&
        LargestDifference(tiles, whole, PointsWithinReach(away, moved, reach, false)) == 0.0 &&
        bricks->Misses() == 0,
      "local normalisation: a scene.Surface moved past the tiles computes them again, = the whole "
      "field");
  }

  ScaleSpaceParameters p;
  p.Sigma = 2.0;
  p.EdgeNormalization = EdgeNormalization::Local;
  p.NumberOfThreads = 2;
  const VoxelBox box =
    SurfaceNeighbourhood(scene.Surface, scene.Geometry, FieldReach(p.EdgeNormalization, p.Sigma));
  ForceField boxWhole, boxBricked;
  std::string error;
  const ImageView view = ImageView::Of(scene.Counts.data(), scene.Geometry);
  DS_CHECK(ComputeForceAtScale(view, box, p, boxWhole, &error), error);
  DS_CHECK(ComputeForceAtScale(view, box, p, boxBricked, &error, &scene.Surface), error);
  DS_CHECK(FieldInBricks(box, scene.Geometry, p) && boxBricked.Bricks &&
      boxWhole.Potential.size() > 0 &&
      LargestDifference(boxBricked, boxWhole,
        PointsWithinReach(scene.Surface, scene.Centre, BrickReachSigmas * p.Sigma)) == 0.0,
    "local normalisation: a level's box in bricks = its whole field bit for bit");
  DS_CHECK(FieldBytes(box, scene.Geometry, p, &scene.Surface) >= boxBricked.Bricks->Bytes(),
    "local normalisation: the memory count covers what the bricks hold once made");
}
} // namespace

int TestFieldBricks(int, char*[])
{
  ImageGeometry g;
  g.Dimensions[0] = g.Dimensions[1] = g.Dimensions[2] = 128;
  g.Origin[0] = -3.0;
  const Vec3 c{ 60.5, 63.5, 63.5 };
  const std::vector<float> image = sstest::SoftBall(g, c.data(), 30.0);
  const ImageView view = ImageView::Of(image.data(), g);
  const TriangleMesh surface = dstest::MakeIcosphere(3, 31.5, c);
  ScaleSpaceParameters p;
  p.Sigma = 2.0;
  p.NumberOfThreads = 2;
  ForceField whole, bricked;
  const VoxelBox box = WholeAndBricked(view, surface, p.Sigma, whole, bricked);
  std::string error;
  DS_CHECK(
    bricked.Bricks && whole.Potential.size() == static_cast<std::size_t>(box.NumberOfVoxels()),
    "the bricked field and the whole box's");
  const double reach = BrickReachSigmas * p.Sigma;
  DS_CHECK(LargestDifference(bricked, whole, PointsWithinReach(surface, c, reach)) == 0.0,
    "bricked = whole-box field bit for bit at the vertices, within the reach, across seams");
  DS_CHECK(bricked.Bricks->Misses() == 0, "no sample within the reach missed a brick");

  const double wholeBytes = 4.0 * sizeof(float) * static_cast<double>(whole.Potential.size());
  std::cout << "box " << box.NumberOfVoxels() << " voxels, " << bricked.Bricks->ComputedBricks()
            << " bricks; bytes: bricked " << bricked.Bricks->Bytes() << ", whole " << wholeBytes
            << std::endl;
  // 8^3-voxel bricks within 1 sigma + 1 voxel of a ball of radius 31.5: 446 of the box's 1 728
  // (0.26), 0.70 of its bytes with G_sigma * f over the box (4 of the 16 bytes a voxel); the
  // share falls as the ball grows against a brick (512^3 ball, radius 128: docs/SCALING.md).
  const double boxBricks =
    std::ceil((box.End[0] - box.Begin[0] - 1) / double(FieldBricks::BrickSize)) *
    std::ceil((box.End[1] - box.Begin[1] - 1) / double(FieldBricks::BrickSize)) *
    std::ceil((box.End[2] - box.Begin[2] - 1) / double(FieldBricks::BrickSize));
  DS_CHECK_LE(bricked.Bricks->ComputedBricks() / boxBricks, 0.35,
    "bricks computed, of the box's (8^3 voxels each)");
  DS_CHECK_LE(bricked.Bricks->Bytes() / wholeBytes, 0.8,
    "memory of the bricked field against the whole box's (16 bytes a voxel)");

  // The memory count of a field made around a surface (FieldBytes with it): what the field
  // holds once made, no less, and a fraction of the upper bound over the whole box; Cover checks
  // what it adds, and adds nothing the memory cannot hold.
  const double counted = FieldBytes(box, g, p, &surface);
  const double bound = FieldBytes(box, g, p);
  std::cout << "counted " << counted << " bytes, held " << bricked.Bricks->Bytes()
            << ", the box's bound " << bound << std::endl;
  DS_CHECK(counted >= bricked.Bricks->Bytes(), "the count covers what the field holds once made");
  DS_CHECK_LE(counted / bound, 0.5, "the count with the surface, against the box's bound (0.42)");
  FieldBricks starved;
  DS_CHECK(starved.Initialize(view.Box(box), p, reach, &error), error);
  starved.CheckMemoryAsAdded(1.0e6); // less than the bricks near the ball
  DS_CHECK(starved.Cover(surface) == 0 && starved.ComputedBricks() == 0 &&
      starved.Shortfall().find("GiB") != std::string::npos,
    "bricks the memory cannot hold are not made, and Shortfall says why: " + starved.Shortfall());
  FieldBricks budgeted; // a budget for the first bricks alone is used up by them
  DS_CHECK(budgeted.Initialize(view.Box(box), p, reach, &error), error);
  budgeted.CheckMemoryAsAdded(bricked.Bricks->ComputedBricks() * FieldBricks::BrickBytes + 1.0);
  DS_CHECK(budgeted.Cover(surface) == bricked.Bricks->ComputedBricks() &&
      budgeted.Shortfall().empty() &&
      budgeted.Cover(dstest::MakeIcosphere(3, 31.5, c + Vec3{ 6, 0, 0 })) == 0 &&
      !budgeted.Shortfall().empty(),
    "a budget given for the first bricks: they are made, the next ones not");

  // The centre of the ball is far from the surface: its brick is not computed.
  double f[3] = { 1, 1, 1 };
  DS_CHECK(bricked.SampleForce(c.data(), f) && f[0] == 0 && f[1] == 0 && f[2] == 0 &&
      bricked.Bricks->Misses() == 1,
    "a point in a brick not computed: no force, a miss, not outside the image");
  TriangleMesh inner = dstest::MakeIcosphere(1, 2.0, c);
  DS_CHECK(bricked.Bricks->Cover(inner) > 0, "Cover computes the bricks a surface came near");
  DS_CHECK(LargestDifference(bricked, whole, { c }) == 0.0, "and then they equal the box's");
  DS_CHECK(bricked.Bricks->Cover(inner) == 0, "a brick is computed once");

  // A surface travelling across the box: the bricks held never pass the whole field's size (a
  // brick holds 9^3 values), the ones left behind dropped; back where it started, the bricks
  // computed again equal the whole box's field bit for bit.
  const double budget = box.NumberOfVoxels() / std::pow(FieldBricks::BrickSize + 1.0, 3);
  int mostHeld = 0;
  for (const Vec3& shift : { Vec3{ 9, 0, 0 }, Vec3{ 0, 9, 0 }, Vec3{ 0, 0, 9 }, Vec3{ -9, 0, 0 },
         Vec3{ 0, -9, 0 }, Vec3{ 0, 0, -9 }, Vec3{ 0, 0, 0 } })
  {
    bricked.Bricks->Cover(dstest::MakeIcosphere(3, 31.5, c + shift));
    mostHeld = std::max(mostHeld, bricked.Bricks->ComputedBricks());
  }
  std::cout << "a surface travelling across the box: at most " << mostHeld
            << " bricks held, the whole field's size " << budget << " bricks" << std::endl;
  DS_CHECK_LE(mostHeld, budget, "bricks held by a travelling surface, at most the whole field");
  DS_CHECK(LargestDifference(bricked, whole, PointsWithinReach(surface, c, reach)) == 0.0,
    "dropped bricks computed again = whole-box field bit for bit");

  // Outside the box (the surface's neighbourhood) but inside the image, and outside the image.
  const Vec3 corner{ g.Origin[0] + 2.0, 2.0, 2.0 }, away{ g.Origin[0] - 5.0, 2.0, 2.0 };
  DS_CHECK(box.Begin[0] > 3, "the box is a cut of the image");
  DS_CHECK(whole.SampleForce(corner.data(), f) && bricked.SampleForce(corner.data(), f),
    "beyond the level's box but inside the image: not outside the image");
  DS_CHECK(!whole.SampleForce(away.data(), f) && !bricked.SampleForce(away.data(), f),
    "beyond the image: outside");

  // A whole solve from the box around the volume: no vertex ever sampled a missing brick.
  MultilevelSolver solver;
  TriangleMesh mesh = dstest::MakeIcosphere(1, 60.0, c);
  DS_CHECK(solver.Run(view, mesh, &error), error);
  long long misses = 0;
  for (const LevelRecord& rec : solver.GetLevels())
  {
    misses += rec.FieldMisses;
  }
  DS_CHECK(misses == 0 && solver.GetMaxOutsideVertices() == 0 && solver.GetLevels().size() > 3,
    "a solve: no missed brick, no vertex outside the image");

  // The first level in bricks, its surface travelling far: a seed of radius 3 grown by the region
  // force to the ball (radius 30) at sigma 1 voxel (reach 1 voxel), in batches of up to 200
  // sweeps. A batch ends once its sweeps' largest corrections add up to half the reach, so Cover
  // follows the surface (batches of 200 sweeps left whole would sample bricks not computed).
  MultilevelParameters grow;
  grow.Sigma = 1.0;
  grow.MaxLevels = 0;
  grow.RegionWeight = 1.0;
  grow.IntensityRange[0] = 0.5;
  grow.IntensityRange[1] = 2.0;
  grow.SweepBatch = 200;
  grow.Solver.NumberOfThreads = 1;
  MultilevelSolver grower;
  grower.SetParameters(grow);
  TriangleMesh seed = dstest::MakeIcosphere(2, 3.0, c);
  DS_CHECK(grower.Run(view, seed, &error), error);
  double radius = 0;
  for (const Vec3& x : seed.Points)
  {
    radius += Norm(x - c) / seed.NumberOfPoints();
  }
  std::cout << "grown seed: mean radius " << radius << ", field misses "
            << grower.GetLevels()[0].FieldMisses << std::endl;
  DS_CHECK(grower.GetLevels().size() == 1 && grower.GetLevels()[0].FieldMisses == 0,
    "a seed grown far on a bricked first level: no missed brick");
  DS_CHECK(std::abs(radius - 30.0) < 1.0, "and it reaches the ball (mean radius within 1 voxel)");
  TurnedGrid();
  InSlabs();
  LocallyNormalisedTiles();
  return dstest::Result("TestFieldBricks");
}

int main(int argc, char* argv[])
{
  return TestFieldBricks(argc, argv);
}
