# SPDX-License-Identifier: BSD-3-Clause
# The README's pvpython pipeline under `mpiexec -n 2 pvbatch`: readers not yet run, Scalars
# empty; the result gathered on rank 0 must equal a serial run of the same filter (the VTK class
# with no controller, on the same file and the same Box) in points and distance. The .vti is read
# in pieces and solved by every rank (field data PieceVoxels, one count per rank); the NIfTI and
# MetaImage readers cannot split a file, so rank 0 solves alone there (no PieceVoxels).
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview.modules.vtkRemotingCore import vtkProcessModule  # noqa: E402
from vtkmodules.vtkFiltersSources import vtkCubeSource  # noqa: E402
from deformablesurface import vtkDSNIFTIImageReader  # noqa: E402 (the class the reader proxy uses)

import readme_pipeline as rp  # noqa: E402
from deformablesurface import vtkDeformableSurfaceFilter  # noqa: E402

rp.load_plugin()
n_ranks = vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
assert n_ranks >= 2, "run this test under mpiexec with at least 2 processes"
out = os.path.join(os.environ.get("DS_TEST_OUTPUT", "."), "readme_pipeline_mpi")
held = {}
results = rp.run_all(out, held)

# The serial reference: the same filter in this process alone, on the NIfTI phantom.
reader = vtkDSNIFTIImageReader()
reader.SetFileName(os.path.join(out, "ball.nii"))
box = vtkCubeSource()
box.SetXLength(rp.N)
box.SetYLength(rp.N)
box.SetZLength(rp.N)
box.SetCenter(rp.CENTER, rp.CENTER, rp.CENTER)
serial = vtkDeformableSurfaceFilter()
serial.SetController(None)
serial.SetInputConnection(0, reader.GetOutputPort())
serial.SetInputConnection(1, box.GetOutputPort())
rp.ds_invariants.update_filter(serial, "serial reference")
rp.ds_invariants.check_surface(box.GetOutput(), serial.GetOutput(), "serial reference")
n_ref, mean_ref = rp.score(serial.GetOutput())
print("serial reference (NIfTI): %d points, mean |d| %.6f" % (n_ref, mean_ref))

failures = []
for name, (scalars, n, mean) in sorted(results.items()):
    print("%-9s Scalars property %-16s -> %5d points, mean |d| %.6f voxel" % (name, scalars, n, mean))
    if n == 0 or not mean <= rp.TOLERANCE:
        failures.append("%s: %d points, mean |d| %.3f (allowed %.2f)" % (name, n, mean, rp.TOLERANCE))
    elif n != n_ref or abs(mean - mean_ref) > 1e-6 * max(1.0, mean_ref):
        failures.append("%s under MPI: %d points, mean %.6f; serial: %d points, mean %.6f"
                        % (name, n, mean, n_ref, mean_ref))
    in_pieces = name.endswith(".vti")
    if in_pieces and (held[name] is None or len(held[name]) != n_ranks or min(held[name]) <= 0):
        failures.append("%s: solved in pieces by every rank, but PieceVoxels is %s" % (name, held[name]))
    if not in_pieces and held[name] is not None:
        failures.append("%s: rank 0 should solve alone, but the ranks held %s" % (name, held[name]))
    print("%-9s PieceVoxels %s" % (name, held[name]))
# Asserting (not sys.exit) lets pvbatch finalise MPI on every rank when all is well.
assert not failures, "; ".join(failures)
print("mpi_readme_pipeline: all checks passed")
