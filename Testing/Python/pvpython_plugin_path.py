# SPDX-License-Identifier: BSD-3-Clause
"""The plugin loads through PV_PLUGIN_PATH alone (no LoadPlugin call), the way a user
installs it for the GUI, and every filter appears in paraview.simple."""
import os
import sys

assert os.environ.get("PV_PLUGIN_PATH"), "ctest must set PV_PLUGIN_PATH"
import paraview.simple as simple  # noqa: E402

wanted = ["ScaleSpaceGradient", "DeformableSurface", "DelaunaySeedSurface"]
missing = [name for name in wanted if not hasattr(simple, name)]
print("found:", [name for name in wanted if name not in missing])
if missing:
    sys.exit("not loaded through PV_PLUGIN_PATH: %s" % missing)

# The VTK-level package imports in pvpython too (PYTHONPATH set by ctest), and its
# classes are the ones the plugin's proxies wrap.
from deformablesurface import (vtkDeformableSurfaceFilter, vtkDelaunaySeedSurface,  # noqa: E402
                               vtkImageScaleSpaceGradient)

for cls in (vtkImageScaleSpaceGradient, vtkDeformableSurfaceFilter, vtkDelaunaySeedSurface):
    assert cls().GetClassName() == cls.__name__, cls
print("deformablesurface imports in pvpython")

# The GUI's defaults are the C++ defaults (SigmaFraction 0: sigma chosen from the start; the
# region force's weight and range), so a ParaView run and a VTK run with defaults give the same
# surface.
from deformablesurface import vtkDeformableSurfaceFilter as _F  # noqa: E402
_proxy, _cpp = simple.DeformableSurface(), _F()
assert _proxy.SigmaFraction == _cpp.GetSigmaFraction() == 0.0
assert _proxy.RegionWeight == _cpp.GetRegionWeight()
assert list(_proxy.IntensityRange) == list(_cpp.GetIntensityRange())
assert _proxy.EdgeNormalization == "Global maximum" and _cpp.GetEdgeNormalization() == _F.GLOBAL_MAXIMUM
assert simple.DelaunaySeedSurface().SeedRadius == vtkDelaunaySeedSurface().GetSeedRadius()
assert simple.ScaleSpaceGradient().SigmaFraction == vtkImageScaleSpaceGradient().GetSigmaFraction()
print("ParaView defaults equal the C++ defaults")
