// The whole multilevel solve on a distributed image (MultilevelSolver::SetDistribution), the
// processes emulated by threads (EmulatedRanks.h): a soft capsule along z in a 32 x 32 x 240
// image with noise, split into 2 and 3 slabs along z (neighbouring pieces share their border
// voxels, as VTK's), each rank holding its slab and DistributedGhostVoxels() around it.
// - Every default, from the box around the volume: every rank ends with the serial surface, bit
//   for bit (the levels on the image's own grid use the recursive Gaussian: each rank holds the
//   whole image).
// - A start near the object with Sigma 2.5 voxels and the edge force alone (RegionWeight 0; the
//   region force's exchange is TestForceExchange's): the serial surface bit for bit, and no rank
//   holds the whole image.
// - Bad input: an empty piece on one rank fails every rank with a message (no rank waits in a
//   reduction: a hang would hit the ctest timeout); a start that would need sigma_0 from the
//   image is refused on every rank.
#include "CapsulePhantom.h"
#include "DSTestHelpers.h"
#include "EmulatedRanks.h"

#include "dsMultilevel.h"
#include "dsPieceField.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace dsurf;

namespace
{
constexpr int NX = dstest::CapsuleNX, NY = dstest::CapsuleNY, NZ = dstest::CapsuleNZ;

ImagePiece Slab(const ImageGeometry& g, const std::vector<float>& image, int r, int ranks,
  const MultilevelParameters& p, std::vector<float>& held, bool empty = false)
{
  ImagePiece piece;
  piece.Whole = g;
  piece.Owned = VoxelBox::Whole(g);
  const int cells = g.Dimensions[2] - 1;
  piece.Owned.Begin[2] = cells * r / ranks;
  piece.Owned.End[2] = empty ? piece.Owned.Begin[2] : cells * (r + 1) / ranks + 1;
  piece.Held = piece.Owned;
  for (int a = 0; a < 3 && !empty; ++a)
  {
    const int ghost = MultilevelSolver::DistributedGhostVoxels(p, g, a);
    piece.Held.Begin[a] = std::max(0, piece.Held.Begin[a] - ghost);
    piece.Held.End[a] = std::min(g.Dimensions[a], piece.Held.End[a] + ghost);
  }
  held.clear();
  for (int k = piece.Held.Begin[2]; k < piece.Held.End[2]; ++k)
    for (int j = piece.Held.Begin[1]; j < piece.Held.End[1]; ++j)
      for (int i = piece.Held.Begin[0]; i < piece.Held.End[0]; ++i)
      {
        held.push_back(image[i + NX * (j + static_cast<std::size_t>(NY) * k)]);
      }
  piece.Image = ImageView::Of(held.empty() ? nullptr : held.data(), piece.HeldGeometry());
  return piece;
}

struct Outcome
{
  bool Ok = false;
  std::string Error;
  TriangleMesh Mesh;
  long long Held = 0;
};

/// The serial run and one run per rank, each from `start`.
void Solve(const ImageGeometry& g, const std::vector<float>& image, const MultilevelParameters& p,
  const TriangleMesh& start, int nRanks, int emptyRank, Outcome& serial,
  std::vector<Outcome>& ranks)
{
  serial.Mesh = start;
  MultilevelSolver solver;
  solver.SetParameters(p);
  serial.Ok = solver.Run(image.data(), g, serial.Mesh, &serial.Error);

  dstest::EmulatedRanks emulated(nRanks);
  ranks.assign(nRanks, Outcome());
  emulated.Run(
    [&](int r)
    {
      std::vector<float> held;
      const ImagePiece piece = Slab(g, image, r, nRanks, p, held, r == emptyRank);
      PieceReductions reduce;
      reduce.Sum = [&emulated, r](std::vector<double>& v) { emulated.Sum(r, v); };
      reduce.Max = [&emulated, r](double v) { return emulated.Max(r, v); };
      MultilevelSolver s;
      s.SetParameters(p);
      s.SetDistribution(piece, reduce);
      ranks[r].Mesh = start;
      ranks[r].Held = piece.Held.NumberOfVoxels();
      ImageView whole = piece.Image; // the whole image's geometry, the piece's values
      whole.Geometry = g;
      ranks[r].Ok = s.Run(whole, ranks[r].Mesh, &ranks[r].Error);
    });
  DS_CHECK(emulated.Mismatches() == 0, "the ranks reduced vectors of one size");
}

void SameAsSerial(const std::string& label, const MultilevelParameters& p,
  const TriangleMesh& start, bool pieceSmaller)
{
  const ImageGeometry g = dstest::CapsuleGeometry();
  const std::vector<float> image = dstest::CapsuleImage();
  for (int nRanks : { 2, 3 })
  {
    Outcome serial;
    std::vector<Outcome> ranks;
    Solve(g, image, p, start, nRanks, -1, serial, ranks);
    const std::string l = label + ", " + std::to_string(nRanks) + " ranks";
    DS_CHECK(serial.Ok, l + ": the serial run: " + serial.Error);
    double worst = 0.0;
    long long held = 0;
    for (const Outcome& o : ranks)
    {
      DS_CHECK(o.Ok, l + ": " + o.Error);
      DS_CHECK(o.Mesh.NumberOfPoints() == serial.Mesh.NumberOfPoints(),
        l + ": " + std::to_string(o.Mesh.NumberOfPoints()) + " vertices, serial " +
          std::to_string(serial.Mesh.NumberOfPoints()));
      for (int v = 0;
           v < o.Mesh.NumberOfPoints() && o.Mesh.NumberOfPoints() == serial.Mesh.NumberOfPoints();
           ++v)
      {
        worst = std::max(
          worst, Norm(o.Mesh.Points[v] - serial.Mesh.Points[v]) / Norm(serial.Mesh.Points[v]));
      }
      held = std::max(held, o.Held);
    }
    std::cout << l << ": " << serial.Mesh.NumberOfPoints() << " vertices; the largest piece held "
              << held << " of " << g.NumberOfVoxels() << " voxels" << std::endl;
    DS_CHECK_LE(worst, 1e-12, l + ": max |x_rank - x_serial| / |x_serial|");
    if (pieceSmaller)
    {
      DS_CHECK_LE(held, g.NumberOfVoxels() - 1, l + ": voxels held by the largest piece");
    }
  }
}

void BadInput(const TriangleMesh& box, const TriangleMesh& near)
{
  const ImageGeometry g = dstest::CapsuleGeometry();
  const std::vector<float> image = dstest::CapsuleImage();
  const MultilevelParameters defaults;
  Outcome serial;
  std::vector<Outcome> ranks;
  Solve(g, image, defaults, box, 3, 1, serial, ranks);
  int failed = 0, said = 0;
  for (const Outcome& o : ranks)
  {
    failed += !o.Ok;
    said += o.Error.find("empty") != std::string::npos;
  }
  std::cout << "an empty piece on rank 1: " << ranks[1].Error << " / rank 0: " << ranks[0].Error
            << std::endl;
  DS_CHECK(failed == 3 && said == 3, "an empty piece on one rank fails every rank, saying why");

  // A start near the object with every default needs sigma_0 from the image.
  Solve(g, image, defaults, near, 2, -1, serial, ranks);
  failed = said = 0;
  for (const Outcome& o : ranks)
  {
    failed += !o.Ok;
    said += o.Error.find("give Sigma or SigmaFraction") != std::string::npos;
  }
  DS_CHECK(failed == 2 && said == 2, "sigma_0 from the start is refused on every rank, saying why");
}
} // namespace

int TestDistributedSolve(int, char*[])
{
  const TriangleMesh around = dstest::CapsuleBox({ 15.5, 15.5, 119.5 }, { 15.0, 15.0, 119.0 });
  const TriangleMesh near = dstest::CapsuleBox({ 15.5, 15.5, 119.5 }, { 12.0, 12.0, 84.0 });
  MultilevelParameters defaults;
  defaults.Solver.NumberOfThreads = 1;
  // sigma_0 = extent / 6 = 16.9 voxels: two levels on block means, then 8.4 voxels on the
  // image's grid, with the recursive Gaussian: every rank holds the whole axis.
  SameAsSerial("every default from the box", defaults, around, false);
  // sigma_0 = 2.5 voxels: the sampled Gaussian only, a dozen ghost layers.
  MultilevelParameters small = defaults;
  small.Sigma = 2.5;
  small.RegionWeight = 0.0;
  SameAsSerial("a start near the capsule, Sigma 2.5, RegionWeight 0", small, near, true);
  BadInput(around, near);
  return dstest::Result("TestDistributedSolve");
}

int main(int argc, char* argv[])
{
  return TestDistributedSolve(argc, argv);
}
