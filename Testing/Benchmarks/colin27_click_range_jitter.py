# SPDX-License-Identifier: BSD-3-Clause
"""How far a click's estimated range moves when the click moves by a fraction of a voxel
(docs/RESULTS.md, "A click moved by a fraction of a voxel"; docs/METHOD.md §9.3): the committed
Colin27 clicks (the caudates and putamina of Examples/colin27_nuclei_clicks.csv, the ventricles
of Examples/colin27_ventricle_clicks.csv and the README's white-matter click), each unmoved and
moved at random DRAWS times (a Gaussian of SD mm along each axis, seed 1), through Delaunay Seed
Surface (a 5 mm sphere) and Deformable Surface with PreviewRegion on, every other default: the
range the region force would use, without solving; with --solve, also solved, every default:
the volume each surface encloses, and for the nuclei the mean distance from the surface to its
AAL label's boundary and back (aal.nii.gz of mricron-data, labels 71-74 without their voxels
darker than 60, as BenchObjects scores them; the labels only score). Plain VTK (the plugin's
Python module).

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/colin27_click_range_jitter.py [--solve] [DRAWS [SD]]
"""
import csv
import os
import random
import sys

here = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(here, "..", "..", "Examples")
sys.path.insert(0, EXAMPLES)

import ds_scoring  # noqa: E402
from deformablesurface import vtkDeformableSurfaceFilter, vtkDelaunaySeedSurface  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402


def clicks():
    """(name, AAL label or None, x, y, z) of every committed Colin27 click measured here."""
    names = {71: "left caudate", 72: "right caudate", 73: "left putamen", 74: "right putamen"}
    for name, path in (("nuclei", "colin27_nuclei_clicks.csv"),
                       ("ventricle", "colin27_ventricle_clicks.csv"),
                       ("white matter", "colin27_click.csv")):
        with open(os.path.join(EXAMPLES, path)) as rows:
            for row in csv.DictReader(rows):
                label = int(row["ObjectId"]) if name == "nuclei" else None
                yield (names.get(label, name), label) + tuple(float(row[k]) for k in "xyz")


def label_boundaries(image):
    """The boundary surface of each nucleus's AAL label without its voxels darker than 60."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkImageData
    aal = ds_scoring.read_nifti(os.path.join(ds_scoring.TEMPLATES, "aal.nii.gz"))
    labels = vtk_to_numpy(aal.GetPointData().GetScalars())
    t1 = vtk_to_numpy(image.GetPointData().GetScalars())
    boundaries = {}
    for label in (71, 72, 73, 74):
        mask = vtkImageData()
        mask.CopyStructure(aal)
        scalars = numpy_to_vtk(((labels == label) & (t1 >= 60)).astype(np.uint8), deep=1)
        scalars.SetName("mask")
        mask.GetPointData().SetScalars(scalars)
        boundaries[label] = ds_scoring._iso_surface(mask, 0.5)
    return boundaries


def score(surface, reference):
    """Mean distance surface -> reference boundary and back (mm), and the volume ratio."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    there = np.abs(ds_scoring._distances(reference, vtk_to_numpy(surface.GetPoints().GetData())))
    back = np.abs(ds_scoring._distances(surface, vtk_to_numpy(reference.GetPoints().GetData())))
    return there.mean(), back.mean(), ds_scoring._volume(surface) / ds_scoring._volume(reference)


def click_range(image, centre, solve):
    """The IntensityRange the filter estimates for one click at `centre` (PreviewRegion), and
    with `solve` the surface (a vtkPolyData), else None."""
    points = vtkPoints()
    points.InsertNextPoint(centre)
    click = vtkPolyData()
    click.SetPoints(points)
    seed = vtkDelaunaySeedSurface()
    seed.SetInputData(click)
    surface = vtkDeformableSurfaceFilter()
    surface.SetInputData(image)
    surface.SetInputConnection(1, seed.GetOutputPort())
    surface.SetPreviewRegion(not solve)
    surface.Update()
    r = surface.GetOutput().GetFieldData().GetArray("IntensityRange")
    return ((r.GetValue(0), r.GetValue(1)) if r else (float("nan"), float("nan"))), \
        (surface.GetOutput() if solve else None)


def main(draws, sd, solve):
    image = ds_scoring.read_nifti(ds_scoring.HEAD)
    boundaries = label_boundaries(image) if solve else {}
    rng = random.Random(1)
    print("| click (mm) | object | unmoved range | ranges moved by %g mm s.d. (%d draws) | "
          "low end span | high end span |" % (sd, draws))
    print("|---|---|---|---|---|---|")
    rows = []
    for name, label, x, y, z in clicks():
        unmoved = click_range(image, (x, y, z), solve)
        moved = [click_range(image, tuple(c + rng.gauss(0.0, sd) for c in (x, y, z)), solve)
                 for _ in range(draws)]
        lows = [r[0][0] for r in moved + [unmoved]]
        highs = [r[0][1] for r in moved + [unmoved]]
        print("| (%g, %g, %g) | %s | %.1f-%.1f | %s | %.1f | %.1f |" % (
            x, y, z, name, unmoved[0][0], unmoved[0][1],
            ", ".join("%.1f-%.1f" % r[0] for r in moved), max(lows) - min(lows),
            max(highs) - min(highs)), flush=True)
        rows.append((name, label, [unmoved] + moved))
    if not solve:
        return
    print("\nSolved: per click, unmoved first; volume in ml, and for the nuclei surface -> label / "
          "label -> surface mean (mm) and the volume over the label's")
    print("| object | unmoved | moved |")
    print("|---|---|---|")
    for name, label, runs in rows:
        cells = []
        for _, surface in runs:
            volume = ds_scoring._volume(surface) / 1000.0
            if label is None:
                cells.append("%.1f ml" % volume)
            else:
                there, back, ratio = score(surface, boundaries[label])
                cells.append("%.2f / %.2f, %.2f" % (there, back, ratio))
        print("| %s | %s | %s |" % (name, cells[0], "; ".join(cells[1:])), flush=True)


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--solve"]
    main(int(args[0]) if args else 5, float(args[1]) if len(args) > 1 else 0.3,
         "--solve" in sys.argv[1:])
