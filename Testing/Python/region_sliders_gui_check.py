# SPDX-License-Identifier: BSD-3-Clause
"""The check of ctest Python.gui_region_sliders (gui_region_sliders.py explains the GUI part): run
with pvpython after the client saved DS_TEST_OUTPUT/gui_region_sliders_clamped.pvsm and
gui_region_sliders.pvsm.

- the low slider at its right end gave Intensity Range [250, 250]: the sliders are bounded by the
  image's values (0 to 250, read from the input), and the high slider followed the low one;
- the low slider at a fifth of its way and 300 typed into the high one's text field gave
  [50, 300] (a fifth of 0..250; a typed value may lie beyond the sliders);
- Preview Region with it reaches the ball and its shell: PreviewVoxels is the number of voxels of
  value 100 or 200 (all connected to the seed; the isolated voxel of 250 is not), where the
  scene's range 50 150 reached the ball's voxels only."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader  # noqa: E402

import ds_gui  # noqa: E402


def preview_voxels(surface):
    voxels = servermanager.Fetch(surface, arg1=0).GetFieldData().GetArray("PreviewVoxels")
    return int(voxels.GetValue(0)) if voxels else -1


def phantom_values():
    reader = vtkXMLImageDataReader()
    reader.SetFileName(os.path.join(ds_gui.OUT_DIR, "region_sliders_phantom.vti"))
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("density"))


check = ds_gui.Check()
setup = ds_gui.load_state("gui_region_sliders", check)
low_end, high_end = setup["data_range"]
surface = simple.FindSource("DeformableSurface")
got = list(surface.IntensityRange)
low = low_end + setup["low_positions"][1] / setup["resolution"] * (high_end - low_end)
check(len(got) == 2 and abs(got[0] - low) < 1e-9 and got[1] == 300.0,
      "low slider at %d of %d, 300 typed as high: Intensity Range %s (expected [%g, 300])"
      % (setup["low_positions"][1], setup["resolution"], got, low))
check(surface.PreviewRegion == 1, "the state still previews")

values = phantom_values()
ball = int((values == setup["values"]["ball"]).sum())
ball_and_shell = ball + int((values == setup["values"]["shell"]).sum())
check(setup["voxels_before"] == ball,
      "range 50 150: the preview reached the ball, %d voxels (expected %d)" % (setup["voxels_before"], ball))
after = preview_voxels(surface)
check(after == ball_and_shell, "range %s: the preview reaches the ball and its shell, %d voxels (expected %d)"
      % (got, after, ball_and_shell))

simple.ResetSession()
simple.LoadState(os.path.join(ds_gui.OUT_DIR, "gui_region_sliders_clamped.pvsm"))
clamped = list(simple.FindSource("DeformableSurface").IntensityRange)
check(clamped == [high_end, high_end],
      "low slider at its right end: Intensity Range %s (expected [%g, %g]: the image's largest value, "
      "the high slider moved along)" % (clamped, high_end, high_end))
check.exit()
