// SPDX-License-Identifier: BSD-3-Clause
// The filter with its test-only switch: the docs/METHOD.md §5 self-intersection rule turned off,
// to show what it prevents. Users have no reason to turn it off, so the public
// vtkDeformableSurfaceFilter does not offer it; a test subclass reaches the core parameters the
// filter holds (SolverParameters::ProjectExternalForce, dsSolver.h).
#ifndef DSRuleSwitchFilter_h
#define DSRuleSwitchFilter_h

#include "vtkDeformableSurfaceFilter.h"

#include "dsMultilevel.h"

#include "vtkObjectFactory.h"

namespace dstest
{
class RuleSwitchFilter : public vtkDeformableSurfaceFilter
{
public:
  static RuleSwitchFilter* New();
  vtkTypeMacro(RuleSwitchFilter, vtkDeformableSurfaceFilter);

  /// On (the core's default): the paper's rule; off: the raw external force, which folds.
  void SetProjectExternalForce(bool on)
  {
    if (this->Parameters->Solver.ProjectExternalForce != on)
    {
      this->Parameters->Solver.ProjectExternalForce = on;
      this->Modified();
    }
  }
  bool GetProjectExternalForce() const { return this->Parameters->Solver.ProjectExternalForce; }
};
inline RuleSwitchFilter* RuleSwitchFilter::New()
{
  VTK_STANDARD_NEW_BODY(RuleSwitchFilter);
}
} // namespace dstest

#endif
