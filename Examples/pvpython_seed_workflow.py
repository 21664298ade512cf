# SPDX-License-Identifier: BSD-3-Clause
"""The seeding workflow of the paper (section 7) in ParaView, scripted.

  image -> slices -> boundary points picked on the slices -> Extract Selection
        -> Delaunay Seed Surface (tetrahedra removed by Alpha / by ID / by intensity)
        -> Deformable Surface (when the plugin has it)

In the GUI the picks are made with "Select Points On" in a slice view; here the picks are
emulated by an ID selection of every few points of the object's outline on three slices.

Run:
  pvpython Examples/pvpython_seed_workflow.py [--plugin DeformableSurface.so]
  xvfb-run -a pvbatch Examples/pvpython_seed_workflow.py --png seed.png
The plugin is found from --plugin, $DS_PLUGIN, or PV_PLUGIN_PATH.
"""
import argparse
import os
import sys

from paraview import servermanager
from paraview import simple


def load_plugin(path=None):
    path = path or os.environ.get("DS_PLUGIN")
    if path:
        simple.LoadPlugin(path)  # adds the proxies to paraview.simple
    elif not hasattr(simple, "DelaunaySeedSurface"):
        simple.LoadDistributedPlugin("DeformableSurface")
    if not hasattr(simple, "DelaunaySeedSurface"):
        raise RuntimeError("DeformableSurface plugin not loaded: pass --plugin or set DS_PLUGIN")


PHANTOM_INFO = """
from paraview import util
util.SetOutputWholeExtent(self, [0, 63, 0, 63, 0, 63])
"""

# A bright solid torus (R 20, r 8 voxels; values 0..100 with a soft, 1-voxel edge) in a 64^3 volume.
PHANTOM = """
import numpy as np
executive = self.GetExecutive()
info = executive.GetOutputInformation(0)
output.SetExtent([executive.UPDATE_EXTENT().Get(info, i) for i in range(6)])
z, y, x = np.mgrid[0:64, 0:64, 0:64].astype(float)
rho = np.sqrt((x - 32.0) ** 2 + (y - 32.0) ** 2)
d = np.sqrt((rho - 20.0) ** 2 + (z - 32.0) ** 2) - 8.0
output.PointData.append((100.0 / (1.0 + np.exp(d))).ravel(), "density")
output.PointData.SetActiveScalars("density")
"""


def build_pipeline(step=3):
    """Returns a dict of the proxies; 'seed' is the seed surface, 'solved' the deformed one."""
    image = simple.ProgrammableSource(OutputDataSetType="vtkImageData")
    image.ScriptRequestInformation = PHANTOM_INFO
    image.Script = PHANTOM
    edge = 50.0  # the visible boundary, where the user clicks

    # Five axial slices; on each, the object's outline (two circles: the torus is hollow in the middle).
    slices = simple.Slice(Input=image)
    slices.SliceType = "Plane"
    slices.SliceType.Origin = [32.0, 32.0, 32.0]
    slices.SliceType.Normal = [0.0, 0.0, 1.0]
    slices.SliceOffsetValues = [-6.0, -3.0, 0.0, 3.0, 6.0]
    outline = simple.Contour(Input=slices, ContourBy=["POINTS", "density"], Isosurfaces=[edge])
    outline.UpdatePipeline()
    n_outline = outline.GetDataInformation().GetNumberOfPoints()
    if n_outline < 8:
        raise RuntimeError("no object outline found on the slices")

    # "Picked" points: every step-th outline point, as the (process, index) pairs of an ID selection.
    ids = []
    for i in range(0, n_outline, step):
        ids += [0, i]
    picks = simple.IDSelectionSource(FieldType="POINT", IDs=ids)
    picked = simple.ExtractSelection(Input=outline, Selection=picks)

    # Seed: Delaunay tetrahedra of the picks fill the convex hull, hole included. The intensity
    # rule deletes the tetrahedra whose centroid is dark (the hole), so the seed gets the torus's
    # genus by itself; the lower bound sits below the edge value because the centroids of thin
    # tetrahedra between neighbouring picks lie on the edge. Subdivision gives the solver enough
    # vertices.
    seed = simple.DelaunaySeedSurface(Input=picked, Image=image)
    seed.UseIntensityRange = 1
    seed.IntensityRange = [0.5 * edge, 1.0e9]
    seed.TargetEdgeLength = 2.0
    seed.UpdatePipeline()

    # The solver starts at the seed. Scalars is named: paraview.simple first connects the
    # active source (the seed, whose SeedPointId would be the default array) before Input.
    solved = simple.DeformableSurface(Input=image, InitialSurface=simple.OutputPort(seed, 0))
    solved.Scalars = ["POINTS", "density"]
    solved.UpdatePipeline()
    return {"image": image, "slices": slices, "outline": outline, "picked": picked,
            "seed": seed, "solved": solved, "n_picked": len(ids) // 2}


def render(proxies, png, size=(900, 700)):
    view = simple.CreateRenderView()
    view.ViewSize = list(size)
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    view.OrientationAxesVisibility = 0
    slice_display = simple.Show(proxies["slices"], view)
    simple.ColorBy(slice_display, ("POINTS", "density"))
    slice_display.Opacity = 0.35
    picked_display = simple.Show(proxies["picked"], view)
    picked_display.SetRepresentationType("Points")
    picked_display.PointSize = 7
    picked_display.RenderPointsAsSpheres = 1
    picked_display.ColorArrayName = ["POINTS", ""]
    picked_display.AmbientColor = picked_display.DiffuseColor = [0.85, 0.1, 0.1]
    tets = simple.Show(simple.OutputPort(proxies["seed"], 1), view)
    tets.SetRepresentationType("Wireframe")
    simple.ColorBy(tets, ("CELLS", "Removed"))
    tets.Opacity = 0.25
    # The seed, the subject of this example (the solved surface is finer and hides the picks).
    surface = simple.Show(simple.OutputPort(proxies["seed"], 0), view)
    surface.SetRepresentationType("Surface With Edges")
    surface.ColorArrayName = ["POINTS", ""]
    surface.AmbientColor = surface.DiffuseColor = [0.95, 0.8, 0.35]
    surface.EdgeColor = [0.3, 0.25, 0.1]
    view.CameraPosition = [100.0, -60.0, 110.0]
    view.CameraFocalPoint = [32.0, 32.0, 32.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera()
    simple.Render(view)
    simple.SaveScreenshot(png, view, ImageResolution=list(size))
    print("wrote", png)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--plugin", help="path of DeformableSurface.so")
    parser.add_argument("--png", help="save a screenshot here (needs a display: xvfb-run -a pvbatch)")
    args = parser.parse_args(argv)
    load_plugin(args.plugin)
    proxies = build_pipeline()
    info = proxies["seed"].GetDataInformation()
    print("picked %d points -> seed surface with %d points, %d triangles"
          % (proxies["n_picked"], info.GetNumberOfPoints(), info.GetNumberOfCells()))
    solved = proxies["solved"].GetDataInformation()
    print("DeformableSurface from the seed: %d points, %d triangles"
          % (solved.GetNumberOfPoints(), solved.GetNumberOfCells()))
    if args.png:
        render(proxies, args.png)
    return proxies


if __name__ == "__main__":
    main(sys.argv[1:])
