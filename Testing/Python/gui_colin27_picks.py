# SPDX-License-Identifier: BSD-3-Clause
"""The README's 44 picks replayed with the P key in the real ParaView client (ctest
Python.gui_colin27_picks; CMakeLists.txt gives the command, as for gui_seed_points.py).

This script sets the scene a user would have: the Colin27 head (the plugin's NIfTI reader), one
layout tab per slice the picks of Examples/colin27_picks.csv were made on (axial z = 19 and -26,
coronal y = -15 and -65, sagittal x = -30 and 0), each with a render view looking straight at
its Slice (parallel projection), and a Seed Points source, active. It then writes the events the
client plays (DS_TEST_OUTPUT/gui_colin27_picks.xml, read when the playing starts, after this
script): for each pick, in the CSV's order, the tab of its slice (a click in the view makes it the
active one), the mouse over the pixel nearest to the pick and P; then Apply and File > Save State.
The nearest pixel is at most half a pixel from the pick along each axis of the view.
colin27_picks_gui_check.py compares the result with the CSV route."""
import csv
import os
import sys

# The client runs the script without __file__: the helpers come from beside DS_BASELINE_DIR.
sys.path.insert(0, os.path.join(os.environ["DS_BASELINE_DIR"], "..", "Python"))
import ds_gui  # noqa: E402

EXAMPLES = os.path.join(os.environ["DS_BASELINE_DIR"], "..", "..", "Examples")
HEAD = "/usr/share/mricron/templates/ch2.nii.gz"
# The six slices (axis, coordinate) and, per axis, the view's (right, up) axes, the longer in-plane
# extent across the wide view; right x up points to the viewer, so the camera sits on the -normal
# side for z and y, on the +x side for x.
SLICES = [(2, 19.0), (2, -26.0), (1, -15.0), (1, -65.0), (0, -30.0), (0, 0.0)]
VIEW_AXES = {2: (1, 0, -1.0), 1: (0, 2, -1.0), 0: (1, 2, 1.0)}
TAB_BAR = "pqClientMainWindow/centralwidget/MultiViewWidget/CoreWidget/qt_tabwidget_tabbar"
VIEWPORT = ("pqClientMainWindow/centralwidget/MultiViewWidget/CoreWidget/qt_tabwidget_stackedwidget/"
            "MultiViewWidget%d/Container/Frame.0/CentralWidgetFrame/Viewport")


def slice_of(point):
    for k, (axis, value) in enumerate(SLICES):
        if abs(point[axis] - value) < 1e-6:
            return k
    raise RuntimeError("pick %s lies on none of the six slices" % (point,))


def show_slice(simple, head, view, axis, value, picks):
    """The slice (grey levels) in `view`, the camera straight at it and zoomed onto the picks made
    on it (5 mm around them), as a user zooms in to pick precisely; returns (focal, scale)."""
    right, up, side = VIEW_AXES[axis]
    normal = [0.0, 0.0, 0.0]
    normal[axis] = 1.0
    low = [min(p[a] for p in picks) - 5.0 for a in range(3)]
    high = [max(p[a] for p in picks) + 5.0 for a in range(3)]
    focal = [0.5 * (low[a] + high[a]) for a in range(3)]
    focal[axis] = value
    cut = simple.Slice(registrationName="slice %d" % len(simple.GetSources()), Input=head)
    cut.SliceType = "Plane"
    cut.SliceType.Origin, cut.SliceType.Normal = focal, normal
    shown = simple.Show(cut, view)
    simple.ColorBy(shown, ("POINTS", "NIFTI"))
    simple.Render(view)  # the first Render resets the camera: before the camera is set
    width, height = view.ViewSize
    scale = 0.5 * max(high[up] - low[up], (high[right] - low[right]) * height / width)
    position = list(focal)
    position[axis] += side * 500.0
    up_vector = [0.0, 0.0, 0.0]
    up_vector[up] = 1.0
    view.OrientationAxesVisibility = 0
    view.CameraParallelProjection = 1
    view.CameraFocalPoint, view.CameraPosition, view.CameraViewUp = focal, position, up_vector
    view.CameraParallelScale = scale
    simple.Render(view)
    return focal, scale


def pixel_events(point, axis, focal, scale, size, tab):
    """Mouse to the pixel nearest to `point` in the view of `tab`, then P. The player puts the
    mouse at int(fraction x size): the fraction of the pixel's centre lands on the pixel."""
    right, up, _ = VIEW_AXES[axis]
    width, height = size
    mm_per_pixel = 2.0 * scale / height
    x = round((point[right] - focal[right]) / mm_per_pixel + 0.5 * width)
    y_vtk = round((point[up] - focal[up]) / mm_per_pixel + 0.5 * height)
    y_qt = height - 1 - y_vtk
    where = "(%.6f,%.6f" % ((x + 0.5) / width, (y_qt + 0.5) / height)
    viewport = VIEWPORT % (tab + 1)
    return ['  <pqevent object="%s" command="mouseMove" arguments="%s,0,0,0)" />' % (viewport, where),
            '  <pqevent object="%s" command="keyEvent" arguments="6:80:0:p:0:1" />' % viewport,
            '  <pqevent object="%s" command="keyEvent" arguments="7:80:0:p:0:1" />' % viewport]


def scene():
    from paraview import simple
    with open(os.path.join(EXAMPLES, "colin27_picks.csv")) as f:
        picks = [[float(row[k]) for k in ("x", "y", "z")] for row in csv.DictReader(f)]
    head = simple.OpenDataFile(HEAD)
    head.UpdatePipeline()
    on_slice = [[p for p in picks if slice_of(p) == k] for k in range(len(SLICES))]
    views = [simple.GetActiveViewOrCreate("RenderView")]
    for k in range(1, len(SLICES)):
        layout = simple.CreateLayout("slice %d" % (k + 1))
        views.append(simple.CreateView("RenderView"))
        simple.AssignViewToLayout(view=views[-1], layout=layout, hint=0)
    cameras = [show_slice(simple, head, view, axis, value, slice_picks)
               for view, (axis, value), slice_picks in zip(views, SLICES, on_slice)]
    size = views[0].ViewSize
    seeds = simple.SeedPoints(registrationName="SeedPoints")
    simple.SetActiveView(views[0])
    simple.SetActiveSource(seeds)

    events, tab = [], 0
    for point in picks:
        k = slice_of(point)
        if k != tab:
            # The tab, then a click in its view: the view becomes the active one, which the
            # panel's P key follows.
            events += ['  <pqevent object="%s" command="set_tab" arguments="%d" />' % (TAB_BAR, k),
                       '  <pqevent object="%s" command="mousePress" arguments="(0.5,0.5,1,1,0)" />'
                       % (VIEWPORT % (k + 1)),
                       '  <pqevent object="%s" command="mouseRelease" arguments="(0.5,0.5,1,0,0)" />'
                       % (VIEWPORT % (k + 1))]
            tab = k
        events += pixel_events(point, SLICES[k][0], cameras[k][0], cameras[k][1], size, k)
    events += ['  <pqevent object="pqClientMainWindow/propertiesDock/propertiesPanel/Accept" '
               'command="activate" arguments="" />',
               '  <pqevent object="pqClientMainWindow/MainControlsToolbar/actionSaveState" '
               'command="activate" arguments="" />',
               '  <pqevent object="pqClientMainWindow/FileSaveServerStateDialog" command="filesSelected" '
               'arguments="$PARAVIEW_TEST_ROOT/gui_colin27_picks.pvsm" />']
    with open(os.path.join(ds_gui.OUT_DIR, "gui_colin27_picks.xml"), "w") as f:
        f.write('<?xml version="1.0" ?>\n<pqevents>\n%s\n</pqevents>\n' % "\n".join(events))
    return {"picks": picks, "mm_per_pixel": [2.0 * c[1] / size[1] for c in cameras]}


ds_gui.write_setup("gui_colin27_picks", scene)
