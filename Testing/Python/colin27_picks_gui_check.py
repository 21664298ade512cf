# SPDX-License-Identifier: BSD-3-Clause
"""The check of ctest Python.gui_colin27_picks (gui_colin27_picks.py explains the GUI part): run
with pvpython after the client saved DS_TEST_OUTPUT/gui_colin27_picks.pvsm.

- every one of the 44 points placed with P lies within half a voxel (0.5 mm) of its pick in
  Examples/colin27_picks.csv;
- Delaunay Seed Surface on them gives the CSV route's seed (Examples/demo.py: CSV Reader -> Table
  To Points): the same vertices, each within half a voxel of its CSV twin (matched by
  SeedPointId);
- Deformable Surface with every default grows it into the CSV route's surface, as far as the
  solver allows: the mean distance from the GUI route's vertices to the CSV route's surface is at
  most half a voxel, and both are equally accurate (the mean distance of their vertices to the
  brain mask's boundary, ch2bet > 0, differs by at most 0.1 mm). The solver does not keep picks
  a fraction of a voxel apart within 0.1 mm of each other: the number of vertices and the
  surface itself change with them (this test measured 0.10 mm and, with views zoomed closer onto
  the picks, 0.41 mm between the surfaces): sigma_0 is a distance measured in steps of half a
  voxel (docs/METHOD.md §9.1), so a pick moved a fraction of a voxel can change it by a step and
  the hierarchy by a level."""
import math
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "..", "Examples"))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.vtkCommonCore import mutable  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellLocator, vtkGenericCell  # noqa: E402

import demo  # noqa: E402
import ds_gui  # noqa: E402
import ds_scoring  # noqa: E402
import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402

check = ds_gui.Check()
setup = ds_gui.load_state("gui_colin27_picks", check)
picks = setup["picks"]
print("view scales: %s mm per pixel" % ", ".join("%.3f" % m for m in setup["mm_per_pixel"]))
seeds = simple.FindSource("SeedPoints")
placed = list(seeds.Points)
check(len(placed) == 3 * len(picks), "%d points placed for %d picks" % (len(placed) // 3, len(picks)))
errors = [math.dist(placed[3 * i: 3 * i + 3], p) for i, p in enumerate(picks[: len(placed) // 3])]
worst = max(errors) if errors else float("nan")
check(bool(errors) and worst <= 0.5, "every point within 0.5 mm of its pick (worst %.3f mm, mean %.3f mm)"
      % (worst, sum(errors) / max(len(errors), 1)))


def seed_vertices(poly):
    ids = poly.GetPointData().GetArray("SeedPointId")
    return {int(ids.GetValue(i)): poly.GetPoint(i) for i in range(poly.GetNumberOfPoints())}


csv_route = demo.segment_head("colin27", "picks")
seed = simple.DelaunaySeedSurface(Input=seeds)
gui_seed = servermanager.Fetch(seed, idx=0)
ours, theirs = seed_vertices(gui_seed), seed_vertices(csv_route["seed_polydata"])
shift = max((math.dist(ours[k], theirs[k]) for k in ours if k in theirs), default=float("nan"))
check(set(ours) == set(theirs) and gui_seed.GetNumberOfPolys() == csv_route["seed_polydata"].GetNumberOfPolys()
      and shift <= 0.5, "the seed: %d vertices, %d triangles, each vertex within %.3f mm of the CSV route's"
      % (len(ours), gui_seed.GetNumberOfPolys(), shift))

surface = simple.DeformableSurface(Input=csv_route["image_proxy"], InitialSurface=seed)
demo.solve(surface, demo.HEAD_SETTINGS["picks"])
grown = servermanager.Fetch(surface, idx=0)
locator = vtkCellLocator()
locator.SetDataSet(csv_route["polydata"])
locator.BuildLocator()
closest, cell, cell_id, sub_id, d2 = [0.0] * 3, vtkGenericCell(), mutable(0), mutable(0), mutable(0.0)
total = 0.0
for i in range(grown.GetNumberOfPoints()):
    locator.FindClosestPoint(grown.GetPoint(i), closest, cell, cell_id, sub_id, d2)
    total += math.sqrt(float(d2))
mean = total / max(grown.GetNumberOfPoints(), 1)
check(grown.GetNumberOfPoints() > 1000 and mean <= 0.5,
      "the surface: %d vertices (CSV route: %d), %.3f mm from the CSV route's on average"
      % (grown.GetNumberOfPoints(), csv_route["polydata"].GetNumberOfPoints(), mean))
mask = ds_scoring.read_nifti(ds_scoring.BRAIN)
t1 = vtk_to_numpy(mask.GetPointData().GetScalars())
mask.GetPointData().SetScalars(numpy_to_vtk((t1 > 0).astype(np.float32), deep=1))
truth = ds_scoring._iso_surface(mask, 0.5)
accuracy = [float(np.abs(ds_scoring._distances(truth, vtk_to_numpy(poly.GetPoints().GetData()))).mean())
            for poly in (grown, csv_route["polydata"])]
check(abs(accuracy[0] - accuracy[1]) <= 0.1,
      "as accurate: %.3f mm from the brain mask's boundary on average (CSV route: %.3f mm)" % tuple(accuracy))
check.exit()
