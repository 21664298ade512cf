# SPDX-License-Identifier: BSD-3-Clause
"""The check of ctest Python.gui_removed_tetrahedra (gui_removed_tetrahedra.py explains the GUI
part): run with pvpython after the client saved DS_TEST_OUTPUT/gui_removed_tetrahedra.pvsm.

The aims lie in two different tetrahedra A and B (found here by locating the aimed points in the
Tetrahedra output); P over A, B, A must leave Removed Tetrahedra = [B]: B removed, A kept again.
The filter, run on the saved state, marks B removed by ID (Removed = 1) and A kept, and its
surface stays a closed, manifold, outward-oriented surface (ds_invariants). The second state,
saved after a thirteenth seed point was picked and applied, has an empty Removed Tetrahedra: the
TetraIds were renumbered, so the panel cleared the list."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellLocator  # noqa: E402

import ds_gui  # noqa: E402
import ds_invariants  # noqa: E402

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

simple.ResetSession()
simple.LoadState(os.path.join(ds_gui.OUT_DIR, "gui_removed_tetrahedra_renumbered.pvsm"))
seeds, seed = simple.FindSource("SeedPoints"), simple.FindSource("DelaunaySeedSurface")
check(len(seeds.Points) == 3 * (len(setup["points"]) + 1), "a thirteenth point picked (%d coordinates)" % len(seeds.Points))
check(len(seed.RemovedTetrahedra) == 0,
      "Removed Tetrahedra cleared when the tetrahedrisation changed (%s)" % list(seed.RemovedTetrahedra))
check.exit()
