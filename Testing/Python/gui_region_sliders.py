# SPDX-License-Identifier: BSD-3-Clause
"""Intensity Range set with the sliders of the DeformableSurfaceGUI plugin in the real ParaView
client (ctest Python.gui_region_sliders; CMakeLists.txt gives the command, as for
gui_seed_points.py).

This script sets the scene: a phantom (DS_TEST_OUTPUT/region_sliders_phantom.vti: a ball of
value 100 inside a shell of 200, background 0, one isolated voxel of 250 in a corner, so the
image's values run from 0 to 250), one seed point at the centre, Delaunay Seed Surface (a seed
sphere) and Deformable Surface with Intensity Range 50 150 and Preview Region on,
shown and active, so its panel shows the two sliders. The preview then reaches the ball only; its
PreviewVoxels goes to DS_TEST_OUTPUT/gui_region_sliders.json with the slider positions the
events use. The client plays gui_region_sliders.xml: the low slider to its right end (the high
one must follow), Apply, Save State; the low slider to a fifth of its way, 300 typed into the
high one's text field, Apply, Save State.
region_sliders_gui_check.py checks the saved ranges and previews."""
import os
import sys

# The client runs the script without __file__: the helpers come from beside DS_BASELINE_DIR.
sys.path.insert(0, os.path.join(os.environ["DS_BASELINE_DIR"], "..", "Python"))
import ds_gui  # noqa: E402

BALL, SHELL = 8.0, 14.0  # radii, mm (1 mm voxels)
VALUES = {"ball": 100.0, "shell": 200.0, "corner": 250.0}
RESOLUTION = 1000  # the sliders' steps (pqDSRangeSlidersPropertyWidget)
LOW_POSITIONS = [1000, 200]  # the low slider's positions in gui_region_sliders.xml


def write_phantom(path):
    import numpy as np

    half = int(SHELL) + 4
    axis = np.arange(-half, half + 1, dtype=float)
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    r = np.sqrt(x * x + y * y + z * z)
    value = np.where(r < BALL, VALUES["ball"], np.where(r < SHELL, VALUES["shell"], 0.0))
    value[0, 0, 0] = VALUES["corner"]
    ds_gui.write_phantom(value, (-half, -half, -half), path)


def scene():
    from paraview import servermanager, simple
    path = os.path.join(ds_gui.OUT_DIR, "region_sliders_phantom.vti")
    write_phantom(path)
    view = simple.GetActiveViewOrCreate("RenderView")
    phantom = simple.XMLImageDataReader(registrationName="phantom", FileName=[path])
    seeds = simple.SeedPoints(registrationName="SeedPoints", Points=[0.0, 0.0, 0.0])
    seed = simple.DelaunaySeedSurface(registrationName="DelaunaySeedSurface", Input=seeds, SeedRadius=3.0)
    surface = simple.DeformableSurface(registrationName="DeformableSurface", Input=phantom, InitialSurface=seed)
    surface.Scalars = ["POINTS", "density"]
    surface.IntensityRange = [50.0, 150.0]
    surface.PreviewRegion = 1
    simple.Show(surface, view)
    simple.Render(view)
    preview = servermanager.Fetch(surface, arg1=0)
    voxels = preview.GetFieldData().GetArray("PreviewVoxels")
    simple.SetActiveSource(surface)
    return {"voxels_before": int(voxels.GetValue(0)) if voxels else -1, "values": VALUES,
            "data_range": [0.0, VALUES["corner"]], "resolution": RESOLUTION,
            "low_positions": LOW_POSITIONS, "radii": [BALL, SHELL]}


ds_gui.write_setup("gui_region_sliders", scene)
