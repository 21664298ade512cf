# SPDX-License-Identifier: BSD-3-Clause
"""The check of ctest Python.gui_seed_points (gui_seed_points.py explains the GUI part): run with
pvpython after the client saved DS_TEST_OUTPUT/gui_seed_points.pvsm.

- the state holds three seed points (the fourth pick was deleted with the Delete key), each
  within half a voxel (0.5 mm) of where the mouse aimed, on the slice (the first where its
  handle was dragged to: as far as the mouse moved, in whole pixels), with ObjectIds 0 0 1 as the
  spin box said;
- Delaunay Seed Surface (three points: a seed sphere each) and Deformable Surface (IntensityRange
  50 150, so the clicks pull with RegionWeight 1) grow them into three closed surfaces, each on
  its ball: the centre of its bounding box within 0.5 mm of the ball's centre, the radius of a
  ball of its volume within 0.5 mm of the ball's radius;
- the client's view (its camera, the slice) with the traces of the grown surfaces on the slice,
  drawn at 480x360 pixels, matches Testing/Baseline/gui_seed_points.png (ds_gui.compare_view): a
  surface grown elsewhere or to another size fails it;
- a fifth pick, applied, then Edit > Undo: the state holds the three points again; Edit > Redo:
  the fifth is back, within half a voxel of its aim, for the object of the spin box."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.vtkFiltersCore import (vtkCleanPolyData, vtkMassProperties,  # noqa: E402
                                       vtkPolyDataConnectivityFilter)

import ds_gui  # noqa: E402

def pieces(poly):
    """[(centre of the bounding box, radius of the ball of the same volume)] of each connected
    piece: both robust to a mesh whose vertices are not spread evenly."""
    conn = vtkPolyDataConnectivityFilter()
    conn.SetInputData(poly)
    conn.SetExtractionModeToAllRegions()
    conn.Update()
    found = []
    for region in range(conn.GetNumberOfExtractedRegions()):
        conn.SetExtractionModeToSpecifiedRegions()
        conn.InitializeSpecifiedRegionList()
        conn.AddSpecifiedRegion(region)
        clean = vtkCleanPolyData()
        clean.SetInputConnection(conn.GetOutputPort())
        mass = vtkMassProperties()
        mass.SetInputConnection(clean.GetOutputPort())
        mass.Update()
        b = clean.GetOutput().GetBounds()
        centre = [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]
        found.append((centre, (3.0 * mass.GetVolume() / (4.0 * math.pi)) ** (1.0 / 3.0)))
    return found


check = ds_gui.Check()
setup = ds_gui.load_state("gui_seed_points", check)
aims, radius = setup["aims"], setup["radius"]
# Where the points should be: the first one moved with the mouse, in whole pixels.
expected = [list(a) for a in aims]
width, start, end = setup["view"][0], setup["drag"][0], setup["drag"][1]
expected[0][0] += (int(end * width) - int(start * width)) * setup["mm_per_pixel"]
seeds = simple.FindSource("SeedPoints")
points = list(seeds.Points) if seeds else []
check(len(points) == 9, "three points picked (Points holds %d values)" % len(points))
for i, aim in enumerate(expected[: len(points) // 3]):
    got = points[3 * i: 3 * i + 3]
    error = math.dist(got, aim)
    check(error <= 0.5, "pick %d at (%.2f, %.2f, %.2f), %.3f mm from the aim (%.2f, %.2f, %.2f)"
          % ((i,) + tuple(got) + (error,) + tuple(aim)))
check(list(seeds.ObjectIds) == setup["objects"] if seeds else False,
      "ObjectIds %s (the spin box's)" % (list(seeds.ObjectIds) if seeds else None,))

phantom = simple.FindSource("phantom")
seed = simple.DelaunaySeedSurface(Input=seeds, SeedRadius=3.0)
surface = simple.DeformableSurface(Input=phantom, InitialSurface=seed)
surface.Scalars = ["POINTS", "density"]
surface.IntensityRange = [50.0, 150.0]
grown = servermanager.Fetch(surface, arg1=0)
found = pieces(grown)
check(len(found) == 3, "three closed surfaces grown (%d pieces, %d points)" % (len(found), grown.GetNumberOfPoints()))
for centre, equivalent in found:
    aim = min(aims, key=lambda c: math.dist(c, centre))
    check(math.dist(centre, aim) <= 0.5 and abs(equivalent - radius) <= 0.5,
          "surface around (%.1f, %.1f, %.1f): centre %.3f mm off, radius by volume %.3f mm (ball %.1f)"
          % (tuple(aim) + (math.dist(centre, aim), equivalent, radius)))

view = simple.GetRenderViews()[0]
for source in simple.GetSources().values():
    simple.Hide(source, view)
simple.Show(simple.FindSource("Slice"), view)
trace = simple.Slice(Input=surface)
trace.SliceType = "Plane"
trace.SliceType.Origin, trace.SliceType.Normal = expected[0], [0.0, 0.0, 1.0]
line = simple.Show(trace, view)
line.ColorArrayName = ["POINTS", ""]
line.AmbientColor = line.DiffuseColor = [0.2, 0.85, 1.0]
line.Ambient, line.Diffuse = 1.0, 0.0
line.LineWidth = 3.0
line.Position = [0.0, 0.0, 1.0]  # towards the camera, above the slice
check(*ds_gui.compare_view(view, "gui_seed_points.png", [480, 360]))


def saved_points(name):
    simple.ResetSession()
    simple.LoadState(os.path.join(ds_gui.OUT_DIR, name + ".pvsm"))
    seeds = simple.FindSource("SeedPoints")
    return (list(seeds.Points), list(seeds.ObjectIds)) if seeds else ([], [])


undone, undone_ids = saved_points("gui_seed_points_undone")
check(undone == points and undone_ids == setup["objects"],
      "a fifth pick applied and undone: the three points are left (%d coordinates, ObjectIds %s)"
      % (len(undone), undone_ids))
redone, redone_ids = saved_points("gui_seed_points_redone")
fifth = redone[9:12]
check(redone[:9] == points and len(fifth) == 3 and math.dist(fifth, setup["undo_aim"]) <= 0.5
      and redone_ids == setup["objects"] + [setup["objects"][-1]],
      "redone: the fifth point is back (%s, aimed at %s; ObjectIds %s)" % (fifth, setup["undo_aim"], redone_ids))
check.exit()
