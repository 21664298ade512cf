// SPDX-License-Identifier: BSD-3-Clause
// A surface that would cross itself is solved again kept off itself (docs/METHOD.md §9.3, "Why
// one click can fold"; MultilevelSolver::SolveLevelKeptApart), through the public filters as a
// user runs them: the assembly phantom's two clicks (SeveralObjectPhantoms.h: two blocks of the
// same material joined by a glue line) seeded without an ObjectId are one object whose two
// spheres grow into each other through the glue (solved freely, they cross: docs/RESULTS.md).
// - The output has no intersecting pair of triangles (SelfIntersections 0) and says that levels
//   were kept apart (KeptApartLevels >= 1);
// - both blocks are found: at least 90 % of each block's voxels lie inside the surface, and at
//   most 5 % of the enclosed voxels lie outside the two blocks and their glue line.
// TestFrontLevels checks that a surface that never crosses itself keeps no level apart.
#include "DSTestHelpers.h"
#include "ObjectScore.h"
#include "SeveralObjects.h"

#include "vtkCellData.h"
#include "vtkPointData.h"

#include <algorithm>
#include <iostream>
#include <string>

using namespace dsobjects;

int TestKeptApart(int, char*[])
{
  const SeveralPhantom s = AssemblyPhantom();
  vtkSmartPointer<vtkPolyData> seed = SeedObjects(LabelledPoints(s.Clicks, s.Labels));
  seed->GetCellData()->RemoveArray("ObjectId");
  const SeveralResult one = RunSeveral(s.Phantom.Image, seed);
  const double pairs = FieldValue(one.Surface, "SelfIntersections");
  const double kept = FieldValue(one.Surface, "KeptApartLevels");
  std::cout << "assembly, two clicks as one object: " << one.Surface->GetNumberOfPoints()
            << " vertices, " << pairs << " intersecting pairs, " << kept << " levels kept apart"
            << std::endl;
  DS_CHECK(pairs == 0, "assembly as one object: no intersecting pair");
  DS_CHECK(kept >= 1, "assembly as one object: levels kept apart, and the output says so");
  const std::vector<unsigned char> inside = SurfaceInterior(one.Surface, s.Phantom.Image);
  // The glue line: the voxels whose x extent is its [31.5, 32.5) (i = 32), between the blocks.
  const auto inGlue = [](int i, int j, int k)
  {
    return i == 32 && j > assembly::Side[0] && j < assembly::Side[1] && k > assembly::Side[0] &&
      k < assembly::Side[1];
  };
  const int* dims = s.Phantom.Image->GetDimensions();
  vtkDataArray* labels = s.Phantom.Label->GetPointData()->GetScalars();
  long long enclosed = 0, outside = 0;
  long long blockVoxels[3] = { 0, 0, 0 }, blockInside[3] = { 0, 0, 0 };
  for (vtkIdType v = 0; v < static_cast<vtkIdType>(inside.size()); ++v)
  {
    const int label = static_cast<int>(labels->GetTuple1(v));
    const int i = static_cast<int>(v % dims[0]), j = static_cast<int>(v / dims[0] % dims[1]),
              k = static_cast<int>(v / (static_cast<vtkIdType>(dims[0]) * dims[1]));
    blockVoxels[label] += 1;
    if (inside[v])
    {
      ++enclosed;
      blockInside[label] += 1;
      outside += label == 0 && !inGlue(i, j, k) ? 1 : 0;
    }
  }
  for (int b : { 1, 2 })
  {
    DS_CHECK_GE(double(blockInside[b]) / blockVoxels[b], 0.9,
      "assembly as one object: share of block " + std::to_string(b) + "'s voxels inside");
  }
  DS_CHECK_LE(double(outside) / std::max(1LL, enclosed), 0.05,
    "assembly as one object: share of the enclosed voxels outside the blocks and the glue");

  return dstest::Result("TestKeptApart");
}

int main(int argc, char* argv[])
{
  return TestKeptApart(argc, argv);
}
