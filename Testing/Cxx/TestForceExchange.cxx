// SPDX-License-Identifier: BSD-3-Clause
// The solver's force exchange (Solver::SetForceExchange): a colour's forces are sampled, handed
// to the hook, then applied.
// - A hook that changes nothing gives results bit-identical to no hook (points, per-vertex
//   outputs, statistics) on 1, 2 and 3 threads, with the edge and the region force; it is called
//   once per colour per sweep with that colour's vertices at their current positions.
// - Two "ranks" (two solvers on two threads, each holding the field and the image of one half
//   of the volume plus a voxel of ghosts) exchanging forces with OwnerForceExchange (the forces
//   of the vertices they do not own zeroed, then summed by an all-reduce emulated in memory)
//   give the serial result bit for bit, including the vertices outside the volume (no rank
//   sampled them).
#include "DSTestHelpers.h"
#include "EmulatedRanks.h"
#include "TestSolverMeshes.h"

#include "dsPieceField.h"
#include "dsScaleSpace.h"
#include "dsSolver.h"
#include "dsTriangleMesh.h"

#include <algorithm>
#include <cmath>
#include <vector>

using namespace dsurf;
using dstest::MakeIcosphere;

namespace
{
constexpr int N = 64;           ///< voxels along every axis, spacing 1, origin 0
constexpr double Radius = 20.0; ///< the field pulls onto this sphere around the centre
const Vec3 Centre{ 31.5, 31.5, 31.5 };

/// F = (Radius - r) rhat, and the image 1 inside r < 16, 0 outside (the region force pushes
/// out where the image is 1).
void MakeVolume(ForceField& field, std::vector<float>& image)
{
  field.Geometry.Dimensions[0] = field.Geometry.Dimensions[1] = field.Geometry.Dimensions[2] = N;
  field.Sigma = 1;
  const long long n = field.Geometry.NumberOfVoxels();
  field.Potential.assign(n, 0.0f);
  field.Force.assign(3 * n, 0.0f);
  image.assign(n, 0.0f);
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
      {
        const Vec3 d = Vec3{ double(i), double(j), double(k) } - Centre;
        const double r = Norm(d);
        const long long idx = i + N * (j + N * static_cast<long long>(k));
        for (int a = 0; a < 3; ++a)
        {
          field.Force[3 * idx + a] = static_cast<float>(0.05 * (Radius - r) * d[a] / r);
        }
        image[idx] = r < 16 ? 1.0f : 0.0f;
      }
}

/// The voxel columns [i0, i1) of the field and the image, as a piece with its own origin.
void Cut(const ForceField& whole, const std::vector<float>& image, int i0, int i1,
  ForceField& piece, std::vector<float>& pieceImage)
{
  piece.Geometry = whole.Geometry;
  piece.Geometry.Dimensions[0] = i1 - i0;
  piece.Geometry.Origin[0] = i0;
  piece.Sigma = whole.Sigma;
  piece.Potential.clear();
  piece.Force.clear();
  pieceImage.clear();
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = i0; i < i1; ++i)
      {
        const long long idx = i + N * (j + N * static_cast<long long>(k));
        piece.Potential.push_back(whole.Potential[idx]);
        pieceImage.push_back(image[idx]);
        for (int a = 0; a < 3; ++a)
        {
          piece.Force.push_back(whole.Force[3 * idx + a]);
        }
      }
}

/// Rank r's piece: rank 0 owns the voxels 0..32 along x (cells 0..31), rank 1 32..63.
ImagePiece PieceOf(int r, const ForceField& whole)
{
  ImagePiece piece;
  piece.Whole = whole.Geometry;
  piece.Owned = VoxelBox::Whole(whole.Geometry);
  piece.Owned.Begin[0] = r == 0 ? 0 : 32;
  piece.Owned.End[0] = r == 0 ? 33 : N;
  return piece;
}

/// A start sphere slightly off-centre (no symmetry) reaching past the volume at the poles.
TriangleMesh Start(double radius)
{
  TriangleMesh m = MakeIcosphere(4, radius, Centre);
  for (auto& x : m.Points)
  {
    x[0] += 0.3 * std::sin(0.2 * x[1]);
  }
  std::string err;
  DS_CHECK(m.BuildTopology(&err), err);
  return m;
}

struct Run
{
  TriangleMesh Mesh;
  std::vector<SweepStatistics> Stats;
  std::vector<double> Error, Displacement, Force;
};

void Sweep(Solver& s, Run& run, int sweeps)
{
  s.Sweeps(sweeps,
    [&run](const SweepStatistics& st)
    {
      run.Stats.push_back(st);
      return true;
    });
  run.Error = s.ErrorIndicator();
  run.Displacement = s.Displacement();
  run.Force = s.ExternalForceMagnitude();
}

/// Points, per-vertex outputs and statistics that differ between a and b (bit for bit).
int Differences(const Run& a, const Run& b)
{
  int n = a.Mesh.NumberOfPoints() != b.Mesh.NumberOfPoints() || a.Stats.size() != b.Stats.size();
  for (int v = 0; n == 0 && v < a.Mesh.NumberOfPoints(); ++v)
  {
    n += a.Mesh.Points[v] != b.Mesh.Points[v] || a.Error[v] != b.Error[v] ||
      a.Displacement[v] != b.Displacement[v] || a.Force[v] != b.Force[v];
  }
  for (std::size_t i = 0; n == 0 && i < a.Stats.size(); ++i)
  {
    n += a.Stats[i].MeanCorrection != b.Stats[i].MeanCorrection ||
      a.Stats[i].MaxCorrection != b.Stats[i].MaxCorrection ||
      a.Stats[i].OutsideVertices != b.Stats[i].OutsideVertices;
  }
  return n;
}

constexpr int Sweeps = 40;
constexpr double RegionScale = 0.2;

Run Serial(const ForceField& field, const std::vector<float>& image, int threads,
  const ForceExchange& exchange, std::vector<int>* counts)
{
  Run run;
  run.Mesh = Start(32.5);
  Solver s;
  SolverParameters p;
  p.NumberOfThreads = threads;
  s.SetParameters(p);
  s.SetMesh(&run.Mesh);
  s.SetForceField(&field, 1.0);
  s.SetRegionForce(ImageView::Of(image.data(), field.Geometry), 0.5, 1.5, RegionScale);
  s.SetForceExchange(exchange);
  Sweep(s, run, Sweeps);
  if (counts)
  {
    for (int c = 0; c < s.NumberOfColors(); ++c)
    {
      counts->push_back(s.ColorOffsets()[c + 1] - s.ColorOffsets()[c]);
    }
  }
  return run;
}

void IdentityHook(const ForceField& field, const std::vector<float>& image)
{
  const Run reference = Serial(field, image, 1, nullptr, nullptr);
  DS_CHECK_GE(reference.Stats.front().OutsideVertices, 1, "vertices outside the volume (sweep 1)");
  for (int threads : { 1, 2, 3 })
  {
    std::vector<int> calls, colors;
    int positionsSeen = 0, positionsMatching = 0;
    const TriangleMesh start = Start(32.5);
    const Run hooked = Serial(
      field, image, threads,
      [&](VertexForce* forces, int count)
      {
        calls.push_back(count);
        if (calls.size() == 1) // colour 0 of sweep 1: the start's points
        {
          for (int i = 0; i < count; ++i, ++positionsSeen)
          {
            positionsMatching += std::find(start.Points.begin(), start.Points.end(),
                                   forces[i].Position) != start.Points.end();
          }
        }
      },
      &colors);
    const std::string label = std::to_string(threads) + " thread(s)";
    std::vector<int> expected;
    for (int s = 0; s < Sweeps; ++s)
    {
      expected.insert(expected.end(), colors.begin(), colors.end());
    }
    DS_CHECK(calls == expected, label + ": the hook is called once per colour, in order");
    DS_CHECK(positionsSeen > 0 && positionsMatching == positionsSeen,
      label + ": the hook sees the vertices where they stand");
    DS_CHECK_LE(Differences(reference, hooked), 0,
      label + ": values differing between an identity hook and none");
  }
}

void TwoRanks(const ForceField& field, const std::vector<float>& image)
{
  const Run reference = Serial(field, image, 1, nullptr, nullptr);
  // Rank 0 owns the cells of x < 32 and needs voxels 0..32; rank 1 owns 32.. and needs 32..63.
  // One more voxel each side stands for the ghost layers.
  ForceField pieces[2];
  std::vector<float> images[2];
  Cut(field, image, 0, 34, pieces[0], images[0]);
  Cut(field, image, 31, N, pieces[1], images[1]);
  dstest::EmulatedRanks ranks(2);
  Run runs[2];
  ranks.Run(
    [&](int r)
    {
      runs[r].Mesh = Start(32.5);
      Solver s;
      SolverParameters p;
      p.NumberOfThreads = 1;
      s.SetParameters(p);
      s.SetMesh(&runs[r].Mesh);
      s.SetForceField(&pieces[r], 1.0);
      s.SetRegionForce(ImageView::Of(images[r].data(), pieces[r].Geometry), 0.5, 1.5, RegionScale);
      PieceReductions reduce;
      reduce.Sum = [&ranks, r](std::vector<double>& v) { ranks.Sum(r, v); };
      s.SetForceExchange(OwnerForceExchange(PieceOf(r, field), reduce));
      Sweep(s, runs[r], Sweeps);
    });
  for (int r = 0; r < 2; ++r)
  {
    DS_CHECK_LE(Differences(reference, runs[r]), 0,
      "rank " + std::to_string(r) + ": values differing from the serial solve");
  }
  std::cout << "two ranks: " << reference.Mesh.NumberOfPoints() << " vertices, "
            << reference.Stats.front().OutsideVertices << " outside at sweep 1, mean |c| "
            << reference.Stats.back().MeanCorrection << " at sweep " << Sweeps << std::endl;
}
} // namespace

int TestForceExchange(int, char*[])
{
  ForceField field;
  std::vector<float> image;
  MakeVolume(field, image);
  IdentityHook(field, image);
  TwoRanks(field, image);
  return dstest::Result("TestForceExchange");
}

int main(int argc, char* argv[])
{
  return TestForceExchange(argc, argv);
}
