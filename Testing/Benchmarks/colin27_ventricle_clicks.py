# SPDX-License-Identifier: BSD-3-Clause
"""One click in Colin27's lateral ventricles, every default (docs/RESULTS.md, docs/METHOD.md §9.3
"Front levels"): the points of Examples/colin27_ventricle_clicks.csv, chosen on coronal slices
y = -10 and -14 mm of the T1 (mricron-data ch2.nii.gz) where it reads 28-30 (CSF) in the bodies
of the left and right lateral ventricles, each through Delaunay Seed Surface (a 5 mm sphere) and
Deformable Surface. Prints a row per click: the range the click estimated, the solve's seconds,
vertices, enclosed volume, self-intersecting pairs and front levels (Python.pvpython_colin27_ventricle_clicks
checks them).

    PYTHONPATH=build/lib/python3/dist-packages pvpython Testing/Benchmarks/colin27_ventricle_clicks.py \\
        build/lib/paraview-5.11/plugins/DeformableSurface/DeformableSurface.so
"""
import csv
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "Examples"))
from paraview import servermanager, simple  # noqa: E402

import demo  # noqa: E402
import ds_scoring  # noqa: E402

CLICKS = os.path.join(here, "..", "..", "Examples", "colin27_ventricle_clicks.csv")


def solve_clicks(plugin):
    """Yields, per click of CLICKS: its centre, range (None without one), seconds, vertices,
    volume (ml), SelfIntersections, FrontLevels and the surface (a vtkPolyData)."""
    demo.load_plugin(plugin)
    image = demo.nifti_source(ds_scoring.HEADS["colin27"]["image"])
    image.UpdatePipeline()
    for row in csv.DictReader(open(CLICKS)):
        centre = [float(row[k]) for k in "xyz"]
        point = simple.PointSource(NumberOfPoints=1, Radius=0.0, Center=centre)
        seed = simple.DelaunaySeedSurface(Input=point)
        surface = simple.DeformableSurface(Input=image, InitialSurface=seed)
        seconds = demo.solve(surface, {})
        poly = servermanager.Fetch(surface, arg1=0)
        fields = poly.GetFieldData()

        def value(name):
            array = fields.GetArray(name)
            return array.GetTuple1(0) if array else float("nan")

        used = fields.GetArray("IntensityRange")
        yield {"centre": centre, "range": used.GetTuple2(0) if used else None, "seconds": seconds,
               "vertices": poly.GetNumberOfPoints(),
               "volume": ds_scoring._volume(poly) / 1000.0 if poly.GetNumberOfPoints() else 0.0,
               "self_intersections": value("SelfIntersections"), "front_levels": value("FrontLevels"),
               "surface": poly}
        for source in (surface, seed, point):
            simple.Delete(source)


if __name__ == "__main__":
    print("| click (mm) | range | s | vertices | volume | self-int. | front levels |")
    print("|---|---|---|---|---|---|---|")
    for r in solve_clicks(sys.argv[1] if len(sys.argv) > 1 else None):
        print("| (%g, %g, %g) | %s | %.1f | %d | %.1f ml | %d | %d |" % (
            tuple(r["centre"]) + ("[%.1f, %.1f]" % r["range"] if r["range"] else "-", r["seconds"],
                                  r["vertices"], r["volume"], r["self_intersections"], r["front_levels"])))
        sys.stdout.flush()
