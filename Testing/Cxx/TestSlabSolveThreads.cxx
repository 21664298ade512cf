// SPDX-License-Identifier: BSD-3-Clause
// A whole solve whose fine levels smooth their box in slabs and keep G_sigma * f only in tiles
// near the surface (a box of more than half the image, SlabSmoothingShare; docs/METHOD.md §9.7)
// gives the same surface, bit for bit, on one thread and on two, with the global and with the
// local edge normalisation; no force sample misses a brick, and the surface lies on the ball.
// (TestFieldBricks compares such fields with the whole image's; this checks a solve through
// them, whose batches, refills and bricks follow the surface.)
#include "DSTestHelpers.h"
#include "ScaleSpaceTestUtils.h"
#include "TestSolverMeshes.h"

#include "dsFieldGrid.h"
#include "dsMultilevel.h"

#include <cmath>
#include <iostream>
#include <vector>

using namespace dsurf;

namespace
{
struct Solve
{
  TriangleMesh Mesh;
  std::vector<LevelRecord> Levels;
};

/// The multilevel solve of `image` from a sphere 3 voxels outside the ball (sigma_0 from the
/// start: a few voxels, so the first level is on the image's own grid), on `threads` threads.
Solve Run(const ImageView& image, const Vec3& centre, int threads, EdgeNormalization normalization)
{
  MultilevelParameters p;
  p.EdgeNormalization = normalization;
  p.Solver.NumberOfThreads = threads;
  MultilevelSolver solver;
  solver.SetParameters(p);
  Solve out;
  out.Mesh = dstest::MakeIcosphere(4, 43.0, centre);
  std::string error;
  DS_CHECK(solver.Run(image, out.Mesh, &error), error);
  out.Levels = solver.GetLevels();
  return out;
}

void Compare(const ImageView& image, const Vec3& centre, EdgeNormalization normalization,
  const std::string& what)
{
  const Solve one = Run(image, centre, 1, normalization);
  const Solve two = Run(image, centre, 2, normalization);
  const double voxels = static_cast<double>(image.Geometry.NumberOfVoxels());
  int inSlabs = 0;
  long long misses = 0;
  for (const LevelRecord& rec : two.Levels)
  {
    // A level on the image's own grid (sigma below 9 voxels, dsFieldGrid.h) whose box holds more
    // than SlabSmoothingShare of the image is smoothed in slabs and kept in tiles.
    inSlabs += rec.Sigma < 9.0 && rec.FieldVoxels > SlabSmoothingShare * voxels ? 1 : 0;
    misses += rec.FieldMisses;
  }
  std::cout << what << ": " << two.Levels.size() << " levels, " << inSlabs << " in slabs, "
            << two.Mesh.NumberOfPoints() << " vertices" << std::endl;
  DS_CHECK(inSlabs >= 2, what + ": at least two levels smooth their box in slabs");
  DS_CHECK(misses == 0, what + ": no force sample missed a brick");
  bool same = one.Mesh.Points.size() == two.Mesh.Points.size() &&
    one.Mesh.Triangles == two.Mesh.Triangles && one.Levels.size() == two.Levels.size();
  for (std::size_t i = 0; same && i < one.Mesh.Points.size(); ++i)
  {
    same = one.Mesh.Points[i] == two.Mesh.Points[i];
  }
  DS_CHECK(same, what + ": one and two threads give the same surface bit for bit");
  double worst = 0;
  for (const Vec3& x : two.Mesh.Points)
  {
    worst = std::max(worst, std::abs(Norm(x - centre) - 40.0));
  }
  DS_CHECK_LE(worst, 0.5, what + ": largest distance of a vertex from the ball (voxels)");
}
} // namespace

int TestSlabSolveThreads(int, char*[])
{
  // A ball of radius 40 in 96^3 voxels: every fine level's box (the surface's and 6 sigma around
  // it) holds most of the image.
  ImageGeometry g;
  g.Dimensions[0] = g.Dimensions[1] = g.Dimensions[2] = 96;
  const Vec3 c{ 47.5, 47.5, 47.5 };
  const std::vector<float> image = sstest::SoftBall(g, c.data(), 40.0);
  const ImageView view = ImageView::Of(image.data(), g);
  Compare(view, c, EdgeNormalization::GlobalMaximum, "global edge normalisation");
  Compare(view, c, EdgeNormalization::Local, "local edge normalisation");
  return dstest::Result("TestSlabSolveThreads");
}

int main(int argc, char* argv[])
{
  return TestSlabSolveThreads(argc, argv);
}
