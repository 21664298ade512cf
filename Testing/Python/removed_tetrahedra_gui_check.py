# SPDX-License-Identifier: BSD-3-Clause
"""The check of ctest Python.gui_removed_tetrahedra (gui_removed_tetrahedra.py explains the GUI
part): run with pvpython after the client saved DS_TEST_OUTPUT/gui_removed_tetrahedra.pvsm.

The aims lie in two different tetrahedra A and B (found here by locating the aimed points in the
Tetrahedra output); P over A, B, A must leave Removed Tetrahedra = [B]: B removed, A kept again.
The filter, run on the saved state, marks B removed by ID (Removed = 1) and A kept, and its
surface stays a closed, manifold, outward-oriented surface (ds_invariants). Solved on a ball
that the points enclose, the seed without B shrinks onto it (the radius of a ball of its volume
within half a voxel), and the client's view of the slice, coloured by Removed, with the trace of
the solved surface matches Testing/Baseline/gui_removed_tetrahedra.png (ds_gui.compare_view): a
different tetrahedron removed or a surface off the ball fails it. The second state,
saved after a thirteenth seed point was picked and applied, has an empty Removed Tetrahedra: the
TetraIds were renumbered, so the panel cleared the list."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellLocator  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkMassProperties  # noqa: E402

import ds_gui  # noqa: E402
import ds_invariants  # noqa: E402
import numpy as np  # noqa: E402

check = ds_gui.Check()
setup = ds_gui.load_state("gui_removed_tetrahedra", check)
seed = simple.FindSource("DelaunaySeedSurface")
tets = servermanager.Fetch(seed, idx=1)
locator = vtkCellLocator()
locator.SetDataSet(tets)
locator.BuildLocator()
tetra_ids = tets.GetCellData().GetArray("TetraId")
a, b = [int(tetra_ids.GetValue(locator.FindCell(aim))) for aim in setup["aims"]]
check(a != b, "the aims lie in two tetrahedra, A = %d and B = %d" % (a, b))
removed = [int(v) for v in seed.RemovedTetrahedra]
check(removed == [b], "Removed Tetrahedra %s after P over A, B, A (expected [%d])" % (removed, b))
status = tets.GetCellData().GetArray("Removed")
check(status.GetValue(b) == 1 and status.GetValue(a) != 1,
      "the filter removed B by ID (Removed %d) and kept A (Removed %d)" % (status.GetValue(b), status.GetValue(a)))
surface = servermanager.Fetch(seed, idx=0)
try:
    ds_invariants.check_closed_manifold(ds_invariants.surface_facts(surface), "seed without B")
    check(True, "the seed without B is closed and manifold (%d triangles)" % surface.GetNumberOfPolys())
except AssertionError as error:
    check(False, str(error))

# The solve: the seed without B shrinks onto a ball of radius BALL (value 100 inside, 0 outside,
# a one-voxel ramp) that the twelve points enclose; the view of the slice, coloured by Removed,
# with the trace of the grown surface must match the baseline.
BALL = 16.0
axis = np.arange(-30.0, 31.0)
z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
ball = 100.0 * np.clip(BALL + 0.5 - np.sqrt(x * x + y * y + z * z), 0.0, 1.0)
phantom_path = os.path.join(ds_gui.OUT_DIR, "removed_tetrahedra_phantom.vti")
ds_gui.write_phantom(ball, (-30.0, -30.0, -30.0), phantom_path)
phantom = simple.XMLImageDataReader(FileName=[phantom_path])
solved = simple.DeformableSurface(Input=phantom, InitialSurface=seed)
solved.Scalars = ["POINTS", "density"]
grown = servermanager.Fetch(solved, arg1=0)
mass = vtkMassProperties()
mass.SetInputData(grown)
mass.Update()
radius = (3.0 * mass.GetVolume() / (4.0 * math.pi)) ** (1.0 / 3.0)
check(abs(radius - BALL) <= 0.5, "the seed without B solved onto the ball: radius by volume %.3f mm (ball %.1f)"
      % (radius, BALL))
view = simple.GetRenderViews()[0]
cut = simple.FindSource("TetrahedraSlice")
simple.ColorBy(simple.GetDisplayProperties(cut, view), ("CELLS", "Removed"))
trace = simple.Slice(Input=solved)
trace.SliceType = "Plane"
trace.SliceType.Origin, trace.SliceType.Normal = [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]
line = simple.Show(trace, view)
line.ColorArrayName = ["POINTS", ""]
line.AmbientColor = line.DiffuseColor = [0.2, 0.85, 1.0]
line.Ambient, line.Diffuse = 1.0, 0.0
line.LineWidth = 3.0
line.Position = [0.0, 0.0, 5.0]  # towards the camera, clear above the slice and its edges
check(*ds_gui.compare_view(view, "gui_removed_tetrahedra.png", [480, 360]))

simple.ResetSession()
simple.LoadState(os.path.join(ds_gui.OUT_DIR, "gui_removed_tetrahedra_renumbered.pvsm"))
seeds, seed = simple.FindSource("SeedPoints"), simple.FindSource("DelaunaySeedSurface")
check(len(seeds.Points) == 3 * (len(setup["points"]) + 1), "a thirteenth point picked (%d coordinates)" % len(seeds.Points))
check(len(seed.RemovedTetrahedra) == 0,
      "Removed Tetrahedra cleared when the tetrahedrisation changed (%s)" % list(seed.RemovedTetrahedra))
check.exit()
