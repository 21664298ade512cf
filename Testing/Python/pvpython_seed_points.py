# SPDX-License-Identifier: BSD-3-Clause
"""Seed Points (vtkDSSeedPoints) through ParaView proxies:
- the demo's picks given as SeedPoints(Points=[...]) give, through Delaunay Seed Surface and
  Deformable Surface, the same seed and the same surface, bit for bit, as the demo's CSV route
  (CSV Reader -> Table To Points, Examples/demo.py);
- a state file saved and loaded again holds the same points and gives the same output;
- the ObjectId array carries ObjectIds (0 for every point when none are given), and bad input
  (a count that is not a multiple of 3, a NaN, an ObjectIds count that does not match) gives an
  empty output."""
import csv
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "Examples"))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

import demo  # noqa: E402

demo.load_plugin()
out_dir = os.environ.get("DS_TEST_OUTPUT", "/tmp")
os.makedirs(out_dir, exist_ok=True)
failures = []


def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what)
    if not ok:
        failures.append(what)


def same_polydata(a, b):
    """Equal point coordinates (bit for bit, as doubles) and equal triangle connectivity."""
    if a.GetNumberOfPoints() != b.GetNumberOfPoints() or a.GetNumberOfPolys() != b.GetNumberOfPolys():
        return False
    pa = vtk_to_numpy(a.GetPoints().GetData()).astype("float64")
    pb = vtk_to_numpy(b.GetPoints().GetData()).astype("float64")
    ca = vtk_to_numpy(a.GetPolys().GetConnectivityArray())
    cb = vtk_to_numpy(b.GetPolys().GetConnectivityArray())
    return bool((pa == pb).all() and (ca == cb).all())


def object_ids(source):
    data = servermanager.Fetch(source)
    array = data.GetPointData().GetArray("ObjectId")
    return None if array is None else [array.GetValue(i) for i in range(array.GetNumberOfTuples())]


# 1. The demo's picks: the CSV route against Seed Points.
demo.require_data()
csv_route = demo.segment_head("colin27", "picks")
with open(demo.HEADS["colin27"]["picks"]) as f:
    picks = [[float(row[k]) for k in ("x", "y", "z")] for row in csv.DictReader(f)]
seeds = simple.SeedPoints(Points=[c for p in picks for c in p])
seed = simple.DelaunaySeedSurface(Input=seeds)
surface = simple.DeformableSurface(Input=csv_route["image_proxy"], InitialSurface=seed)
demo.solve(surface, demo.HEAD_SETTINGS["picks"])
check(object_ids(seeds) == [0] * len(picks), "%d picks, ObjectId 0 each" % len(picks))
check(same_polydata(servermanager.Fetch(seed, arg1=0), csv_route["seed_polydata"]),
      "the seed equals the CSV route's (%d points)" % csv_route["seed_polydata"].GetNumberOfPoints())
grown = servermanager.Fetch(surface, arg1=0)
check(grown.GetNumberOfPoints() > 1000 and same_polydata(grown, csv_route["polydata"]),
      "the surface equals the CSV route's, bit for bit (%d points)" % grown.GetNumberOfPoints())

# 2. A state file keeps the points and the objects.
seeds.ObjectIds = [i % 3 for i in range(len(picks))]
expected_ids = object_ids(seeds)
check(expected_ids == [i % 3 for i in range(len(picks))], "ObjectIds reach the ObjectId array")
before = servermanager.Fetch(seeds)
state = os.path.join(out_dir, "seed_points_state.pvsm")
simple.SaveState(state)
simple.ResetSession()
check(simple.FindSource("SeedPoints1") is None, "the session is empty after ResetSession")
simple.LoadState(state)
loaded = simple.FindSource("SeedPoints1")
check(loaded is not None and list(loaded.Points) == [c for p in picks for c in p],
      "the loaded state holds the same Points")
check(loaded is not None and object_ids(loaded) == expected_ids, "... and the same ObjectIds")
after = servermanager.Fetch(loaded) if loaded is not None else None
check(after is not None and (vtk_to_numpy(after.GetPoints().GetData()) ==
                             vtk_to_numpy(before.GetPoints().GetData())).all(),
      "... and the same output points")

# 3. Bad input: an error and an empty output.
for points, ids, what in (([0.0, 0.0, 0.0, 1.0], [], "4 coordinates"),
                          ([0.0, float("nan"), 0.0], [], "a NaN"),
                          ([0.0, 0.0, 0.0], [1, 2], "2 ObjectIds for 1 point")):
    bad = simple.SeedPoints(Points=points, ObjectIds=ids)
    check(servermanager.Fetch(bad).GetNumberOfPoints() == 0, "%s: empty output" % what)

for f in failures:
    print("FAILED:", f)
sys.exit(1 if failures else 0)
