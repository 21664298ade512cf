# SPDX-License-Identifier: BSD-3-Clause
"""The whole-head solves of the README's main job, timed in plain VTK Python (what a C++ or VTK
Python user runs; pvbatch adds ParaView's pipeline around the same filter):

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Testing/Benchmarks/BenchHeads.py [RUNS]

(`scripts/benchmark.sh Heads` does this.) For each head (Colin27 from mricron-data, ITK's
KmeansTest from insighttoolkit5-examples) and start (the picked points with every default; one
click with the user's IntensityRange (so RegionWeight 1), as Examples/ds_scoring.py's HEADS), RUNS
solves (default 5) of vtkDeformableSurfaceFilter from the same seed, the seed and the reading
outside the clock; and, in the same run for comparison, vtkFlyingEdges3D on the same head at the
same CSF/cortex level (what a user would try first: README). Prints one row per solve: min,
median and max seconds, the vertices, and the median over the iso-surface's median."""
import csv
import os
import statistics
import sys
import time

from deformablesurface import vtkDeformableSurfaceFilter, vtkDelaunaySeedSurface
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples"))
from ds_scoring import HEADS, read_nifti  # noqa: E402 (each head's image, picks, click, range, iso level)


def seed(case, start):
    points = vtkPoints()
    with open(HEADS[case][start]) as f:
        for row in csv.DictReader(f):
            points.InsertNextPoint(float(row["x"]), float(row["y"]), float(row["z"]))
    cloud = vtkPolyData()
    cloud.SetPoints(points)
    delaunay = vtkDelaunaySeedSurface()
    delaunay.SetInputData(cloud)
    delaunay.Update()
    return delaunay.GetOutput()


def timed(make, runs):
    seconds, last = [], None
    for _ in range(runs):
        algorithm = make()
        t0 = time.perf_counter()
        algorithm.Update()
        seconds.append(time.perf_counter() - t0)
        last = algorithm.GetOutput()
    return seconds, last


def main():
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    print("| head | start | runs | min s | median s | max s | vertices | vtkFlyingEdges3D median s | ratio |")
    print("|---|---|---|---|---|---|---|---|---|")
    for case, head in HEADS.items():
        path, click_range, iso_level = head["image"], head["range"], head["iso"]
        if not os.path.exists(path):
            print("| %s | | | | | | missing %s | | |" % (case, path))
            continue
        image = read_nifti(path)

        def iso():
            flying = vtkFlyingEdges3D()
            flying.SetInputData(image)
            flying.SetValue(0, iso_level)
            return flying

        iso_median = statistics.median(timed(iso, runs)[0])
        for start in ("picks", "click"):
            start_surface = seed(case, start)

            def solve():
                surface = vtkDeformableSurfaceFilter()
                surface.SetInputData(0, image)
                surface.SetInitialSurfaceData(start_surface)
                if start == "click":
                    surface.SetIntensityRange(*click_range)
                return surface

            seconds, out = timed(solve, runs)
            median = statistics.median(seconds)
            print("| %s | %s | %d | %.2f | %.2f | %.2f | %d | %.3f | %.0f |"
                  % (case, start, runs, min(seconds), median, max(seconds), out.GetNumberOfPoints(),
                     iso_median, median / iso_median), flush=True)


if __name__ == "__main__":
    main()
