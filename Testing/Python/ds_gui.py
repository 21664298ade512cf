# SPDX-License-Identifier: BSD-3-Clause
"""Helpers for the GUI tests with played events (gui_X.py + gui_X.xml + X_gui_check.py, see
CMakeLists.txt).

In the client (gui_X.py): top_view() points the render view straight down at the z plane of
`focal` with a parallel projection and returns the world point under each fraction of the view
the XML moves the mouse to; write_phantom() writes a phantom image for the client to open;
write_setup() hands what the check needs over in DS_TEST_OUTPUT/gui_X.json (or the script's
error).

In pvpython (X_gui_check.py): Check collects the verdicts; load_state() reads the JSON, loads the
state the client saved and returns the JSON's content."""
import json
import os
import sys

OUT_DIR = os.environ.get("DS_TEST_OUTPUT", "/tmp")


def top_view(view, focal, scale, fractions):
    """Parallel projection looking down -z at `focal`, `scale` mm from the view's centre to its
    top edge; returns the world points at `fractions` (x from the left, y from the top) on the
    plane z = focal[2]."""
    from paraview import simple
    simple.Render(view)  # the first Render resets the camera: before the camera is set
    width, height = view.ViewSize
    view.OrientationAxesVisibility = 0
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = focal
    view.CameraPosition = [focal[0], focal[1], focal[2] + 200.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelScale = scale
    mm_per_pixel = 2.0 * scale / height
    return [[focal[0] + (fx - 0.5) * width * mm_per_pixel,
             focal[1] + (0.5 - fy) * height * mm_per_pixel, focal[2]] for fx, fy in fractions]


def write_phantom(value, origin, path):
    """Writes the numpy array `value` (indexed z, y, x; 1 mm voxels from `origin`) as the point
    array "density" of an XML image at `path`."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

    image = vtkImageData()
    image.SetDimensions(*value.shape[::-1])
    image.SetOrigin(*origin)
    array = numpy_to_vtk(value.ravel().astype(np.float32), deep=1)
    array.SetName("density")
    image.GetPointData().SetScalars(array)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.SetDataModeToBinary()
    writer.Write()


def write_setup(name, build):
    """Runs build() (the scene; returns a dict for the check) and writes its result, or the
    traceback, to DS_TEST_OUTPUT/<name>.json: the client exits 0 whatever the script does."""
    import traceback
    try:
        setup = build()
    except Exception:
        setup = {"error": traceback.format_exc()}
    with open(os.path.join(OUT_DIR, name + ".json"), "w") as f:
        json.dump(setup, f)


class Check:
    """Prints each verdict; exit() ends the check with 1 if any failed."""

    def __init__(self):
        self.failures = []

    def __call__(self, ok, what):
        print(("ok      " if ok else "FAILED  ") + what)
        if not ok:
            self.failures.append(what)
        return ok

    def exit(self):
        for f in self.failures:
            print("FAILED:", f)
        sys.exit(1 if self.failures else 0)


def load_state(name, check):
    """Loads the plugin and the state the client saved as <name>.pvsm; returns the setup the
    client's script wrote (exits when the script failed or no state was saved)."""
    from paraview import simple
    simple.LoadPlugin(os.environ["DS_PLUGIN"])
    with open(os.path.join(OUT_DIR, name + ".json")) as f:
        setup = json.load(f)
    if "error" in setup:
        sys.exit("FAILED: the GUI script: " + setup["error"])
    state = os.path.join(OUT_DIR, name + ".pvsm")
    if not check(os.path.exists(state), "the client saved its state (%s)" % state):
        check.exit()
    simple.LoadState(state)
    return setup
