// SPDX-License-Identifier: BSD-3-Clause
// The field of a piece of a distributed image (dsPieceField.h), with the processes emulated by
// threads (EmulatedRanks.h): a 49 x 47 x 160 image of two blurred objects and noise, split into
// 2 and 3 slabs along z as VTK splits an image (neighbouring pieces share their border voxels),
// each rank holding its slab and the ghost layers PieceGhostVoxels() asks for.
// - The piece fields equal the whole image's field (ComputeForceAtScale) on the owned voxels to
//   1e-12 of the largest force: a fine sigma (sampled Gaussian: a few ghost layers), a middle
//   one (recursive Gaussian, its state passed from piece to piece), a coarse one (block means
//   summed over the ranks, twice the block size of ghosts), over the whole image and over a box
//   (a later level's neighbourhood); the same for a uint16 image, its pieces read in their own
//   type. No rank holds the whole image.
// - The recursive Gaussian (sigma 3.5 and 8 on this anisotropic grid: 3.2-8.9 voxels, and 5.5)
//   on 2 and 3 slabs and on 3 bricks (split along z then y, and along x then z, as VTK's block mode
//   cuts an image): P and -grad P equal the serial field bit for bit on every owned voxel, and
//   each rank holds exactly its piece and one ghost layer (the largest
//   piece 188 846 of 368 480 voxels on 2 slabs, 128 968 on 3, 132 300 on 3 bricks).
// - Kept in bricks around a sphere across the slabs' borders (sigma 1.5 and 3): every rank's
//   force equals the serial bricks' near the sphere to 1e-12 of the largest force.
// - A single-level solve on every rank with its piece field and OwnerForceExchange equals the
//   serial solve on the whole field (coordinates to 1e-12 relative).
// - Bad input: a rank holding too few ghost layers makes every rank fail with a message, none
//   waiting in a reduction (a hang would hit the ctest timeout); a non-default potential is
//   refused on every rank.
#include "DSTestHelpers.h"
#include "PieceSlabs.h"
#include "TestSolverMeshes.h"

#include "dsFieldGrid.h"
#include "dsPieceField.h"
#include "dsSolver.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

using namespace dsurf;

namespace
{
/// A soft ball and a dimmer soft cube, with deterministic noise.
std::vector<float> Image(const ImageGeometry& g)
{
  std::vector<float> v;
  unsigned state = 12345;
  for (int k = 0; k < g.Dimensions[2]; ++k)
    for (int j = 0; j < g.Dimensions[1]; ++j)
      for (int i = 0; i < g.Dimensions[0]; ++i)
      {
        const double x = i - 20.0, y = 1.1 * j - 26.0, z = 0.9 * k - 22.0;
        const double ball = 1.0 / (1.0 + std::exp(std::sqrt(x * x + y * y + z * z) - 12.0));
        const double cube = 0.5 /
          (1.0 +
            std::exp(
              std::max({ std::abs(i - 38.0), std::abs(1.1 * j - 14.0), std::abs(0.9 * k - 32.0) }) -
              5.0));
        state = state * 1664525u + 1013904223u;
        v.push_back(static_cast<float>(100.0 * (ball + cube) + 5.0 * (state >> 8) / 16777216.0));
      }
  return v;
}

/// Rank r's slab of `ranks` with the ghosts sigma needs: twice the block size on coarse grids,
/// PieceGhostVoxels on the image's own (or ghostOverride layers).
template <typename T>
ImagePiece Slab(const ImageGeometry& g, const std::vector<T>& image, int r, int ranks, double sigma,
  std::vector<T>& held, int ghostOverride = -1)
{
  const int f = DecimationFactor(sigma, g);
  return dstest::Slab<T>(
    g, image, r, ranks,
    [&](int a) {
      return ghostOverride >= 0 ? ghostOverride : f > 1 ? 2 * f : PieceGhostVoxels(sigma, g, a);
    },
    held);
}

using dstest::ReductionsOf;

/// Largest |F_piece - F_whole| over the world points of the piece's owned voxels in `box` (those
/// `keep` accepts, when given; `compared` counts them), sampled in both fields, and the largest
/// |F_whole| there.
void CompareOnOwned(const ForceField& whole, const ForceField& piece, const ImagePiece& p,
  const VoxelBox& box, double& maxDiff, double& maxForce, int& missing,
  const std::function<bool(const double*)>& keep = nullptr, int* compared = nullptr)
{
  for (int k = std::max(p.Owned.Begin[2], box.Begin[2]); k < std::min(p.Owned.End[2], box.End[2]);
       ++k)
    for (int j = box.Begin[1]; j < box.End[1]; ++j)
      for (int i = box.Begin[0]; i < box.End[0]; ++i)
      {
        const double ijk[3] = { double(i), double(j), double(k) };
        double x[3], a[3], b[3];
        p.Whole.IndexToWorld(ijk, x);
        if (keep && !keep(x))
        {
          continue;
        }
        compared && ++*compared;
        const bool inWhole = whole.SampleForce(x, a);
        const bool inPiece = piece.SampleForce(x, b);
        missing += inWhole != inPiece;
        for (int c = 0; c < 3; ++c)
        {
          maxDiff = std::max(maxDiff, std::abs(a[c] - b[c]));
          maxForce = std::max(maxForce, std::abs(a[c]));
        }
      }
}

ScaleSpaceParameters OneThread(double sigma)
{
  ScaleSpaceParameters parameters;
  parameters.Sigma = sigma;
  parameters.NumberOfThreads = 1;
  return parameters;
}

/// The serial field of the whole image on `box`.
template <typename T>
ForceField SerialField(const ImageGeometry& g, const std::vector<T>& image, const VoxelBox& box,
  const ScaleSpaceParameters& parameters)
{
  ForceField whole;
  std::string error;
  DS_CHECK(
    ComputeForceAtScale(ImageView::Of(image.data(), g), box, parameters, whole, &error), error);
  return whole;
}

/// Rank r's slab of `nRanks` (held: its values) and its field over `box` into `field` (ok: it
/// was made), with a `surface` kept in bricks around it.
template <typename T>
ImagePiece PieceField(const ImageGeometry& g, const std::vector<T>& image, int r, int nRanks,
  const VoxelBox& box, const ScaleSpaceParameters& parameters, dstest::EmulatedRanks& ranks,
  std::vector<T>& held, ForceField& field, int& ok, const TriangleMesh* surface = nullptr)
{
  const ImagePiece piece = Slab(g, image, r, nRanks, parameters.Sigma, held);
  std::string message;
  ok = ComputePieceForce(piece, box, parameters, ReductionsOf(ranks, r), field, &message, surface);
  return piece;
}

template <typename T>
void FieldsAgree(const ImageGeometry& g, const std::vector<T>& image, int nRanks, double sigma,
  const VoxelBox& box, bool pieceSmaller, const std::string& label)
{
  const ScaleSpaceParameters parameters = OneThread(sigma);
  const ForceField whole = SerialField(g, image, box, parameters);
  dstest::EmulatedRanks ranks(nRanks);
  std::vector<double> diff(nRanks, 0.0), force(nRanks, 0.0);
  std::vector<int> missing(nRanks, 0), ok(nRanks, 0);
  std::vector<long long> heldVoxels(nRanks, 0);
  std::vector<double> fieldBytes(nRanks, 0.0), boundBytes(nRanks, 0.0);
  ranks.Run(
    [&](int r)
    {
      std::vector<T> held;
      ForceField field;
      const ImagePiece piece =
        PieceField(g, image, r, nRanks, box, parameters, ranks, held, field, ok[r]);
      heldVoxels[r] = piece.Held.NumberOfVoxels();
      // What MultilevelSolver::MakeField checks before making it.
      fieldBytes[r] =
        sizeof(float) * static_cast<double>(field.Potential.size() + field.Force.size());
      boundBytes[r] = PieceFieldBytes(piece, box, parameters);
      CompareOnOwned(whole, field, piece, box, diff[r], force[r], missing[r]);
    });
  const double relative = *std::max_element(diff.begin(), diff.end()) /
    std::max(1e-300, *std::max_element(force.begin(), force.end()));
  std::cout << label << ": held voxels per rank";
  for (long long h : heldVoxels)
  {
    std::cout << " " << h;
  }
  std::cout << " of " << g.NumberOfVoxels() << std::endl;
  for (int r = 0; r < nRanks; ++r)
  {
    DS_CHECK_LE(fieldBytes[r], boundBytes[r], label + ": the piece's field within PieceFieldBytes");
  }
  DS_CHECK(
    std::count(ok.begin(), ok.end(), 1) == nRanks, label + ": every rank computed its field");
  DS_CHECK_LE(relative, 1e-12, label + ": max |F_piece - F_whole| / max |F| on the owned voxels");
  DS_CHECK_LE(*std::max_element(missing.begin(), missing.end()), 0,
    label + ": owned voxels inside one field and outside the other");
  if (pieceSmaller)
  {
    DS_CHECK_LE(*std::max_element(heldVoxels.begin(), heldVoxels.end()), g.NumberOfVoxels() - 1,
      label + ": voxels held by the largest piece");
  }
  DS_CHECK(ranks.Mismatches() == 0, label + ": the ranks reduced vectors of one size");
}

/// A field kept in bricks around a surface (ComputeForceAtScale and ComputePieceForce with a
/// surface, a sphere across the slabs' borders): every rank's force equals the serial bricks'
/// at every owned voxel within half a sigma of the sphere (where both have computed their
/// bricks), to 1e-12 of the largest force as FieldsAgree's whole fields.
void BrickedFieldsAgree(const ImageGeometry& g, const std::vector<float>& image, int nRanks,
  double sigma, const std::string& label)
{
  const ScaleSpaceParameters parameters = OneThread(sigma);
  const Vec3 c = { 17.0, 28.0, 65.0 }; // across z = 52.7 and 77, the borders of 3 and 2 slabs
  const double radius = 14.0;
  const TriangleMesh surface = dstest::MakeIcosphere(3, radius, c);
  const VoxelBox box =
    SurfaceNeighbourhood(surface, g, FieldReach(parameters.EdgeNormalization, sigma));
  ForceField whole;
  std::string error;
  DS_CHECK(
    ComputeForceAtScale(ImageView::Of(image.data(), g), box, parameters, whole, &error, &surface) &&
      whole.Bricks,
    label + ": the serial field in bricks: " + error);
  DS_CHECK(FieldInBricks(box, g, parameters), label + ": FieldInBricks tells bricks");
  dstest::EmulatedRanks ranks(nRanks);
  std::vector<double> diff(nRanks, 0.0), force(nRanks, 0.0);
  std::vector<int> ok(nRanks, 0), compared(nRanks, 0), bricked(nRanks, 0);
  std::vector<int> missing(nRanks, 0);
  const auto near = [&](const double* x) {
    return std::abs(Norm(Vec3{ x[0], x[1], x[2] } - c) - radius) <= 0.5 * sigma;
  };
  ranks.Run(
    [&](int r)
    {
      std::vector<float> held;
      ForceField field;
      const ImagePiece piece =
        PieceField(g, image, r, nRanks, box, parameters, ranks, held, field, ok[r], &surface);
      bricked[r] = field.Bricks != nullptr;
      CompareOnOwned(whole, field, piece, box, diff[r], force[r], missing[r], near, &compared[r]);
    });
  std::cout << label << ": voxels compared per rank";
  for (int r = 0; r < nRanks; ++r)
  {
    std::cout << " " << compared[r];
  }
  std::cout << std::endl;
  DS_CHECK(std::count(ok.begin(), ok.end(), 1) == nRanks, label + ": every rank made its field");
  DS_CHECK(std::count_if(compared.begin(), compared.end(), [](int c) { return c > 0; }) >= 2,
    label + ": the sphere lies across a border of the pieces");
  for (int r = 0; r < nRanks; ++r)
  {
    DS_CHECK(bricked[r] || compared[r] == 0,
      label + ": rank " + std::to_string(r) + " keeps its part in bricks");
  }
  const double largest = *std::max_element(force.begin(), force.end());
  DS_CHECK(largest > 0.0, label + ": a force near the sphere");
  DS_CHECK_LE(*std::max_element(diff.begin(), diff.end()) / std::max(1e-300, largest), 1e-12,
    label + ": max |F_piece - F_serial| / max |F| near the sphere");
}

/// The values of `piece` (a field on a box of the image) that differ from `whole`'s bit for
/// bit on the voxels of `voxels` (whole-image indices), P and the three components of -grad P.
long long DifferingValues(const ForceField& whole, const ForceField& piece, const VoxelBox& voxels)
{
  const auto firstVoxel = [](const ForceField& f, int a)
  {
    return static_cast<int>(
      std::lround((f.Geometry.Origin[a] - f.Image.Origin[a]) / f.Image.Spacing[a]));
  };
  const auto index = [&](const ForceField& f, int i, int j, int k)
  {
    const int* n = f.Geometry.Dimensions;
    return (i - firstVoxel(f, 0)) +
      static_cast<long long>(n[0]) *
      ((j - firstVoxel(f, 1)) + static_cast<long long>(n[1]) * (k - firstVoxel(f, 2)));
  };
  long long differing = 0;
  for (int k = voxels.Begin[2]; k < voxels.End[2]; ++k)
    for (int j = voxels.Begin[1]; j < voxels.End[1]; ++j)
      for (int i = voxels.Begin[0]; i < voxels.End[0]; ++i)
      {
        const long long w = index(whole, i, j, k), q = index(piece, i, j, k);
        differing += std::memcmp(&whole.Potential[w], &piece.Potential[q], sizeof(float)) != 0;
        differing += std::memcmp(&whole.Force[3 * w], &piece.Force[3 * q], 3 * sizeof(float)) != 0;
      }
  return differing;
}

/// The owned voxels of rank r of 3 as VTK's block mode splits an image whose longest axis is
/// `first`: rank 0 a third of it, ranks 1 and 2 the rest split along `second`.
VoxelBox Brick(const ImageGeometry& g, int r, int first, int second)
{
  VoxelBox owned = VoxelBox::Whole(g);
  dstest::SplitAxis(owned, first, r == 0 ? 0 : 1, 3);
  if (r > 0)
  {
    owned.End[first] = VoxelBox::Whole(g).End[first];
    dstest::SplitAxis(owned, second, r - 1, 2);
  }
  return owned;
}

/// The recursive Gaussian (sigma between 3 and 9 voxels, fine grids) on pieces holding one ghost
/// layer: the field on every owned voxel equals the serial one bit for bit, and each rank holds
/// exactly its owned voxels and one layer around them (clipped to the image).
template <typename T>
void RecursiveFieldsExact(const ImageGeometry& g, const std::vector<T>& image, double sigma,
  const VoxelBox& box, const std::function<VoxelBox(int)>& ownedOf, int nRanks,
  const std::string& label)
{
  const ScaleSpaceParameters parameters = OneThread(sigma);
  const ForceField whole = SerialField(g, image, box, parameters);
  DS_CHECK(DecimationFactor(sigma, g) == 1 && PieceGhostVoxels(sigma, g, 0) == 1 &&
      PieceGhostVoxels(sigma, g, 1) == 1 && PieceGhostVoxels(sigma, g, 2) == 1,
    label + ": a fine grid, one ghost layer per axis");
  dstest::EmulatedRanks ranks(nRanks);
  std::vector<long long> differing(nRanks, -1), held(nRanks, 0), expected(nRanks, 0);
  ranks.Run(
    [&](int r)
    {
      std::vector<T> values;
      const ImagePiece piece = dstest::PieceOf<T>(
        g, image, ownedOf(r), [](int) { return 1; }, values);
      held[r] = piece.Held.NumberOfVoxels();
      expected[r] = 1;
      for (int a = 0; a < 3; ++a)
      {
        expected[r] *=
          std::min(g.Dimensions[a], piece.Owned.End[a] + 1) - std::max(0, piece.Owned.Begin[a] - 1);
      }
      ForceField field;
      std::string message;
      if (ComputePieceForce(piece, box, parameters, ReductionsOf(ranks, r), field, &message))
      {
        VoxelBox owned = piece.Owned;
        for (int a = 0; a < 3; ++a)
        {
          owned.Begin[a] = std::max(owned.Begin[a], box.Begin[a]);
          owned.End[a] = std::max(owned.Begin[a], std::min(owned.End[a], box.End[a]));
        }
        differing[r] = DifferingValues(whole, field, owned);
      }
    });
  std::cout << label << ": held voxels per rank";
  for (long long h : held)
  {
    std::cout << " " << h;
  }
  std::cout << " of " << g.NumberOfVoxels() << std::endl;
  for (int r = 0; r < nRanks; ++r)
  {
    const std::string rank = label + ", rank " + std::to_string(r);
    DS_CHECK(differing[r] == 0,
      rank + ": values differing from the serial field on the owned voxels: " +
        std::to_string(differing[r]));
    DS_CHECK(held[r] == expected[r], rank + ": holds its piece and one ghost layer");
    DS_CHECK_LE(held[r], g.NumberOfVoxels() * 2 / 3, rank + ": voxels held");
  }
  DS_CHECK(ranks.Mismatches() == 0, label + ": the ranks reduced vectors of one size");
}

/// One level's sweeps from a sphere around the ball: serial on the whole field, and on every
/// rank with its piece field and the owner exchange.
void SolvesAgree(const ImageGeometry& g, const std::vector<float>& image, int nRanks, double sigma)
{
  ScaleSpaceParameters parameters;
  parameters.Sigma = sigma;
  parameters.NumberOfThreads = 1;
  const VoxelBox box = VoxelBox::Whole(g);
  const Vec3 centre{ 17.0, 28.0, 27.0 }; // the ball's centre in world coordinates
  const auto sweep = [&](const ForceField& field, const ForceExchange& exchange)
  {
    TriangleMesh mesh = dstest::MakeIcosphere(3, 16.0, centre);
    std::string err;
    mesh.BuildTopology(&err);
    Solver s;
    SolverParameters p;
    p.NumberOfThreads = 2;
    s.SetParameters(p);
    s.SetMesh(&mesh);
    s.SetForceField(&field, mesh.MeanEdgeLength() * sigma);
    s.SetForceExchange(exchange);
    s.Sweeps(150, [](const SweepStatistics&) { return true; });
    return mesh;
  };
  ForceField whole;
  std::string error;
  ComputeForceAtScale(ImageView::Of(image.data(), g), box, parameters, whole, &error);
  const TriangleMesh serial = sweep(whole, nullptr);
  dstest::EmulatedRanks ranks(nRanks);
  std::vector<TriangleMesh> results(nRanks);
  ranks.Run(
    [&](int r)
    {
      std::vector<float> held;
      ForceField field;
      int ok = 0;
      const ImagePiece piece =
        PieceField(g, image, r, nRanks, box, parameters, ranks, held, field, ok);
      results[r] = sweep(field, OwnerForceExchange(piece, ReductionsOf(ranks, r)));
    });
  double worst = 0.0, moved = 0.0;
  for (const TriangleMesh& m : results)
  {
    DS_CHECK(m.NumberOfPoints() == serial.NumberOfPoints(), "same vertices");
    for (int v = 0; v < m.NumberOfPoints() && m.NumberOfPoints() == serial.NumberOfPoints(); ++v)
    {
      worst = std::max(worst, Norm(m.Points[v] - serial.Points[v]) / Norm(serial.Points[v]));
      moved = std::max(moved, std::abs(Norm(serial.Points[v] - centre) - 16.0));
    }
  }
  const std::string label = std::to_string(nRanks) + " ranks, sigma " + std::to_string(sigma);
  DS_CHECK_GE(moved, 1.0, label + ": the serial solve moved the sphere (largest |r - 16|)");
  DS_CHECK_LE(worst, 1e-12, label + ": max |x_rank - x_serial| / |x_serial| after 150 sweeps");
}

void BadPieces(const ImageGeometry& g, const std::vector<float>& image)
{
  const double sigma = 4.0;
  dstest::EmulatedRanks ranks(3);
  std::vector<int> ok(3, 1), named(3, 0);
  ranks.Run(
    [&](int r)
    {
      std::vector<float> held;
      // Rank 1 holds its slab without ghosts.
      const ImagePiece piece = Slab(g, image, r, 3, sigma, held, r == 1 ? 0 : -1);
      ScaleSpaceParameters parameters;
      parameters.Sigma = sigma;
      parameters.NumberOfThreads = 1;
      ForceField field;
      std::string message;
      ok[r] = ComputePieceForce(
        piece, VoxelBox::Whole(g), parameters, ReductionsOf(ranks, r), field, &message);
      named[r] =
        message.find(r == 1 ? "too few ghost layers" : "another process") != std::string::npos;
      if (r == 1)
      {
        std::cout << "rank 1 without ghosts: " << message << std::endl;
      }
    });
  DS_CHECK(std::count(ok.begin(), ok.end(), 0) == 3, "a piece without ghosts fails on every rank");
  DS_CHECK(std::count(named.begin(), named.end(), 1) == 3, "each rank says why");

  std::vector<int> refused(3, 0);
  ranks.Run(
    [&](int r)
    {
      std::vector<float> held;
      const ImagePiece piece = Slab(g, image, r, 3, sigma, held);
      ScaleSpaceParameters parameters;
      parameters.Sigma = sigma;
      parameters.ImageWeight = 0.5;
      ForceField field;
      std::string message;
      refused[r] = !ComputePieceForce(piece, VoxelBox::Whole(g), parameters, ReductionsOf(ranks, r),
                     field, &message) &&
        message.find("default potential") != std::string::npos;
    });
  DS_CHECK(std::count(refused.begin(), refused.end(), 1) == 3,
    "ImageWeight > 0 is refused on every rank, saying why");
}
} // namespace

int TestPieceField(int, char*[])
{
  const ImageGeometry g = dstest::AnisotropicGeometry(49, 47, 160);
  const std::vector<float> image = Image(g);
  VoxelBox box; // a later level's neighbourhood: less than half the image
  box.Begin[0] = 4;
  box.End[0] = 40;
  box.Begin[1] = 6;
  box.End[1] = 44;
  box.Begin[2] = 3;
  box.End[2] = 35;
  for (int nRanks : { 2, 3 })
  {
    const std::string n = std::to_string(nRanks) + " ranks";
    FieldsAgree(
      g, image, nRanks, 1.5, VoxelBox::Whole(g), true, n + ", sigma 1.5 (sampled Gaussian)");
    FieldsAgree(
      g, image, nRanks, 3.0, VoxelBox::Whole(g), true, n + ", sigma 3 (recursive Gaussian)");
    FieldsAgree(g, image, nRanks, 3.0, box, true, n + ", sigma 3 on a box");
    FieldsAgree(g, image, nRanks, 14.0, VoxelBox::Whole(g), true, n + ", sigma 14 (blocks of 3)");
    FieldsAgree(g, image, nRanks, 14.0, box, true, n + ", sigma 14 on a box");
    BrickedFieldsAgree(g, image, nRanks, 1.5, n + ", sigma 1.5 in bricks");
    BrickedFieldsAgree(g, image, nRanks, 3.0, n + ", sigma 3 in bricks");
    SolvesAgree(g, image, nRanks, 2.0);
    SolvesAgree(g, image, nRanks, 3.0);
  }
  // The recursive Gaussian passed from piece to piece: 2 and 3 slabs along z, and 3 bricks
  // as VTK's block mode cuts an image longest along z (then y) or along x (then z).
  const auto slabs = [&](int n)
  {
    return [&g, n](int r)
    {
      VoxelBox owned = VoxelBox::Whole(g);
      dstest::SplitAxis(owned, 2, r, n);
      return owned;
    };
  };
  for (double sigma : { 3.5, 8.0 })
  {
    const std::string s = ", sigma " + std::to_string(sigma).substr(0, 3);
    RecursiveFieldsExact(g, image, sigma, VoxelBox::Whole(g), slabs(2), 2, "2 slabs" + s);
    RecursiveFieldsExact(g, image, sigma, VoxelBox::Whole(g), slabs(3), 3, "3 slabs" + s);
  }
  RecursiveFieldsExact(
    g, image, 5.5, VoxelBox::Whole(g), [&g](int r) { return Brick(g, r, 2, 1); }, 3,
    "3 bricks z then y, sigma 5.5");
  RecursiveFieldsExact(
    g, image, 5.5, box, [&g](int r) { return Brick(g, r, 2, 1); }, 3,
    "3 bricks z then y, sigma 5.5 on a box");
  const ImageGeometry wide = dstest::AnisotropicGeometry(160, 47, 49);
  const std::vector<float> wideImage = Image(wide);
  RecursiveFieldsExact(
    wide, wideImage, 5.5, VoxelBox::Whole(wide), [&wide](int r) { return Brick(wide, r, 0, 2); }, 3,
    "3 bricks x then z, sigma 5.5");

  // The pieces read in the input's own type (no float copy): a uint16 image's piece fields
  // equal its whole field as the float image's do.
  std::vector<std::uint16_t> image16;
  for (float v : image)
  {
    image16.push_back(static_cast<std::uint16_t>(std::lround(100.0 * v)));
  }
  FieldsAgree(g, image16, 3, 1.5, VoxelBox::Whole(g), true, "uint16, 3 ranks, sigma 1.5");
  FieldsAgree(g, image16, 3, 5.5, VoxelBox::Whole(g), true, "uint16, 3 ranks, sigma 5.5");
  FieldsAgree(g, image16, 3, 14.0, box, true, "uint16, 3 ranks, sigma 14 on a box");
  BadPieces(g, image);
  return dstest::Result("TestPieceField");
}

int main(int argc, char* argv[])
{
  return TestPieceField(argc, argv);
}
