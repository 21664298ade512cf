# SPDX-License-Identifier: BSD-3-Clause
"""Seed points placed with the P key in the real ParaView client (ctest Python.gui_seed_points):

    PV_PLUGIN_PATH=<both plugin dirs> paraview --dr --script=gui_seed_points.py \\
        --test-directory=<out> --test-script=gui_seed_points.xml --exit          (under Xvfb)
    pvpython seed_points_gui_check.py

This script sets the scene as a user would: a phantom of three balls (written to
DS_TEST_OUTPUT/seed_points_phantom.vti, opened with the XML image reader), a Slice through their
centres, the view looking down on it (parallel projection), and a Seed Points source, active, so
its panel (the DeformableSurfaceGUI plugin's table) is shown. The client then plays
gui_seed_points.xml: the mouse over the view at three fractions of its size, P at each (the third
with the panel's "object" spin box at 1), a fourth pick removed again with Delete in the table,
the first row selected and its point handle dragged to the right, Apply, File > Save State; then
a fifth pick, Apply, Edit > Undo, Save State, Edit > Redo, Save State.

The aim: each fraction of the view is turned into the world point the camera shows there, and a
ball is centred on it; the aims go to DS_TEST_OUTPUT/gui_seed_points.json for the check, which
reads the saved state (ds_gui.py). The GUI exits with 0 whatever happens, so the check is the
verdict."""
import os
import sys

# The client runs the script without __file__: the helpers come from beside DS_BASELINE_DIR.
sys.path.insert(0, os.path.join(os.environ["DS_BASELINE_DIR"], "..", "Python"))
import ds_gui  # noqa: E402

# The fractions gui_seed_points.xml moves the mouse to (x from the left, y from the top) and the
# object each pick seeds.
FRACTIONS = [(0.3, 0.4), (0.7, 0.4), (0.5, 0.7)]
OBJECTS = [0, 0, 1]
SCALE = 32.0  # the camera's parallel scale: half the view's height, mm
RADIUS = 8.0  # the balls' radius, mm
SLICE_Z = 12.0
DRAG = (0.3, 0.33)  # the handle of the first point, dragged from x = 0.3 to 0.33 of the view
UNDO_FRACTION = (0.5, 0.2)  # the pick that is applied, undone and redone


def write_phantom(centres, path):
    """Balls of RADIUS around `centres` (value 100 inside, 0 outside, a one-voxel linear ramp
    so the 50 level lies at RADIUS), 1 mm voxels."""
    import numpy as np

    c = np.array(centres)
    lo = np.floor(c.min(axis=0) - RADIUS - 6.0)
    hi = np.ceil(c.max(axis=0) + RADIUS + 6.0)
    lo[2], hi[2] = 0.0, 2 * SLICE_Z
    dims = (hi - lo + 1).astype(int)
    z, y, x = np.meshgrid(*[lo[a] + np.arange(dims[a]) for a in (2, 1, 0)], indexing="ij")
    value = np.zeros(x.shape)
    for centre in c:
        d = np.sqrt((x - centre[0]) ** 2 + (y - centre[1]) ** 2 + (z - centre[2]) ** 2)
        value = np.maximum(value, 100.0 * np.clip(RADIUS + 0.5 - d, 0.0, 1.0))
    ds_gui.write_phantom(value, lo, path)


def scene():
    from paraview import simple
    view = simple.GetActiveViewOrCreate("RenderView")
    focal = [0.0, 0.0, SLICE_Z]
    *aims, undo_aim = ds_gui.top_view(view, focal, SCALE, FRACTIONS + [UNDO_FRACTION])
    phantom_path = os.path.join(ds_gui.OUT_DIR, "seed_points_phantom.vti")
    write_phantom(aims, phantom_path)
    phantom = simple.XMLImageDataReader(registrationName="phantom", FileName=[phantom_path])
    cut = simple.Slice(registrationName="Slice", Input=phantom)
    cut.SliceType = "Plane"
    cut.SliceType.Origin, cut.SliceType.Normal = focal, [0.0, 0.0, 1.0]
    shown = simple.Show(cut, view)
    simple.ColorBy(shown, ("POINTS", "density"))
    simple.Render(view)
    seeds = simple.SeedPoints(registrationName="SeedPoints")
    simple.SetActiveSource(seeds)
    return {"aims": aims, "objects": OBJECTS, "radius": RADIUS, "view": list(view.ViewSize),
            "mm_per_pixel": 2.0 * SCALE / view.ViewSize[1], "drag": DRAG, "undo_aim": undo_aim}


ds_gui.write_setup("gui_seed_points", scene)
