# SPDX-License-Identifier: BSD-3-Clause
"""DelaunaySeedSurface through ParaView proxies: a CSV through TableToPoints, the tetrahedra
output and RemovedTetrahedra, and the Examples/ workflow (slices -> Extract Selection -> seed)
whose intensity rule must give the torus phantom's genus."""
import builtins
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkMassProperties  # noqa: E402

import ds_invariants  # noqa: E402

simple.LoadPlugin(os.environ["DS_PLUGIN"])
assert hasattr(simple, "DelaunaySeedSurface"), "proxy DelaunaySeedSurface missing"

out_dir = os.environ.get("DS_TEST_OUTPUT", "/tmp")
os.makedirs(out_dir, exist_ok=True)


def facts(poly):
    """(triangles, Euler characteristic, edges not used twice, volume)."""
    edges = {}
    conn = poly.GetPolys()
    ids = conn.GetConnectivityArray()
    n = poly.GetNumberOfCells()
    used = set()
    for c in range(n):
        tri = [ids.GetValue(3 * c + j) for j in range(3)]
        used.update(tri)
        for j in range(3):
            key = tuple(sorted((tri[j], tri[(j + 1) % 3])))
            edges[key] = edges.get(key, 0) + 1
    # builtins: ProgrammableSource scripts run in this interpreter and import numpy-style sum
    bad = builtins.sum(1 for v in edges.values() if v != 2)
    volume = 0.0
    if n:
        mass = vtkMassProperties()
        mass.SetInputData(poly)
        mass.Update()
        volume = mass.GetVolume()
    euler = len(used) - len(edges) + n
    print("  %d triangles, Euler %d, %d bad edges, volume %.3f" % (n, euler, bad, volume))
    # Every seed here is a valid surface: closed, manifold, outward, finite, its own Euler.
    ds_invariants.check_closed_manifold(ds_invariants.surface_facts(poly), "seed", euler=euler)
    return n, euler, bad, volume


# 1. Cube corners from a CSV file.
csv = os.path.join(out_dir, "delaunay_seed_cube.csv")
with open(csv, "w") as f:
    f.write("x,y,z\n")
    for k in range(2):
        for j in range(2):
            for i in range(2):
                f.write("%g,%g,%g\n" % (10 * i, 10 * j, 10 * k))
reader = simple.CSVReader(FileName=[csv])
points = simple.TableToPoints(Input=reader, XColumn="x", YColumn="y", ZColumn="z")
seed = simple.DelaunaySeedSurface(Input=points)
for name in ("RemovedTetrahedra", "Alpha", "UseIntensityRange", "IntensityRange", "TargetEdgeLength", "Tolerance"):
    assert name in seed.ListProperties(), name
ds_invariants.update_proxy(seed, [points], "DelaunaySeedSurface from the CSV")
print("CSV cube:")
n, euler, bad, volume = facts(servermanager.Fetch(seed))
assert n == 12 and euler == 2 and bad == 0 and abs(volume - 1000.0) < 1e-6, "cube surface"

tets = servermanager.Fetch(seed, idx=1)
n_tets = tets.GetNumberOfCells()
for name in ("TetraId", "Removed", "Circumradius"):
    assert tets.GetCellData().GetArray(name) is not None, "cell array " + name
print("  %d tetrahedra" % n_tets)
assert n_tets >= 5

# 2. Delete one tetrahedron by ID: flagged 1 in output 1, the surface loses its volume.
seed.RemovedTetrahedra = [0]
seed.UpdatePipeline()
tets = servermanager.Fetch(seed, idx=1)
removed = tets.GetCellData().GetArray("Removed")
flags = [int(removed.GetValue(i)) for i in range(removed.GetNumberOfTuples())]
print("  Removed flags with RemovedTetrahedra=[0]:", flags)
assert flags[0] == 1 and builtins.sum(1 for v in flags if v != 0) == 1, "only tetrahedron 0 removed"
n, euler, bad, volume = facts(servermanager.Fetch(seed))
assert bad == 0 and volume < 1000.0 - 1.0, "surface without tetrahedron 0"
seed.RemovedTetrahedra = []
seed.UpdatePipeline()
assert facts(servermanager.Fetch(seed))[0] == 12, "clearing the list restores the cube"

# 3. The Examples/ workflow on the torus phantom: genus 1 (Euler 0) by the intensity rule,
# genus 0 (the convex hull, Euler 2) without it.
here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "Examples"))
import pvpython_seed_workflow as workflow  # noqa: E402

proxies = workflow.build_pipeline()
print("Workflow, %d picked points, intensity rule on:" % proxies["n_picked"])
n, euler, bad, volume = facts(servermanager.Fetch(proxies["seed"]))
torus_volume = 2 * 3.141592653589793 ** 2 * 20.0 * 8.0 ** 2
print("  phantom torus volume %.0f; seed covers slices z = 26..38 only" % torus_volume)
assert bad == 0 and euler == 0, "genus-1 seed"
assert 0.5 * torus_volume < volume < torus_volume, "seed volume inside the torus"
proxies["seed"].UseIntensityRange = 0
print("Workflow, intensity rule off:")
n, euler, bad, volume = facts(servermanager.Fetch(proxies["seed"]))
assert bad == 0 and euler == 2 and volume > torus_volume, "convex hull without the rule"
print("pvpython_delaunay_seed: all checks passed")
