# SPDX-License-Identifier: BSD-3-Clause
"""The real ParaView GUI client, tested: run as
    PV_PLUGIN_PATH=<plugin dir> paraview --dr --script=gui_one_click.py --exit   (under Xvfb) The client loads the plugin at startup from PV_PLUGIN_PATH (as a user's ParaView does); inside
the GUI's own Python the script builds the README's
one-click workflow as a user does: the whole Colin27 head (the plugin's NIfTI reader), a Slice,
the clicked point (CSV Reader -> Table To Points), Delaunay Seed Surface (a seed sphere),
Deformable Surface (IntensityRange 62 130, no weight typed: a click given its range pulls with
RegionWeight 1), the surface's trace on the slice.
Checks: the proxies exist in the GUI's session and the surface is one closed piece around the
click of the expected size; the render view matches Testing/Baseline/gui_one_click.png
(ds_gui.compare_view: vtkImageDifference, AllowShift, per-pixel threshold 20, thresholded
error <= 10, as pvbatch_delaunay_seed_image.py explains). The GUI exits with 0 whatever the script does, so the
verdict goes to DS_TEST_OUTPUT/gui_one_click.result ("PASSED" or "FAILED: ..."), which the ctest
command reads. A missing baseline is written and the test fails: look at it, then git add it."""
import os
import traceback

out_dir = os.environ.get("DS_TEST_OUTPUT", "/tmp")
result_file = os.path.join(out_dir, "gui_one_click.result")


def main():
    from paraview import servermanager
    from paraview.simple import (CSVReader, GetActiveViewOrCreate, Glyph, GetColorTransferFunction, LoadPlugin,
                                 OpenDataFile, Render, SetActiveSource, Show, Slice,
                                 TableToPoints)

    # The GUI runs the script without __file__: the source tree comes from DS_BASELINE_DIR.
    baseline_dir = os.environ["DS_BASELINE_DIR"]
    examples = os.path.join(baseline_dir, "..", "..", "Examples")
    # The client loaded the plugin at startup from PV_PLUGIN_PATH, as a user's ParaView does;
    # its proxies are then in paraview.simple. (LoadPlugin only if it did not.)
    from paraview import simple
    loaded_at_startup = hasattr(simple, "DeformableSurface")
    namespace = vars(simple)
    if not loaded_at_startup:
        LoadPlugin(os.environ["DS_PLUGIN"], remote=False, ns=globals())
        namespace = globals()
    head = OpenDataFile("/usr/share/mricron/templates/ch2.nii.gz")
    if head is None:
        return "FAILED: the plugin's NIfTI reader did not open ch2.nii.gz (mricron-data missing?)"
    view = GetActiveViewOrCreate("RenderView")
    head.UpdatePipeline()
    b = head.GetDataInformation().GetBounds()  # MNI coordinates: the reader applies the sform
    c = [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]
    plane = dict(Origin=[c[0], c[1] + 2.0, c[2]], Normal=[0.0, 1.0, 0.0])
    cut = Slice(registrationName="Slice", Input=head)
    cut.SliceType = "Plane"
    cut.SliceType.Origin, cut.SliceType.Normal = plane["Origin"], plane["Normal"]
    shown = Show(cut, view)
    shown.ColorArrayName = ["POINTS", "NIFTI"]
    grey = GetColorTransferFunction("NIFTI")
    grey.ApplyPreset("Grayscale", True)
    grey.RescaleTransferFunction(0.0, 140.0)
    shown.LookupTable = grey
    shown.Ambient, shown.Diffuse = 1.0, 0.0
    table = CSVReader(registrationName="clicked point", FileName=[os.path.join(examples, "colin27_click.csv")])
    points = TableToPoints(registrationName="TableToPoints", Input=table, XColumn="x", YColumn="y", ZColumn="z")
    seed = namespace["DelaunaySeedSurface"](registrationName="DelaunaySeedSurface", Input=points)
    surface = namespace["DeformableSurface"](registrationName="DeformableSurface", Input=head, InitialSurface=seed)
    surface.Scalars = ["POINTS", "NIFTI"]
    surface.IntensityRange = [62.0, 130.0]
    trace = Slice(registrationName="trace", Input=surface)
    trace.SliceType = "Plane"
    trace.SliceType.Origin, trace.SliceType.Normal = plane["Origin"], plane["Normal"]
    line = Show(trace, view)
    line.ColorArrayName = ["POINTS", ""]
    line.AmbientColor = line.DiffuseColor = [0.2, 0.85, 1.0]
    line.Ambient, line.Diffuse = 1.0, 0.0
    line.LineWidth = 3.0
    line.Position = [0.0, -1.0, 0.0]
    # The click as a small sphere of triangles (Glyph), not points rendered as spheres: the
    # latter is a shader whose output differs between hosts (no dot at all on some), which the
    # baseline comparison would take for a change of the surface.
    marker = Glyph(registrationName="click marker", Input=points, GlyphType="Sphere")
    marker.ScaleArray = ["POINTS", "No scale array"]
    marker.ScaleFactor = 4.0
    marker.GlyphMode = "All Points"
    dot = Show(marker, view)
    dot.ColorArrayName = ["POINTS", ""]
    dot.AmbientColor = dot.DiffuseColor = [1.0, 0.2, 0.2]
    dot.Position = [0.0, -2.0, 0.0]
    view.OrientationAxesVisibility = 0
    view.CameraPosition = [c[0], c[1] - 558.0, c[2]]
    view.CameraFocalPoint, view.CameraViewUp = plane["Origin"], [0, 0, 1]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 95.0
    SetActiveSource(surface)
    Render(view)

    data = servermanager.Fetch(surface, arg1=0)
    problems = []
    # The invariants every surface keeps (ds_invariants.py, beside this script).
    import sys
    sys.path.insert(0, os.path.join(baseline_dir, "..", "Python"))
    import ds_gui
    import ds_invariants
    try:
        ds_invariants.check_surface(servermanager.Fetch(seed), data, "one click grown")
    except AssertionError as error:
        problems.append(str(error))
    # 18 223 points at the defaults (docs/RESULTS.md; no split below the level's sigma with the region
    # force, below 2 sigma once it has faded: 31 364 before); the bounds catch a surface that did
    # not grow or that kept subdividing.
    if not (5000 <= data.GetNumberOfPoints() <= 25000):
        problems.append("surface of %d points" % data.GetNumberOfPoints())
    bounds = data.GetBounds()
    if not (bounds[1] - bounds[0] > 120 and bounds[5] - bounds[4] > 100 and bounds[0] < -50):
        problems.append("the click did not grow to the brain: bounds %s" % (bounds,))
    selfx = data.GetFieldData().GetArray("SelfIntersections")
    if selfx is None or selfx.GetTuple1(0) != 0:
        problems.append("self-intersections")
    weight = data.GetFieldData().GetArray("RegionWeight")
    if weight is None or weight.GetTuple1(0) != 1.0:
        problems.append("the click given its range did not pull with RegionWeight 1")

    matches, found = ds_gui.compare_view(view, "gui_one_click.png", [500, 500])
    if not matches:
        problems.append(found)
    if not loaded_at_startup:
        problems.append("the client did not load the plugin from PV_PLUGIN_PATH at startup")
    if problems:
        return "FAILED: " + "; ".join(problems)
    return "PASSED: %d points, bounds %s" % (data.GetNumberOfPoints(), tuple(round(b) for b in bounds))


try:
    verdict = main()
except Exception:
    verdict = "FAILED: " + traceback.format_exc()
with open(result_file, "w") as f:
    f.write(verdict + "\n")
