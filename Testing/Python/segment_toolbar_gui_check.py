# SPDX-License-Identifier: BSD-3-Clause
"""The check of ctest Python.gui_segment_toolbar (gui_segment_toolbar.py explains the GUI part):
run with pvpython after the client saved DS_TEST_OUTPUT/gui_segment_toolbar.pvsm.

- the toolbar's button added Seed Points on the active image and showed the image as a Slice (it
  was an outline); the one Apply with a point added Delaunay Seed Surface and Deformable Surface
  (the image its Input) and showed the grown surface;
- the one P over the ball's centre placed one point there, within half a voxel (0.5 mm);
- Deformable Surface, every default as the button left it, grows it into one closed surface on
  the ball: the centre of its bounding box within 0.5 mm of the ball's centre, the radius of a
  ball of its volume within 0.5 mm of the ball's radius, no self-intersecting pair;
- Undo takes the two filters back (an undo step of their own); with Seed Points hidden, a second
  P, on the image's slice, and Apply bring them again, on the two points;
- five Undo go back to before the button (an Undo of an Apply of the points brings no filter
  back); Redo of the button brings Seed Points back, empty; Redo of the first Apply its point,
  with no filter (a Redo makes none); a P and the panel's Reset make none either (Reset applies
  nothing); a P and Apply bring the two filters once more, on the two points."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkMassProperties  # noqa: E402

import ds_gui  # noqa: E402

check = ds_gui.Check()
setup = ds_gui.load_state("gui_segment_toolbar", check)
centre, radius = setup["centre"], setup["radius"]
image = simple.FindSource("ball")
points = simple.FindSource("SeedPoints1")
seed = simple.FindSource("DelaunaySeedSurface1")
surface = simple.FindSource("DeformableSurface1")
if not check(None not in (image, points, seed, surface),
             "the state holds the ball, SeedPoints1, DelaunaySeedSurface1 and DeformableSurface1"):
    check.exit()
check(seed.Input.GetXMLName() == "SeedPoints" and surface.Input.GetXMLName() == "XMLImageDataReader"
      and surface.InitialSurface.GetXMLName() == "DelaunaySeedSurface",
      "the chain: Seed Points -> Delaunay Seed Surface -> Deformable Surface, the image its Input")
shown = simple.GetDisplayProperties(image, simple.GetActiveView())
check(shown.Representation == "Slice", "the image is shown as a Slice (%s)" % shown.Representation)
view = simple.GetActiveView()
representation = servermanager.GetRepresentation(surface, view)
check(representation is not None and representation.Visibility == 1,
      "the client shows the grown surface after the one Apply")
placed = list(points.Points)
check(len(placed) == 3 and math.dist(placed, [centre[0], centre[1], centre[2]]) <= 0.5,
      "one point placed, within 0.5 mm of the ball's centre (%s)" % placed)
grown = servermanager.Fetch(surface, idx=0)
mass = vtkMassProperties()
mass.SetInputData(grown)
mass.Update()
bounds = grown.GetBounds()
middle = [0.5 * (bounds[2 * a] + bounds[2 * a + 1]) for a in range(3)]
equivalent = (3.0 * mass.GetVolume() / (4.0 * math.pi)) ** (1.0 / 3.0)
intersecting = grown.GetFieldData().GetArray("SelfIntersections")
check(grown.GetNumberOfPoints() > 100 and math.dist(middle, centre) <= 0.5
      and abs(equivalent - radius) <= 0.5,
      "the surface on the ball: bounding box centre %.2f mm from its centre, radius of its volume "
      "%.2f mm (the ball's %.1f), %d vertices" % (math.dist(middle, centre), equivalent, radius,
                                                  grown.GetNumberOfPoints()))
check(intersecting is not None and intersecting.GetValue(0) == 0, "no self-intersecting pair")

def sources_in(state):
    simple.ResetSession()
    simple.LoadState(os.path.join(ds_gui.OUT_DIR, state))
    return sorted(p.GetXMLName() for p in simple.GetSources().values())


def points_in(state):
    """The sources' type names and Seed Points' coordinates in `state`."""
    found = sources_in(state)
    points = simple.FindSource("SeedPoints1")
    return found, (list(points.Points) if points else None)


# Undo took the filters back; with Seed Points hidden, a second P and Apply brought them again.
found, placed = points_in("gui_segment_toolbar_again.pvsm")
points = simple.FindSource("SeedPoints1")
surfaces = [p for p in simple.GetSources().values() if p.GetXMLName() == "DeformableSurface"]
check(placed is not None and len(placed) == 6 and len(surfaces) == 1
      and surfaces[0].InitialSurface.Input == points,
      "after Undo, hiding, a second point and Apply: one Deformable Surface on the two points "
      "again (%s, points %s)" % (found, placed))
hidden = servermanager.GetRepresentation(points, simple.GetActiveView()) if points else None
check(hidden is not None and hidden.Visibility == 0,
      "Seed Points hidden for that Apply (its eye; an Apply then updates no data)")


found, placed = points_in("gui_segment_toolbar_undone.pvsm")
shown = simple.GetDisplayProperties(simple.FindSource("ball"), simple.GetActiveView())
check(found == ["XMLImageDataReader"] and shown.Representation == "Outline",
      "five Undo: back to before the button, the image an outline again (%s, %s)"
      % (found, shown.Representation))
found, placed = points_in("gui_segment_toolbar_button_redone.pvsm")
check(found == ["SeedPoints", "XMLImageDataReader"] and placed == [],
      "Redo of the button: Seed Points again, empty, no filter (%s)" % found)
found, placed = points_in("gui_segment_toolbar_apply_redone.pvsm")
check(found == ["SeedPoints", "XMLImageDataReader"] and placed is not None and len(placed) == 3,
      "Redo of the first Apply: its point again, no filter (a Redo makes none; %s, %s)"
      % (found, placed))
found, placed = points_in("gui_segment_toolbar_reset.pvsm")
check(found == ["SeedPoints", "XMLImageDataReader"] and placed is not None and len(placed) == 3,
      "P, then the panel's Reset: still one point, no filter (Reset applies nothing; %s, %s)"
      % (found, placed))
found, placed = points_in("gui_segment_toolbar_redone.pvsm")
points = simple.FindSource("SeedPoints1")
surfaces = [p for p in simple.GetSources().values() if p.GetXMLName() == "DeformableSurface"]
check(placed is not None and len(placed) == 6 and math.dist(placed[:3], centre) <= 0.5
      and len(surfaces) == 1 and surfaces[0].InitialSurface.Input == points,
      "a P and Apply after them: one Deformable Surface on the two points (%s, points %s)"
      % (found, placed))
check.exit()
