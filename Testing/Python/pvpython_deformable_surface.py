# SPDX-License-Identifier: BSD-3-Clause
# pvpython: load the plugin, deform ParaView's Sphere source (seam and poles: points
# must be merged) onto a soft ball phantom of radius 20 made with Wavelet + Calculator,
# and check the numbers a user would look at.
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

import ds_invariants  # noqa: E402

LoadPlugin(os.environ["DS_PLUGIN"], ns=globals())

wavelet = Wavelet(WholeExtent=[-32, 32, -32, 32, -32, 32])
ball = Calculator(Input=wavelet, ResultArrayName="ball",
                  Function="1/(1+exp(4*(sqrt(coordsX^2+coordsY^2+coordsZ^2)-20)))")
start = Sphere(Radius=23.0, ThetaResolution=48, PhiResolution=48)

ds = DeformableSurface(Input=ball, InitialSurface=start)
ds.Scalars = ["POINTS", "ball"]
ds.Sigma = 1.5
ds.MaxLevels = 0  # single level: the hierarchy has its own tests
ds.MaxSweepsPerLevel = 1500
ds.ConvergenceTolerance = 1e-4
ds_invariants.update_proxy(ds, [ball, start], "DeformableSurface")

surface = servermanager.Fetch(ds, arg1=0)
table = servermanager.Fetch(ds, idx=1)
ds_invariants.check_surface(servermanager.Fetch(start), surface, "Sphere onto the ball")

n = surface.GetNumberOfPoints()
dist = [abs(math.sqrt(sum(c * c for c in surface.GetPoint(i))) - 20.0) for i in range(n)]
mean_d = sum(dist) / max(n, 1)
max_d = max(dist) if dist else float("inf")
fd = surface.GetFieldData()
sweeps = int(fd.GetArray("Sweeps").GetTuple1(0))
selfx = int(fd.GetArray("SelfIntersections").GetTuple1(0))
print("points %d (Sphere source: %d), sweeps %d, mean |d| %.4f, max |d| %.4f, self-intersections %d"
      % (n, start.GetDataInformation().GetNumberOfPoints(), sweeps, mean_d, max_d, selfx))

failures = []
if n != 48 * 46 + 2:
    failures.append("seam/pole points not merged: %d points" % n)
if not mean_d <= 0.25:
    failures.append("mean |d| %.4f > 0.25" % mean_d)
if not max_d <= 0.6:
    failures.append("max |d| %.4f > 0.6" % max_d)
if selfx != 0:
    failures.append("%d self-intersections" % selfx)
if table.GetNumberOfRows() != sweeps or table.GetNumberOfColumns() != 7:
    failures.append("convergence table %d x %d for %d sweeps"
                    % (table.GetNumberOfRows(), table.GetNumberOfColumns(), sweeps))
for name in ("Normals", "Displacement", "ExternalForce", "ErrorIndicator"):
    if surface.GetPointData().GetArray(name) is None:
        failures.append("point array %s missing" % name)
first = table.GetColumnByName("MeanCorrection").GetValue(0)
last = table.GetColumnByName("MeanCorrection").GetValue(table.GetNumberOfRows() - 1)
mc = table.GetColumnByName("MeanCorrection")
print("mean correction by sweep: " + ", ".join(
    "%d: %.3g" % (i + 1, mc.GetValue(i)) for i in range(0, table.GetNumberOfRows(), 100)))
# The UV sphere's vertices keep sliding slowly along the surface towards the even
# spacing the umbrella operator prefers (tangential, so the shape is already done).
if not last < 0.02 * first:
    failures.append("mean correction did not decrease 50x: %.3g -> %.3g" % (first, last))

if failures:
    for f in failures:
        print("FAILED:", f)
    sys.exit(1)
print("pvpython_deformable_surface: all checks passed")
