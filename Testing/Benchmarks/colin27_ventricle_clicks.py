# SPDX-License-Identifier: BSD-3-Clause
"""One click in Colin27's lateral ventricles, every default (docs/RESULTS.md, docs/METHOD.md §9.3
"Front levels"): the points of Examples/colin27_ventricle_clicks.csv, chosen on coronal slices
y = -10 and -14 mm of the T1 (mricron-data ch2.nii.gz) where it reads 28-30 (CSF) in the bodies
of the left and right lateral ventricles, each through Delaunay Seed Surface (a 5 mm sphere) and
Deformable Surface. Prints a row per click: the range the click estimated, the solve's seconds,
vertices, enclosed volume, self-intersecting pairs, front levels and the run's warnings.

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

demo.load_plugin(sys.argv[1] if len(sys.argv) > 1 else None)
image = demo.nifti_source(ds_scoring.HEADS["colin27"]["image"])
image.UpdatePipeline()
clicks = os.path.join(here, "..", "..", "Examples", "colin27_ventricle_clicks.csv")
print("| click (mm) | range | s | vertices | volume | self-int. | front levels |")
print("|---|---|---|---|---|---|---|")
for row in csv.DictReader(open(clicks)):
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
    print("| (%g, %g, %g) | %s | %.1f | %d | %.1f ml | %d | %d |" % (
        centre[0], centre[1], centre[2],
        "[%.1f, %.1f]" % used.GetTuple2(0) if used else "-", seconds, poly.GetNumberOfPoints(),
        ds_scoring._volume(poly) / 1000.0 if poly.GetNumberOfPoints() else 0.0,
        value("SelfIntersections"), value("FrontLevels")))
    sys.stdout.flush()
    for source in (surface, seed, point):
        simple.Delete(source)
