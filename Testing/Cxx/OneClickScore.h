// SPDX-License-Identifier: BSD-3-Clause
// One click with every default on a phantom of ObjectPhantoms.h (OneClick.h's workflow at the
// phantom's click), scored by ObjectScore.h against the clicked object's label, and its numbers
// printed on one line. Shared by TestOneClickObjects and TestFrontLevels.
#ifndef OneClickScore_h
#define OneClickScore_h

#include "ObjectPhantoms.h"
#include "ObjectScore.h"
#include "OneClick.h"

#include <iostream>
#include <vector>

namespace dsobjects
{
/// The click's output and its score.
struct ScoredClick
{
  ClickResult Click;
  ObjectScore Score;
};

inline ScoredClick ScoreOneClick(const ObjectPhantom& phantom)
{
  ScoredClick r;
  r.Click = RunOneClick(phantom.Image, phantom.Click, ClickSettings());
  const int object = phantom.ObjectLabel;
  const std::vector<unsigned char> reference =
    MaskOf(phantom.Label, [object](double l, vtkIdType) { return l == object; });
  vtkPolyData* surface = r.Click.Surface;
  r.Score = Score(surface, SurfaceInterior(surface, phantom.Image), reference,
    MaskBoundary(reference, phantom.Image), phantom.Image);
  const ObjectScore& s = r.Score;
  std::cout << phantom.Name << ": " << s.Vertices << " vertices, " << r.Click.Seconds
            << " s; surface -> reference mean " << s.SurfaceMean << " (95 % " << s.SurfaceP95
            << "), reference -> surface mean " << s.ReferenceMean << " (95 % " << s.ReferenceP95
            << ") mm; Dice " << s.Dice << ", volume ratio " << s.VolumeRatio << ", "
            << 100 * s.OutsideShare << " % outside, " << s.SelfIntersections
            << " intersecting pairs" << std::endl;
  return r;
}
} // namespace dsobjects

#endif
