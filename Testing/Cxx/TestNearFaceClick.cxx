// SPDX-License-Identifier: BSD-3-Clause
// A click whose seed touches its object's face (docs/METHOD.md §9.3, "A click's competitors"):
// the tube and slab phantom (SeveralObjectPhantoms.h), the slab clicked five voxels beyond its
// face, where the default 5 mm seed sphere just touches it; RegionWeight 1, every other default
// (the README's one click, OneClick.h). Around this click the histogram fit splits the slab's
// one class (120, noise s.d. 4) into two halves; the click's median fell to the lower one, the
// upper was taken for a competitor and the range ended at the slab's own level (95.0-120.6):
// half the slab pulled the surface in, which kept the seed (0.1 % of the slab's volume).
// - The range holds the slab's intensities: its upper end lies above its level + 2 s.d.
// - The surface encloses the slab: within 10 % of its voxels (the label's count).
// - It lies on the slab's face: its vertices near the face (away from the image's sides) lie
//   at most a voxel from it on average.
// And with every default (RegionWeight 0.3) the bright ball of ObjectPhantoms.h (radius 16)
// clicked 7 and 4 voxels inside its face, where the click's sigma_0 is its own face and that
// edge pulls the seed's far side toward it (a cap on the face, volume ratio 0.01, unless a
// click's first levels drop the inward edge pull where the image says object,
// WithoutInwardEdgePull): the surface encloses the ball (within 5 % of its voxels) and lies on
// it (mean distance both ways at most 0.3 voxel).
#include "DSTestHelpers.h"
#include "OneClickScore.h"
#include "SeveralObjects.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

using namespace dsobjects;

namespace
{
/// Mean |x - SlabX| of the vertices within `near` voxels of the slab's face and at least two
/// voxels from the image's sides (there the slab is cut by the image, not by its face).
double FaceDistance(vtkPolyData* surface, double near, long long& vertices)
{
  double sum = 0;
  vertices = 0;
  for (vtkIdType v = 0; v < surface->GetNumberOfPoints(); ++v)
  {
    double x[3];
    surface->GetPoint(v, x);
    const bool inside =
      x[1] > 2 && x[1] < tubeslab::Dims[1] - 3 && x[2] > 2 && x[2] < tubeslab::Dims[2] - 3;
    if (inside && std::abs(x[0] - tubeslab::SlabX) < near)
    {
      sum += std::abs(x[0] - tubeslab::SlabX);
      ++vertices;
    }
  }
  return vertices > 0 ? sum / vertices : 1e300;
}
} // namespace

int TestNearFaceClick(int, char*[])
{
  const SeveralPhantom s = TubeSlabPhantom();
  const ObjectPhantom& p = s.Phantom;
  ClickSettings settings;
  settings.RegionWeight = 1.0;
  const Point3 click = { tubeslab::SlabX + settings.SeedRadius, 56.3, tubeslab::Centre[2] };
  const ClickResult r = RunOneClick(p.Image, click, settings);
  const std::vector<unsigned char> label =
    MaskOf(p.Label, [](double l, vtkIdType) { return l == 2; });
  const std::vector<unsigned char> inside = SurfaceInterior(r.Surface, p.Image);
  const double ratio = double(std::count(inside.begin(), inside.end(), 1)) /
    double(std::count(label.begin(), label.end(), 1));
  long long faceVertices = 0;
  const double face = FaceDistance(r.Surface, 10.0, faceVertices);
  std::cout << "slab clicked " << settings.SeedRadius << " voxels beyond its face: range "
            << r.UsedRange[0] << " - " << r.UsedRange[1] << ", InitialSigma "
            << FieldValue(r.Surface, "InitialSigma") << ", " << FieldValue(r.Surface, "Levels")
            << " levels, " << r.Surface->GetNumberOfPoints() << " vertices, " << r.Seconds
            << " s; volume ratio " << ratio << ", " << faceVertices
            << " vertices near the face, mean distance to it " << face << " voxels" << std::endl;
  DS_CHECK(r.HasRange, "slab: the output has its IntensityRange");
  DS_CHECK_GE(r.UsedRange[1], tubeslab::Bright + 2 * tubeslab::Noise, "slab: range's upper end");
  DS_CHECK_LE(r.UsedRange[0], tubeslab::Bright - 2 * tubeslab::Noise, "slab: range's lower end");
  DS_CHECK_GE(ratio, 0.9, "slab: enclosed voxels against the slab's");
  DS_CHECK_LE(ratio, 1.1, "slab: enclosed voxels against the slab's");
  DS_CHECK_GE(faceVertices, 100, "slab: vertices near its face");
  DS_CHECK_LE(face, 1.0, "slab: mean distance of the vertices near the face to it (voxels)");
  for (double d : { 7.0, 4.0 })
  {
    const ObjectPhantom ball = BrightBall(d);
    const ScoredClick scored = ScoreOneClick(ball);
    const std::string name = "ball clicked " + std::to_string(static_cast<int>(d)) + " inside: ";
    DS_CHECK_GE(scored.Score.VolumeRatio, 0.95, name + "enclosed voxels against the ball's");
    DS_CHECK_LE(scored.Score.VolumeRatio, 1.05, name + "enclosed voxels against the ball's");
    DS_CHECK_LE(scored.Score.SurfaceMean, 0.3, name + "surface -> ball mean (voxels)");
    DS_CHECK_LE(scored.Score.ReferenceMean, 0.3, name + "ball -> surface mean (voxels)");
  }
  return dstest::Result("TestNearFaceClick");
}

int main(int argc, char* argv[])
{
  return TestNearFaceClick(argc, argv);
}
