# SPDX-License-Identifier: BSD-3-Clause
"""Tetrahedra removed with the P key in the real ParaView client (ctest
Python.gui_removed_tetrahedra; CMakeLists.txt gives the command, as for gui_seed_points.py):

This script sets the scene: twelve seed points (Seed Points, given as a property), Delaunay Seed
Surface on them, a Slice of its Tetrahedra output through z = 0 seen from above (parallel
projection), and the filter active, so its panel (the DeformableSurfaceGUI plugin's Removed
Tetrahedra widget) is shown. The client then plays gui_removed_tetrahedra.xml: P over tetrahedron
A, over B, over A again, Apply, File > Save State. The world points aimed at go to
DS_TEST_OUTPUT/gui_removed_tetrahedra.json for removed_tetrahedra_gui_check.py."""
import os
import sys

# The client runs the script without __file__: the helpers come from beside DS_BASELINE_DIR.
sys.path.insert(0, os.path.join(os.environ["DS_BASELINE_DIR"], "..", "Python"))
import ds_gui  # noqa: E402

# The fractions of the view the XML points at (x from the left, y from the top): A, B.
FRACTIONS = [(0.5, 0.45), (0.42, 0.6)]
SCALE = 32.0  # the camera's parallel scale, mm
# Irregular points (no four on a circle, no five on a sphere): a unique Delaunay complex.
POINTS = [(-20, -15, -12), (18, -17, -10), (16, 19, -14), (-19, 16, -11), (-17, -18, 13),
          (19, -16, 12), (17, 18, 15), (-18, 17, 11), (2, 1, 20), (-1, 3, -20), (0, -20, 1),
          (1, 20, -1)]


def scene():
    from paraview import simple
    view = simple.GetActiveViewOrCreate("RenderView")
    seeds = simple.SeedPoints(registrationName="SeedPoints", Points=[c for p in POINTS for c in p])
    seed = simple.DelaunaySeedSurface(registrationName="DelaunaySeedSurface", Input=seeds)
    cut = simple.Slice(registrationName="TetrahedraSlice", Input=simple.OutputPort(seed, 1))
    cut.SliceType = "Plane"
    cut.SliceType.Origin, cut.SliceType.Normal = [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]
    shown = simple.Show(cut, view)
    simple.ColorBy(shown, ("CELLS", "TetraId"))
    shown.SetRepresentationType("Surface With Edges")
    aims = ds_gui.top_view(view, [0.0, 0.0, 0.0], SCALE, FRACTIONS)
    simple.Render(view)
    simple.SetActiveSource(seed)
    return {"aims": aims, "points": POINTS}


ds_gui.write_setup("gui_removed_tetrahedra", scene)
