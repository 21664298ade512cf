// SPDX-License-Identifier: BSD-3-Clause
// Several objects that meet in one run (docs/METHOD.md §9.9), every default apart from the seeds
// (the heavier cases of TestSeveralObjects, in an executable of their own):
// - Spine (ObjectPhantoms.h), a click in each of three adjacent vertebrae: each vertebra within
//   half a voxel (mean, both ways), no intersecting pair, no voxel inside two.
// - Engine (SeveralObjectPhantoms.h: a block with two bores, a piston in each with one voxel of
//   air around it): the block from 40 picks with the tetrahedra in the bores removed (genus 2),
//   a click in each piston: each within half a voxel (mean, both ways), none crossing another,
//   no voxel inside two.
#include "SeveralObjectsCheck.h"

#include "vtkExtractEdges.h"

using namespace dsobjects;

namespace
{
vtkIdType CountEdges(vtkPolyData* surface)
{
  vtkNew<vtkExtractEdges> edges;
  edges->SetInputData(surface);
  edges->Update();
  return edges->GetOutput()->GetNumberOfLines();
}

void Spine()
{
  const SeveralPhantom s = SpineThreeClicks();
  const std::vector<int> ids = { 2, 3, 4 };
  const SeveralResult r = RunSeveral(s.Phantom.Image, SeedObjects(LabelledPoints(s.Clicks, ids)));
  CheckObjects(s, r, ids, { 0.5, 0.5, 0.5 }, "spine, three clicks");
}

void Engine()
{
  // The block from picks, the tetrahedra a user sees inside the bores removed (their centroids
  // in the bores' dark air): a seed of genus 2; a click in each piston.
  const SeveralPhantom s = EnginePhantom();
  std::vector<Point3> points = EngineBlockPicks();
  std::vector<int> ids(points.size(), 1);
  points.push_back(s.Clicks[1]);
  points.push_back(s.Clicks[2]);
  ids.push_back(2);
  ids.push_back(3);
  vtkSmartPointer<vtkPolyData> labelled = LabelledPoints(points, ids);
  const std::vector<vtkIdType> inBores = TetrahedraInBores(labelled);
  vtkSmartPointer<vtkPolyData> seed = SeedObjects(labelled, inBores);
  const SeveralResult r = RunSeveral(s.Phantom.Image, seed);
  vtkSmartPointer<vtkPolyData> block = ObjectPart(r.Surface, 1);
  const long long euler =
    block->GetNumberOfPoints() - CountEdges(block) + block->GetNumberOfCells();
  std::cout << "engine: block seed from " << points.size() - 2 << " picks, " << inBores.size()
            << " tetrahedra removed in the bores; the block's Euler characteristic " << euler
            << std::endl;
  DS_CHECK(euler == -2, "engine: the block has genus 2");
  CheckObjects(s, r, { 1, 2, 3 }, { 0.5, 0.5, 0.5 }, "engine");
}

} // namespace

int TestSeveralObjectsMeet(int, char*[])
{
  Spine();
  Engine();
  return dstest::Result("TestSeveralObjectsMeet");
}

int main(int argc, char* argv[])
{
  return TestSeveralObjectsMeet(argc, argv);
}
