# SPDX-License-Identifier: BSD-3-Clause
"""Helpers for the GUI tests with played events (gui_X.py + gui_X.xml + X_gui_check.py, see
CMakeLists.txt).

In the client (gui_X.py): top_view() points the render view straight down at the z plane of
`focal` with a parallel projection and returns the world point under each fraction of the view
the XML moves the mouse to; write_phantom() writes a phantom image for the client to open;
write_setup() hands what the check needs over in DS_TEST_OUTPUT/gui_X.json (or the script's
error).

In pvpython (X_gui_check.py): Check collects the verdicts; load_state() reads the JSON, loads the
state the client saved and returns the JSON's content.

In both: compare_view() saves a view at a fixed size and compares it with a baseline image in
Testing/Baseline."""
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


# vtkImageDifference's settings, as pvbatch_delaunay_seed_image.py measured them: a pixel may match
# within 2 pixels (AllowShift), no averaging, a per-pixel threshold of 20 (|dR|+|dG|+|dB|; VTK's 105
# passed a 3.4 degree turn of the camera), a thresholded error of at most 10 (VTK's tests' value).
PIXEL_THRESHOLD = 20
TOLERANCE = 10.0


def compare_view(view, name, size):
    """Saves `view` at `size` (pixels) as DS_TEST_OUTPUT/<name> and compares it with
    DS_BASELINE_DIR/<name>; returns (ok, what was found). A missing baseline is written there and
    fails: look at it, then git add it. On a mismatch the difference image is left beside the
    saved one (<name>.diff.png)."""
    import shutil
    from paraview import simple
    from vtkmodules.vtkImagingCore import vtkImageDifference
    from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

    image = os.path.join(OUT_DIR, name)
    baseline = os.path.join(os.environ["DS_BASELINE_DIR"], name)
    simple.SaveScreenshot(image, view, ImageResolution=size, TransparentBackground=0)
    if not os.path.exists(baseline):
        shutil.copyfile(image, baseline)
        return False, "no baseline: wrote %s; look at it and git add it" % baseline
    readers = []
    for path in (image, baseline):
        readers.append(vtkPNGReader())
        readers[-1].SetFileName(path)
        readers[-1].Update()
    if readers[0].GetOutput().GetDimensions() != readers[1].GetOutput().GetDimensions():
        return False, "the view is %s pixels, the baseline %s %s" % (
            readers[0].GetOutput().GetDimensions(), baseline, readers[1].GetOutput().GetDimensions())
    diff = vtkImageDifference()
    diff.SetInputConnection(readers[0].GetOutputPort())
    diff.SetImageConnection(readers[1].GetOutputPort())
    diff.SetThreshold(PIXEL_THRESHOLD)
    diff.SetAllowShift(True)
    diff.SetAveraging(False)
    diff.Update()
    error = diff.GetThresholdedError()
    if error > TOLERANCE:
        writer = vtkPNGWriter()
        writer.SetFileName(image[:-4] + ".diff.png")
        writer.SetInputConnection(diff.GetOutputPort())
        writer.Write()
    return error <= TOLERANCE, "the view %s the baseline %s (thresholded error %.2f, at most %.0f)" % (
        "matches" if error <= TOLERANCE else "differs from", baseline, error, TOLERANCE)


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
        # os._exit, not sys.exit: pvpython 5.11 dies of an X error (GLXBadContext) in its
        # teardown after a SystemExit in a script that rendered (a baseline image).
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(1 if self.failures else 0)


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
