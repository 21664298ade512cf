# SPDX-License-Identifier: BSD-3-Clause
"""The convergence table (output port 1 of DeformableSurface) plots in a Line Chart View,
as a user would show it: mean correction per sweep, log scale. Checks the table (one row
per sweep, the levels in order, each level's correction falling to its end) and that the
chart really draws the series (pixels of the series colour in the saved picture)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402

import ds_invariants  # noqa: E402

simple.LoadPlugin(os.environ["DS_PLUGIN"])
out_dir = os.environ.get("DS_TEST_OUTPUT", ".")
os.makedirs(out_dir, exist_ok=True)

# A bright ball of radius 12 in Wavelet's grid; the start is a sphere of radius 17.
image = simple.Wavelet(WholeExtent=[-20, 20, -20, 20, -20, 20])
ball = simple.Calculator(Input=image, ResultArrayName="ball",
                         Function="100*(coordsX*coordsX+coordsY*coordsY+coordsZ*coordsZ < 144)")
start = simple.Sphere(Radius=17, ThetaResolution=24, PhiResolution=24)
surface = simple.DeformableSurface(Input=ball, InitialSurface=start)
surface.Scalars = ["POINTS", "ball"]
surface.MaxLevels = 2
ds_invariants.update_proxy(surface, [ball, start], "DeformableSurface")

table = servermanager.Fetch(surface, idx=1)
polydata = servermanager.Fetch(surface, idx=0)
ds_invariants.check_surface(servermanager.Fetch(start), polydata, "sphere onto the ball, 3 levels")
failures = []


def check(name, ok, value):
    print("%-60s %s" % (name, "ok" if ok else "FAILED (%s)" % (value,)))
    if not ok:
        failures.append(name)


columns = [table.GetColumnName(i) for i in range(table.GetNumberOfColumns())]
check("table columns", columns == ["Sweep", "Level", "Sigma", "Vertices", "Triangles",
                                   "MeanCorrection", "MaxCorrection"], columns)
rows = table.GetNumberOfRows()
sweeps = polydata.GetFieldData().GetArray("Sweeps").GetValue(0)
check("one row per sweep", rows == sweeps and rows > 10, (rows, sweeps))
level = vtk_to_numpy(table.GetColumnByName("Level"))
mean = vtk_to_numpy(table.GetColumnByName("MeanCorrection"))
check("levels 0, 1, 2 in order", list(sorted(set(level))) == [0, 1, 2] and (level[1:] >= level[:-1]).all(),
      sorted(set(level)))
for lv in (0, 1, 2):
    m = mean[level == lv]
    check("level %d: correction at its end < 1/2 of its maximum" % lv, len(m) > 1 and m[-1] < 0.5 * m.max(),
          (m.max() if len(m) else None, m[-1] if len(m) else None))

chart = simple.CreateView("XYChartView")
chart.ViewSize = [600, 400]
shown = simple.Show(simple.OutputPort(surface, 1), chart)
shown.UseIndexForXAxis = 0
shown.XArrayName = "Sweep"
shown.SeriesVisibility = ["MeanCorrection"]
chart.LeftAxisLogScale = 1
simple.Render(chart)
png = os.path.join(out_dir, "convergence_chart.png")
simple.SaveScreenshot(png, chart, ImageResolution=[600, 400])

reader = vtkPNGReader()
reader.SetFileName(png)
reader.Update()
rgb = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).astype(int)
r, g, b = rgb[:, 0], rgb[:, 1], rgb[:, 2]
series = int(((b > 120) & (b > r + 60)).sum())  # ParaView's first series colour is blue
check("the chart draws the series (blue pixels >= 800)", series >= 800, series)

if failures:
    sys.exit("FAILED: " + "; ".join(failures))
print("all checks passed")
