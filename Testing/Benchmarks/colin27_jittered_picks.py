# SPDX-License-Identifier: BSD-3-Clause
"""How much the README's picks may move before the surface does (docs/METHOD.md §9.1, "Why D is
not read between the rays' samples"): the 44 points of Examples/colin27_picks.csv, each moved at
random (a Gaussian of SD mm along each axis, DRAWS draws, seed 1), through Seed Points, Delaunay
Seed Surface and Deformable Surface, every default, as the picks of the GUI would come (the P key
places a pick within half a pixel of where it was aimed). Prints a row per draw: sigma_0
(InitialSigma), levels, vertices, the mean distance of its vertices to the surface of the
unmoved picks, and its mean distance to the brain mask's boundary (ch2bet > 0). With TOLERANCE,
every solve (the unmoved picks' too) takes that ConvergenceTolerance instead of the default.

    PYTHONPATH=build/lib/python3/dist-packages pvpython Testing/Benchmarks/colin27_jittered_picks.py \\
        build/lib/paraview-5.11/plugins/DeformableSurface/DeformableSurface.so [DRAWS [SD [TOLERANCE]]]
"""
import csv
import math
import os
import random
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "Examples"))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.vtkCommonCore import mutable  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellLocator, vtkGenericCell  # noqa: E402

import demo  # noqa: E402
import ds_scoring  # noqa: E402
import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402


def mean_distance(poly, locator):
    """Mean distance of poly's vertices to the surface the locator holds."""
    closest, cell, cell_id, sub_id, d2 = [0.0] * 3, vtkGenericCell(), mutable(0), mutable(0), mutable(0.0)
    total = 0.0
    for i in range(poly.GetNumberOfPoints()):
        locator.FindClosestPoint(poly.GetPoint(i), closest, cell, cell_id, sub_id, d2)
        total += math.sqrt(float(d2))
    return total / max(poly.GetNumberOfPoints(), 1)


def field(poly, name):
    return poly.GetFieldData().GetArray(name).GetValue(0)


def brain_boundary():
    """The brain mask's boundary (ch2bet > 0, its 0.5 iso-surface), as ds_scoring measures it."""
    mask = ds_scoring.read_nifti(ds_scoring.BRAIN)
    t1 = vtk_to_numpy(mask.GetPointData().GetScalars())
    mask.GetPointData().SetScalars(numpy_to_vtk((t1 > 0).astype(np.float32), deep=1))
    return ds_scoring._iso_surface(mask, 0.5)


def main(plugin, draws, sd, tolerance=None):
    demo.load_plugin(plugin)
    reference = demo.segment_head("colin27", "picks")
    settings = {} if tolerance is None else {"ConvergenceTolerance": tolerance}
    if settings:
        demo.solve(reference["surface"], settings)
        reference["polydata"] = servermanager.Fetch(reference["surface"], idx=0)
    truth = brain_boundary()

    def accuracy(poly):
        points = vtk_to_numpy(poly.GetPoints().GetData())
        return float(np.abs(ds_scoring._distances(truth, points)).mean())

    locator = vtkCellLocator()
    locator.SetDataSet(reference["polydata"])
    locator.BuildLocator()
    with open(ds_scoring.HEADS["colin27"]["picks"]) as f:
        picks = [[float(row[k]) for k in "xyz"] for row in csv.DictReader(f)]
    print("| draw | sigma_0 (mm) | levels | vertices | to the unmoved picks' surface (mm) | to the brain (mm) |")
    print("|---|---|---|---|---|---|")
    poly = reference["polydata"]
    print("| unmoved | %.3f | %d | %d | 0 | %.3f |" % (field(poly, "InitialSigma"), field(poly, "Levels"),
                                                      poly.GetNumberOfPoints(), accuracy(poly)), flush=True)
    rng = random.Random(1)
    for draw in range(draws):
        moved = [c + rng.gauss(0.0, sd) for p in picks for c in p]
        points = simple.SeedPoints(Points=moved)
        seed = simple.DelaunaySeedSurface(Input=points)
        surface = simple.DeformableSurface(Input=reference["image_proxy"], InitialSurface=seed)
        demo.solve(surface, settings)
        poly = servermanager.Fetch(surface, idx=0)
        print("| %d | %.3f | %d | %d | %.3f | %.3f |" % (
            draw + 1, field(poly, "InitialSigma"), field(poly, "Levels"), poly.GetNumberOfPoints(),
            mean_distance(poly, locator), accuracy(poly)), flush=True)
        for proxy in (surface, seed, points):
            simple.Delete(proxy)


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 10,
         float(sys.argv[3]) if len(sys.argv) > 3 else 0.07,
         float(sys.argv[4]) if len(sys.argv) > 4 else None)
