// SPDX-License-Identifier: BSD-3-Clause
// Front levels (docs/METHOD.md §9.3, MultilevelSolver::FrontTriangles): one click with every
// default at the centre of the horned phantom's body (ObjectPhantoms.h: a dark body with four
// horns 4, 3, 2 and 3 voxels wide reaching 30, 25, 40 and 35 voxels beyond it) follows its horns
// and nothing else:
// - the horns three and four voxels wide to within a voxel of their ends, and no horn beyond
//   its end by more than a voxel (the surface's farthest vertex near each horn's axis, measured
//   from the body's surface along it);
// - the horn two voxels wide to within two voxels of its end (its voxels, partly surround, lie
//   near the range's end, which the click's mixture places only when the dark body lies within
//   the histogram's span: dsClickCompetition.cxx MixtureTailShare);
// - reference boundary -> surface mean at most 0.5 voxel and 95 % at most 1.5 voxel (the
//   one-click goals); surface -> reference 95 % at most 0.6 voxel and at most 1 % of
//   the enclosed volume outside the object (no leak); at most 6 000 vertices (only the front is
//   refined past sigma's floor); no self-intersections;
// - the output counts its front levels (FrontLevels, 1 to MaxFrontLevels) and keeps no level
//   apart (KeptApartLevels 0: the surface never crosses itself).
#include "DSTestHelpers.h"
#include "OneClickScore.h"
#include "SeveralObjects.h"
#include "dsMultilevel.h"

#include "vtkPoints.h"

#include <algorithm>
#include <iostream>
#include <string>

using namespace dsobjects;

int TestFrontLevels(int, char*[])
{
  const ScoredClick scored = ScoreOneClick(HornedPhantom());
  const ClickResult& click = scored.Click;
  const ObjectScore& s = scored.Score;
  DS_CHECK_LE(s.ReferenceP95, 1.5, "horned: reference -> surface 95 % (voxels)");
  DS_CHECK_LE(s.ReferenceMean, 0.5, "horned: reference -> surface mean (voxels)");
  DS_CHECK_LE(s.SurfaceP95, 0.6, "horned: surface -> reference 95 % (voxels)");
  DS_CHECK_LE(s.OutsideShare, 0.01, "horned: share of the enclosed volume outside the object");
  DS_CHECK_LE(s.Vertices, 6000, "horned: vertices");
  DS_CHECK(s.SelfIntersections == 0, "horned: no self-intersections");
  const double front = FieldValue(click.Surface, "FrontLevels");
  std::cout << "front levels " << front << ", levels kept apart "
            << FieldValue(click.Surface, "KeptApartLevels") << std::endl;
  DS_CHECK(front >= 1 && front <= dsurf::MaxFrontLevels, "horned: FrontLevels counts them");
  DS_CHECK(FieldValue(click.Surface, "KeptApartLevels") == 0, "horned: no level kept apart");

  vtkPoints* points = click.Surface->GetPoints();
  for (int h = 0; h < horned::Horns; ++h)
  {
    const horned::Horn& horn = horned::HornList[h];
    double reach = -1e300; // the farthest vertex near the horn's axis, beyond the body's surface
    for (vtkIdType v = 0; v < points->GetNumberOfPoints(); ++v)
    {
      double x[3];
      points->GetPoint(v, x);
      double along = 0;
      if (horned::AxisDistance(h, { x[0], x[1], x[2] }, &along) < horn.Width + 1.0)
      {
        reach = std::max(reach, along - horned::SurfaceDistance(h));
      }
    }
    std::cout << "horn " << h << " (" << horn.Width << " voxels wide, " << horn.Length
              << " long): reached " << reach << std::endl;
    const double wanted = horn.Length - (horn.Width >= 3 ? 1.0 : 2.0);
    DS_CHECK_GE(reach, wanted, "horn " + std::to_string(h) + ": reach beyond the body (voxels)");
    DS_CHECK_LE(reach, horn.Length + 1.0, "horn " + std::to_string(h) + ": not beyond its end");
  }
  return dstest::Result("TestFrontLevels");
}

int main(int argc, char* argv[])
{
  return TestFrontLevels(argc, argv);
}
