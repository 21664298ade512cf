# SPDX-License-Identifier: BSD-3-Clause
from paraview.simple import *  # noqa: F401,F403
import os
# The README's one-click workflow in the GUI, for its picture: run with
#   scripts/gui_screenshot.sh out.png
# (paraview --script=Examples/gui_one_click.py under Xvfb, then a picture of the whole window).
root = os.environ.get("DS_SOURCE_DIR", os.getcwd())
LoadPlugin(os.environ.get("DS_PLUGIN", os.path.join(root, "build/lib/paraview-5.11/plugins/DeformableSurface/DeformableSurface.so")),
           remote=False, ns=globals())
head = OpenDataFile("/usr/share/mricron/templates/ch2.nii.gz")
head.UpdatePipeline()
b = head.GetDataInformation().GetBounds()  # MNI coordinates: the reader applies the sform
c = [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]
view = GetActiveViewOrCreate("RenderView")
sl = Slice(registrationName="Slice", Input=head)
sl.SliceType = "Plane"
sl.SliceType.Origin = [c[0], c[1] + 2, c[2]]
sl.SliceType.Normal = [0, 1, 0]
d = Show(sl, view)
ColorBy(d, ("POINTS", "NIFTI"))
lut = GetColorTransferFunction("NIFTI"); lut.ApplyPreset("Grayscale", True); lut.RescaleTransferFunction(0, 140)
d.SetScalarBarVisibility(view, False)
table = CSVReader(registrationName="clicked point", FileName=[os.path.join(root, "Examples", "colin27_click.csv")])
pts = TableToPoints(registrationName="TableToPoints", Input=table, XColumn="x", YColumn="y", ZColumn="z")
# The click as a small sphere of triangles (points rendered as spheres draw nothing on some hosts).
marker = Glyph(registrationName="click marker", Input=pts, GlyphType="Sphere")
marker.ScaleArray = ["POINTS", "No scale array"]; marker.ScaleFactor = 4.0; marker.GlyphMode = "All Points"
pd = Show(marker, view); pd.ColorArrayName = ["POINTS", ""]; pd.AmbientColor = pd.DiffuseColor = [1, 0.2, 0.2]
seed = DelaunaySeedSurface(registrationName="DelaunaySeedSurface", Input=pts)
sd = Show(seed, view); sd.SetRepresentationType("Wireframe"); sd.AmbientColor = sd.DiffuseColor = [1, 1, 0.3]
ds = DeformableSurface(registrationName="DeformableSurface", Input=head, InitialSurface=seed)
ds.Scalars = ["POINTS", "NIFTI"]
ds.IntensityRange = [62, 130]
trace = Slice(registrationName="trace", Input=ds)
trace.SliceType = "Plane"
trace.SliceType.Origin = [c[0], c[1] + 2, c[2]]
trace.SliceType.Normal = [0, 1, 0]
td = Show(trace, view); td.ColorArrayName = ["POINTS", ""]; td.AmbientColor = td.DiffuseColor = [0.3, 0.85, 1.0]
td.LineWidth = 3; td.Ambient, td.Diffuse = 1.0, 0.0; td.Position = [0, -1, 0]
pd.Position = [0, -2, 0]
view.OrientationAxesVisibility = 0
view.CameraPosition = [c[0], c[1] - 558, c[2]]; view.CameraFocalPoint = [c[0], c[1] + 2, c[2]]; view.CameraViewUp = [0, 0, 1]
view.CameraParallelProjection = 1
view.ResetCamera(False)
view.CameraParallelScale = 95
SetActiveSource(ds)
Render()
