"""The main job of the README: a real MRI volume through the plugin, written out
with a picture. Run with pvbatch (under xvfb-run when there is no display):

    xvfb-run -a pvbatch Examples/demo.py --plugin <DeformableSurface.so> --output out/

Volume: the Colin27 T1 brain template from Debian's mricron-data package.
"""
import argparse
import os
import sys
import time

from paraview.simple import (LoadPlugin, OpenDataFile, SaveData, Slice, Show, ColorBy,
                             GetActiveViewOrCreate, SaveScreenshot, ResetCamera,
                             GetColorTransferFunction)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--plugin", required=True, help="path of DeformableSurface.so")
parser.add_argument("--output", default="out", help="output folder")
parser.add_argument("--volume", default="/usr/share/mricron/templates/ch2.nii.gz")
args = parser.parse_args()

if not os.path.exists(args.volume):
    sys.exit("demo: %s is missing (apt-get install mricron-data)" % args.volume)
os.makedirs(args.output, exist_ok=True)
LoadPlugin(args.plugin, ns=globals())

volume = OpenDataFile(args.volume)
t0 = time.time()
gradient = ScaleSpaceGradient(Input=volume)  # noqa: F821 (defined by LoadPlugin)
gradient.SigmaFraction = 1.0 / 48.0
gradient.UpdatePipeline()
print("scale-space gradient of %s: %.2f s" % (os.path.basename(args.volume), time.time() - t0))

vti = os.path.join(args.output, "colin27_force.vti")
SaveData(vti, proxy=gradient)

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [900, 900]
view.OrientationAxesVisibility = 0
cut = Slice(Input=gradient)
cut.SliceType = "Plane"
cut.SliceType.Origin = [90, 108, 90]
cut.SliceType.Normal = [0, 0, 1]
display = Show(cut, view)
ColorBy(display, ("POINTS", "Force", "Magnitude"))
display.RescaleTransferFunctionToDataRange(True, False)
GetColorTransferFunction("Force").ApplyPreset("Inferno (matplotlib)", True)
view.CameraPosition = [90, 108, 500]
view.CameraFocalPoint = [90, 108, 90]
view.CameraViewUp = [0, 1, 0]
ResetCamera(view)
png = os.path.join(args.output, "colin27_force.png")
SaveScreenshot(png, view, ImageResolution=[900, 900])
print("wrote", vti)
print("wrote", png)
