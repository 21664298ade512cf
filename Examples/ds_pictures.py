# SPDX-License-Identifier: BSD-3-Clause
"""The demo's pictures (pvpython / pvbatch): a slice of the head with the traces of the
surfaces beside the surface in 3-D coloured by its distance to the brain-mask boundary
(ds_scoring.measure adds that distance as the point array DistanceToMask)."""
from paraview import simple

import ds_scoring


def _caption(view, text, location="Upper Left Corner"):
    label = simple.Text(Text=text)
    display = simple.Show(label, view)
    display.WindowLocation = location
    display.FontSize = 11
    display.Justification = "Left"
    display.Color = [0.9, 0.9, 0.9]


def _centre(proxy):
    """The centre of a source's bounds (the NIfTI reader places images where their file says:
    Colin27 in MNI coordinates), so pictures are set up relative to the head."""
    proxy.UpdatePipeline()
    b = proxy.GetDataInformation().GetBounds()
    return [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]


def _at(c, dx, dy, dz):
    return [c[0] + dx, c[1] + dy, c[2] + dz]


def _distance_mesh(producer, view, limit, title, c):
    """The surface in 3-D in `view`, with edges, coloured by DistanceToMask in [-limit, limit]
    with a horizontal colour bar, seen from the left front above the brain."""
    mesh = simple.Show(producer, view)
    mesh.SetRepresentationType("Surface With Edges")
    mesh.EdgeColor = [0.25, 0.25, 0.3]
    simple.ColorBy(mesh, ("POINTS", "DistanceToMask"))
    lut = simple.GetColorTransferFunction("DistanceToMask")
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(-limit, limit)
    mesh.SetScalarBarVisibility(view, True)
    bar = simple.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.RangeLabelFormat = "%.0f"
    bar.Orientation = "Horizontal"
    bar.WindowLocation = "Lower Center"
    bar.ScalarBarLength = 0.5
    bar.TitleFontSize = bar.LabelFontSize = 12
    view.CameraFocalPoint = _at(c, 0.0, 0.0, -10.0)
    view.CameraPosition = _at(c, -420.0, -258.0, 170.0)
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 24
    view.ResetCamera(False)
    view.CameraPosition = [f + 0.85 * (p - f) for p, f in zip(view.CameraPosition, view.CameraFocalPoint)]


def _two_views(name):
    """A layout of two render views side by side, dark, without orientation axes."""
    layout = simple.CreateLayout(name)
    left = simple.CreateView("RenderView")
    right = simple.CreateView("RenderView")
    simple.AssignViewToLayout(view=left, layout=layout, hint=0)
    simple.AssignViewToLayout(view=right, layout=layout, hint=0)
    for view in (left, right):
        view.OrientationAxesVisibility = 0
        view.UseColorPaletteForBackground = 0
        view.Background = [0.06, 0.06, 0.08]
    return layout, left, right


def _grey_slice(image, origin, normal, view, top):
    """The image's plane through origin, its own greys (0..top), unlit."""
    cut = simple.Slice(Input=image)
    cut.SliceType = "Plane"
    cut.SliceType.Origin, cut.SliceType.Normal = origin, normal
    shown = simple.Show(cut, view)
    simple.ColorBy(shown, ("POINTS", "NIFTI"))
    grey = simple.GetColorTransferFunction("NIFTI")
    grey.ApplyPreset("Grayscale", True)
    grey.RescaleTransferFunction(0.0, top)
    shown.SetScalarBarVisibility(view, False)
    shown.Ambient, shown.Diffuse = 1.0, 0.0


def _trace(surface, origin, normal, view, colour):
    """Where the surface cuts the plane: a thick line, one unit in front of the slice."""
    trace = simple.Slice(Input=surface)
    trace.SliceType = "Plane"
    trace.SliceType.Origin, trace.SliceType.Normal = origin, normal
    line = simple.Show(trace, view)
    line.ColorArrayName = ["POINTS", ""]
    line.AmbientColor = line.DiffuseColor = colour
    line.Ambient, line.Diffuse = 1.0, 0.0
    line.LineWidth = 3.0
    line.Position = [-n for n in normal]


def render(result, png, size=(1600, 800), metrics=None):
    """Left: a sagittal slice of the full head T1 (ch2.nii.gz) with the line where the
    surface cuts it. Right: the surface mesh coloured by its distance to the mask boundary."""
    head = simple.OpenDataFile(ds_scoring.HEAD)  # the plugin's NIfTI reader
    surface = simple.TrivialProducer(registrationName="brain surface")
    surface.GetClientSideObject().SetOutput(result["annotated"])
    surface.UpdatePipeline()
    layout, left, right = _two_views("brain")

    # Left: a parasagittal plane through the left hemisphere, the surface's trace on it.
    c = _centre(head)
    x = c[0] - 20.0
    _grey_slice(head, [x, c[1], c[2]], [1.0, 0.0, 0.0], left, 130.0)
    _trace(surface, [x, c[1], c[2]], [1.0, 0.0, 0.0], left, [1.0, 0.55, 0.1])
    left.CameraFocalPoint = [x, c[1], c[2]]
    left.CameraPosition = _at(c, -490.0, 0.0, 0.0)
    left.CameraViewUp = [0.0, 0.0, 1.0]
    left.CameraParallelProjection = 1
    left.ResetCamera(False)
    left.CameraParallelScale = 116.0

    # Right: the mesh in 3-D, coloured by the signed distance to the mask boundary.
    _distance_mesh(surface, right, 2.0, "distance to the mask boundary (mm)", c)
    # Lift the brain clear of the colour bar.
    right.CameraPosition = [right.CameraPosition[0], right.CameraPosition[1], right.CameraPosition[2] - 14.0]
    right.CameraFocalPoint = [right.CameraFocalPoint[0], right.CameraFocalPoint[1],
                              right.CameraFocalPoint[2] - 14.0]

    _caption(left, "Colin27 T1 head (ch2.nii.gz), sagittal slice x = %g mm (MNI)\n"
                   "orange: where the deformable surface cuts it" % x)
    if metrics:
        _caption(right, "from the box around the volume: %.1f s, %d levels\n"
                        "%d vertices, one closed surface, %d self-intersections\n"
                        "vertex to mask boundary: mean %.2f mm, 95%% %.2f mm"
                 % (metrics["seconds"], metrics["levels"], metrics["vertices"],
                    metrics["self_intersections"], metrics["dist_mean"], metrics["dist_p95"]))
    simple.SaveScreenshot(png, layout, ImageResolution=list(size))
    return png


def render_head(picks, click, png, metrics, size=(1600, 800)):
    """Left: a coronal slice of the head with the traces of both surfaces (orange: from the
    picked points, which are drawn where they lie near the slice; cyan: from one click). Right:
    the surface from the picks in 3-D, coloured by its distance to the mask boundary."""
    annotated = simple.TrivialProducer(registrationName="surface from the picks")
    annotated.GetClientSideObject().SetOutput(picks["annotated"])
    annotated.UpdatePipeline()
    layout, left, right = _two_views("head")

    c = _centre(picks["image_proxy"])
    y = c[1] + 2.0  # the coronal slice the user picked on
    plane = ([c[0], y, c[2]], [0.0, 1.0, 0.0])
    _grey_slice(picks["image_proxy"], plane[0], plane[1], left, 140.0)
    for result, colour in ((picks, [1.0, 0.55, 0.1]), (click, [0.2, 0.85, 1.0])):
        _trace(result["surface"], plane[0], plane[1], left, colour)
    near = simple.Clip(Input=picks["points"], ClipType="Plane", Invert=0, Crinkleclip=0)
    near.ClipType.Origin, near.ClipType.Normal = [c[0], y - 1.0, c[2]], [0.0, 1.0, 0.0]
    near = simple.Clip(Input=near, ClipType="Plane", Invert=1)
    near.ClipType.Origin, near.ClipType.Normal = [c[0], y + 1.0, c[2]], [0.0, 1.0, 0.0]
    dots = simple.Show(near, left)
    dots.SetRepresentationType("Points")
    dots.PointSize = 9.0
    dots.RenderPointsAsSpheres = 1
    dots.ColorArrayName = ["POINTS", ""]
    dots.AmbientColor = dots.DiffuseColor = [1.0, 0.2, 0.2]
    dots.Position = [0.0, -2.0, 0.0]
    left.CameraFocalPoint = [c[0], y, c[2]]
    left.CameraPosition = _at(c, 0.0, -508.0, 0.0)
    left.CameraViewUp = [0.0, 0.0, 1.0]
    left.CameraParallelProjection = 1
    left.ResetCamera(False)
    left.CameraParallelScale = 100.0

    _distance_mesh(annotated, right, 3.0, "distance to the brain-mask boundary (mm)", c)

    mp, mc = metrics["picks"], metrics["click"]
    _caption(left, "Colin27 whole head (ch2.nii.gz), coronal slice y = %g mm (MNI)\n"
                   "red: picked points near this slice\n"
                   "orange: surface from %d picked points (mean %.2f mm from the brain)\n"
                   "cyan: surface from one click (mean %.2f mm)"
             % (y, picks["points"].GetDataInformation().GetNumberOfPoints(), mp["dist_mean"],
                mc["dist_mean"]))
    _caption(right, "from the picked points: %.1f s, %d vertices, one closed surface,\n"
                    "%d self-intersections; 95%% of vertices within %.1f mm of the brain"
             % (mp["seconds"], mp["vertices"], mp["self_intersections"], mp["dist_p95"]))
    simple.SaveScreenshot(png, layout, ImageResolution=list(size))
    return png
