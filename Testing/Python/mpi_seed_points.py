# SPDX-License-Identifier: BSD-3-Clause
"""Seed Points in distributed ParaView: run as
    mpiexec -n 2 pvbatch mpi_seed_points.py
Every rank runs the source, but only rank 0 may hold the points: Delaunay Seed Surface gathers
the points of all ranks, so points on every rank would enter the tetrahedrisation once per rank.
Checks: rank 0 holds the 8 points and 8 vertices, rank 1 nothing; the seed of the cube's corners
has the 12 triangles and the SeedPointIds 0..7 of a serial run."""
import builtins
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from paraview.modules.vtkRemotingCore import vtkProcessModule  # noqa: E402

from ds_mpi import per_rank  # noqa: E402

simple.LoadPlugin(os.environ["DS_PLUGIN"])
n_ranks = vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
assert n_ranks >= 2, "run this test under mpiexec with at least 2 processes"

corners = [10.0 * c for k in range(2) for j in range(2) for i in range(2) for c in (i, j, k)]
seeds = simple.SeedPoints(Points=corners)
split = per_rank(seeds)
# builtins: the ProgrammableFilter of per_rank runs in this interpreter and replaces any().
print("per rank (points, cells):", split)
failures = []
if split.get(0) != (8, 8) or builtins.any(split[r] != (0, 0) for r in split if r != 0):
    failures.append("the points are not on rank 0 alone: %s" % split)
seed = servermanager.Fetch(simple.DelaunaySeedSurface(Input=seeds), arg1=0)
ids = seed.GetPointData().GetArray("SeedPointId")
got = sorted(int(ids.GetValue(i)) for i in range(ids.GetNumberOfTuples())) if ids else []
print("seed: %d triangles, SeedPointIds %s" % (seed.GetNumberOfPolys(), got))
if seed.GetNumberOfPolys() != 12 or got != list(range(8)):
    failures.append("seed of %d triangles with SeedPointIds %s (a cube: 12, 0..7)" % (seed.GetNumberOfPolys(), got))
# An assert, not sys.exit: pvbatch must finalize MPI on rank 0 after a pass.
assert not failures, "; ".join(failures)
print("mpi_seed_points: all checks passed")
