# SPDX-License-Identifier: BSD-3-Clause
# The pictures of docs/GUI.md: the README's picked-points workflow in the ParaView GUI on the
# Colin27 head, one picture per step. Run by scripts/gui_pictures.sh (through
# scripts/gui_screenshot.sh: the paraview client with both plugins, a picture of the whole
# window); DS_GUI_STEP says how far this run goes, and the source of that step is left active so
# its panel shows:
#   1  Seed Points holding the picks of Examples/colin27_picks.csv (as P over the slices puts them)
#   2  Delaunay Seed Surface: its Tetrahedra cut by the slice, coloured by Removed
#   3  Deformable Surface with Preview Region on: what the region force will grow through
#   4  Deformable Surface solved: the trace of the surface on the slice
import csv
import os

from paraview.simple import *  # noqa: F401,F403 (the plugins were loaded at startup)

root = os.environ.get("DS_SOURCE_DIR", os.getcwd())
step = int(os.environ.get("DS_GUI_STEP", "4"))
SLICE_Y = -15.0  # a coronal slice with eight of the picks


def trace(source, name, colour, width=3.0):
    """The cut of `source` by the slice, drawn as lines just in front of it."""
    cut = Slice(registrationName=name, Input=source)
    cut.SliceType = "Plane"
    cut.SliceType.Origin, cut.SliceType.Normal = [0.0, SLICE_Y, 0.0], [0.0, 1.0, 0.0]
    shown = Show(cut, view)
    shown.ColorArrayName = ["POINTS", ""]
    shown.AmbientColor = shown.DiffuseColor = colour
    shown.Ambient, shown.Diffuse = 1.0, 0.0
    shown.LineWidth = width
    shown.Position = [0.0, -1.0, 0.0]
    return shown


view = GetActiveViewOrCreate("RenderView")
head = OpenDataFile("/usr/share/mricron/templates/ch2.nii.gz")
head.UpdatePipeline()
cut = Slice(registrationName="Slice", Input=head)
cut.SliceType = "Plane"
cut.SliceType.Origin, cut.SliceType.Normal = [0.0, SLICE_Y, 0.0], [0.0, 1.0, 0.0]
grey = Show(cut, view)
ColorBy(grey, ("POINTS", "NIFTI"))
lut = GetColorTransferFunction("NIFTI")
lut.ApplyPreset("Grayscale", True)
lut.RescaleTransferFunction(0.0, 140.0)
grey.SetScalarBarVisibility(view, False)

with open(os.path.join(root, "Examples", "colin27_picks.csv")) as f:
    picks = [float(row[k]) for row in csv.DictReader(f) for k in ("x", "y", "z")]
seeds = SeedPoints(registrationName="SeedPoints", Points=picks)
# The picks on this slice as red rings: spheres around every pick, cut by the slice.
marker = Glyph(registrationName="pick markers", Input=seeds, GlyphType="Sphere")
marker.ScaleArray = ["POINTS", "No scale array"]
marker.ScaleFactor = 4.0
marker.GlyphMode = "All Points"
trace(marker, "picks on the slice", [1.0, 0.2, 0.2])
active = seeds

if step >= 2:
    seed = DelaunaySeedSurface(registrationName="DelaunaySeedSurface", Input=seeds, Image=head)
    tetrahedra = Slice(registrationName="tetrahedra on the slice", Input=OutputPort(seed, 1))
    tetrahedra.SliceType = "Plane"
    tetrahedra.SliceType.Origin, tetrahedra.SliceType.Normal = [0.0, SLICE_Y, 0.0], [0.0, 1.0, 0.0]
    shown = Show(tetrahedra, view)
    ColorBy(shown, ("CELLS", "Removed"))
    shown.SetRepresentationType("Surface With Edges")
    shown.Opacity = 0.35 if step == 2 else 0.0
    shown.Position = [0.0, -0.5, 0.0]
    shown.SetScalarBarVisibility(view, False)
    trace(seed, "seed on the slice", [1.0, 1.0, 0.3], 2.0)
    active = seed

if step >= 3:
    surface = DeformableSurface(registrationName="DeformableSurface", Input=head, InitialSurface=seed)
    surface.Scalars = ["POINTS", "NIFTI"]
    surface.PreviewRegion = 1 if step == 3 else 0
    trace(surface, "surface on the slice", [0.3, 0.85, 1.0] if step == 4 else [1.0, 0.6, 0.1])
    active = surface

view.OrientationAxesVisibility = 0
view.CameraPosition = [0.0, SLICE_Y - 500.0, 18.0]
view.CameraFocalPoint, view.CameraViewUp = [0.0, SLICE_Y, 18.0], [0.0, 0.0, 1.0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 95.0
SetActiveSource(active)
Render(view)
