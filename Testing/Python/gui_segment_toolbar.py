# SPDX-License-Identifier: BSD-3-Clause
"""One click with the Deformable Surface toolbar in the real ParaView client (ctest
Python.gui_segment_toolbar; CMakeLists.txt gives the command, as for gui_seed_points.py).

The scene a user has after opening a volume and Apply: a noisy ball (120 in 70, noise s.d. 4,
radius RADIUS mm; written to DS_TEST_OUTPUT/segment_toolbar_phantom.vti and opened with the XML
image reader), shown as ParaView shows a volume (an outline), the reader active, the view looking
down on the image's middle slice. The client then plays gui_segment_toolbar.xml, the rest of the
one-click workflow: the toolbar's "Segment from points" (Seed Points on the reader, the image now
shown as a Slice), the mouse over the ball's centre and P, Apply (Delaunay Seed Surface and
Deformable Surface follow the point), File > Save State: three actions after open and Apply, none
typing a number; then Edit > Undo, Seed Points hidden, a second P and Apply, saved again; then
Undo back to before the button, two Redo, P and the panel's Reset, P and Apply, saved at each
step.
segment_toolbar_gui_check.py checks the saved state."""
import os
import sys

# The client runs the script without __file__: the helpers come from beside DS_BASELINE_DIR.
sys.path.insert(0, os.path.join(os.environ["DS_BASELINE_DIR"], "..", "Python"))
import ds_gui  # noqa: E402

AIM = (0.45, 0.55)  # where gui_segment_toolbar.xml presses P (x from the left, y from the top)
SCALE = 40.0  # the camera's parallel scale: half the view's height, mm
RADIUS = 12.0
HALF = 24  # the image spans the ball's centre +- HALF voxels (1 mm)


def write_phantom(centre, path):
    """The ball of RADIUS around `centre` (120, a one-voxel linear ramp so 95 lies at RADIUS) in
    70, Gaussian noise of s.d. 4 (seed 7), 1 mm voxels, `centre` the image's middle voxel."""
    import numpy as np

    lo = [centre[a] - HALF for a in range(3)]
    n = 2 * HALF + 1
    z, y, x = np.meshgrid(*[lo[a] + np.arange(n) for a in (2, 1, 0)], indexing="ij")
    d = np.sqrt((x - centre[0]) ** 2 + (y - centre[1]) ** 2 + (z - centre[2]) ** 2)
    value = 70.0 + 50.0 * np.clip(RADIUS + 0.5 - d, 0.0, 1.0)
    value += np.random.default_rng(7).normal(0.0, 4.0, value.shape)
    ds_gui.write_phantom(value, lo, path)


def scene():
    from paraview import simple
    view = simple.GetActiveViewOrCreate("RenderView")
    focal = [0.0, 0.0, 0.0]
    # The ball centred where P will be pressed, on the middle slice the Slice representation shows.
    centre, = ds_gui.top_view(view, focal, SCALE, [AIM])
    path = os.path.join(ds_gui.OUT_DIR, "segment_toolbar_phantom.vti")
    write_phantom(centre, path)
    reader = simple.XMLImageDataReader(registrationName="ball", FileName=[path])
    shown = simple.Show(reader, view)
    shown.SetRepresentationType("Outline")
    simple.Render(view)
    simple.SetActiveSource(reader)
    return {"centre": centre, "radius": RADIUS}


ds_gui.write_setup("gui_segment_toolbar", scene)
