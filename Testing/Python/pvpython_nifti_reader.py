"""ParaView 5.11 has no reader for gzipped NIfTI; the plugin adds one (vtkNIFTIImageReader)
so MRI volumes open with OpenDataFile / File > Open. A volume written here round-trips
exactly, and the Colin27 template of the demo opens with its known size and range."""
import os
import sys

from paraview.simple import LoadPlugin, OpenDataFile, servermanager
from vtkmodules.vtkImagingCore import vtkImageCast, vtkRTAnalyticSource
from vtkmodules.vtkIOImage import vtkNIFTIImageWriter
from vtkmodules.util.numpy_support import vtk_to_numpy

LoadPlugin(os.environ["DS_PLUGIN"], ns=globals())
out_dir = os.environ.get("DS_TEST_OUTPUT", ".")
os.makedirs(out_dir, exist_ok=True)

# Round trip: a small int16 volume with spacing and origin.
source = vtkRTAnalyticSource()
source.SetWholeExtent(0, 20, 0, 15, 0, 10)
cast = vtkImageCast()
cast.SetInputConnection(source.GetOutputPort())
cast.SetOutputScalarTypeToShort()
cast.Update()
written = cast.GetOutput()
written.SetSpacing(0.5, 0.75, 1.5)
path = os.path.join(out_dir, "roundtrip.nii.gz")
writer = vtkNIFTIImageWriter()
writer.SetInputData(written)
writer.SetFileName(path)
writer.Write()

reader = OpenDataFile(path)
if reader is None or reader.GetXMLName() != "DSNIfTIImageReader":
    sys.exit("OpenDataFile did not pick the plugin's NIfTI reader for .nii.gz")
image = servermanager.Fetch(reader)
dims = image.GetDimensions()
spacing = image.GetSpacing()
a = vtk_to_numpy(written.GetPointData().GetScalars())
b = vtk_to_numpy(image.GetPointData().GetScalars())
print("round trip: dims", dims, "spacing", spacing, "max |diff|", abs(a.astype(int) - b.astype(int)).max())
assert dims == (21, 16, 11), dims
assert all(abs(s - t) < 1e-6 for s, t in zip(spacing, (0.5, 0.75, 1.5))), spacing
assert (a == b).all(), "voxel values differ after the round trip"

# The real volume of the demo (installed by scripts/install-deps.sh: mricron-data).
colin = "/usr/share/mricron/templates/ch2bet.nii.gz"
if not os.path.exists(colin):
    sys.exit("%s is missing: the test command installs mricron-data, so the setup is broken" % colin)
reader = OpenDataFile(colin)
reader.UpdatePipeline()
info = reader.GetDataInformation()
rng = reader.PointData.GetArray(0).GetRange()
print("Colin27 (brain):", info.GetExtent(), rng)
assert tuple(info.GetExtent()) == (0, 180, 0, 216, 0, 180), info.GetExtent()
assert rng == (0.0, 133.0), rng
