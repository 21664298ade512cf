// SPDX-License-Identifier: BSD-3-Clause
// Whole multilevel solves on a distributed image against the serial solve, the processes
// emulated by threads (EmulatedRanks.h), each rank holding a slab along z and the ghost layers
// MultilevelSolver::DistributedGhostVoxels asks for: shared by TestDistributedSolve and
// TestFollowingField.
#ifndef DistributedSolveCheck_h
#define DistributedSolveCheck_h

#include "CapsulePhantom.h"
#include "DSTestHelpers.h"
#include "EmulatedRanks.h"
#include "PieceSlabs.h"

#include "dsMultilevel.h"
#include "dsPieceField.h"

#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

namespace dsdistributed
{
using namespace dsurf;

inline ImagePiece Slab(const ImageGeometry& g, const std::vector<float>& image, int r, int ranks,
  const MultilevelParameters& p, std::vector<float>& held, bool empty = false)
{
  return dstest::Slab<float>(
    g, image, r, ranks, [&](int a) { return MultilevelSolver::DistributedGhostVoxels(p, g, a); },
    held, empty);
}

struct Outcome
{
  bool Ok = false;
  std::string Error;
  TriangleMesh Mesh;
  long long Held = 0;
  int FrontLevels = 0; ///< levels past sigma's floor that followed a thin part
  LevelRecord First;   ///< the first level's record
};

inline int FrontLevelsOf(const MultilevelSolver& solver)
{
  const std::vector<LevelRecord>& levels = solver.GetLevels();
  return static_cast<int>(
    std::count_if(levels.begin(), levels.end(), [](const LevelRecord& l) { return l.Front; }));
}

/// The serial run from `start`.
inline Outcome SerialRun(const ImageGeometry& g, const std::vector<float>& image,
  const MultilevelParameters& p, const TriangleMesh& start)
{
  Outcome serial;
  serial.Mesh = start;
  MultilevelSolver solver;
  solver.SetParameters(p);
  serial.Ok = solver.Run(image.data(), g, serial.Mesh, &serial.Error);
  serial.FrontLevels = FrontLevelsOf(solver);
  serial.First = solver.GetLevels().empty() ? LevelRecord() : solver.GetLevels().front();
  return serial;
}

/// One run per rank from `start` (rank `emptyRank`'s piece empty; -1: none).
inline void RankRuns(const ImageGeometry& g, const std::vector<float>& image,
  const MultilevelParameters& p, const TriangleMesh& start, int nRanks, int emptyRank,
  std::vector<Outcome>& ranks)
{
  dstest::EmulatedRanks emulated(nRanks);
  ranks.assign(nRanks, Outcome());
  emulated.Run(
    [&](int r)
    {
      std::vector<float> held;
      const ImagePiece piece = Slab(g, image, r, nRanks, p, held, r == emptyRank);
      const PieceReductions reduce = dstest::ReductionsOf(emulated, r);
      MultilevelSolver s;
      s.SetParameters(p);
      s.SetDistribution(piece, reduce);
      ranks[r].Mesh = start;
      ranks[r].Held = piece.Held.NumberOfVoxels();
      ImageView whole = piece.Image; // the whole image's geometry, the piece's values
      whole.Geometry = g;
      ranks[r].Ok = s.Run(whole, ranks[r].Mesh, &ranks[r].Error);
      ranks[r].FrontLevels = FrontLevelsOf(s);
    });
  DS_CHECK(emulated.Mismatches() == 0, "the ranks reduced vectors of one size");
}

/// The serial run and one run per rank, each from `start`.
inline void Solve(const ImageGeometry& g, const std::vector<float>& image,
  const MultilevelParameters& p, const TriangleMesh& start, int nRanks, int emptyRank,
  Outcome& serial, std::vector<Outcome>& ranks)
{
  serial = SerialRun(g, image, p, start);
  RankRuns(g, image, p, start, nRanks, emptyRank, ranks);
}

/// The image a case solves on: the capsule unless given.
struct Phantom
{
  ImageGeometry Geometry = dstest::CapsuleGeometry();
  std::vector<float> Image = dstest::CapsuleImage();
};

/// The serial run, then the runs on each count of ranks, compared with it; returns the serial
/// run's front levels; `serialOut`, when given, gets the serial run.
inline int SameAsSerial(const std::string& label, const MultilevelParameters& p,
  const TriangleMesh& start, bool pieceSmaller, const std::vector<int>& rankCounts = { 2, 3 },
  const Phantom& phantom = Phantom(), Outcome* serialOut = nullptr)
{
  const ImageGeometry& g = phantom.Geometry;
  const std::vector<float>& image = phantom.Image;
  const Outcome serial = SerialRun(g, image, p, start);
  if (serialOut)
  {
    *serialOut = serial;
  }
  for (int nRanks : rankCounts)
  {
    std::vector<Outcome> ranks;
    RankRuns(g, image, p, start, nRanks, -1, ranks);
    const std::string l = label + ", " + std::to_string(nRanks) + " ranks";
    DS_CHECK(serial.Ok, l + ": the serial run: " + serial.Error);
    double worst = 0.0;
    long long held = 0;
    for (const Outcome& o : ranks)
    {
      DS_CHECK(o.Ok, l + ": " + o.Error);
      DS_CHECK(o.FrontLevels == serial.FrontLevels,
        l + ": " + std::to_string(o.FrontLevels) + " front levels, serial " +
          std::to_string(serial.FrontLevels));
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
    std::cout << l << ": " << serial.Mesh.NumberOfPoints() << " vertices, " << serial.FrontLevels
              << " front levels; the largest piece held " << held << " of " << g.NumberOfVoxels()
              << " voxels" << std::endl;
    DS_CHECK_LE(worst, 1e-12, l + ": max |x_rank - x_serial| / |x_serial|");
    if (pieceSmaller)
    {
      DS_CHECK_LE(held, g.NumberOfVoxels() - 1, l + ": voxels held by the largest piece");
    }
  }
  return serial.FrontLevels;
}

} // namespace dsdistributed

#endif
