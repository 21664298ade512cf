"""ParaView 5.11 has no reader for gzipped NIfTI; the plugin adds one (vtkDSNIFTIImageReader)
so MRI volumes open with OpenDataFile / File > Open. A volume written here round-trips
exactly; an oblique one (a qform turned 30 degrees about z and 10 about x, and shifted) lands
where the file says (a known voxel's world position, the direction matrix); and the Colin27
template of the demo opens with its known size, range and place (its sform: MNI coordinates)."""
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

# Oblique: a rotated, shifted qform. Voxel (i, j, k) must land at R (i, j, k) * spacing + t.
import math  # noqa: E402
from vtkmodules.vtkCommonMath import vtkMatrix4x4  # noqa: E402
from vtkmodules.vtkCommonTransforms import vtkTransform  # noqa: E402
turn = vtkTransform()
turn.PostMultiply()
turn.RotateX(10.0)
turn.RotateZ(30.0)
turn.Translate(-40.0, 12.5, 7.0)
qform = vtkMatrix4x4()
qform.DeepCopy(turn.GetMatrix())
oblique = os.path.join(out_dir, "oblique.nii.gz")
writer = vtkNIFTIImageWriter()
writer.SetInputData(written)
writer.SetQFormMatrix(qform)
writer.SetFileName(oblique)
writer.Write()
image = servermanager.Fetch(OpenDataFile(oblique))
ijk = (7, 11, 4)
placed = [0.0, 0.0, 0.0]
image.TransformIndexToPhysicalPoint(ijk, placed)
local = [ijk[a] * (0.5, 0.75, 1.5)[a] for a in range(3)]
expected = [sum(qform.GetElement(r, c) * local[c] for c in range(3)) + qform.GetElement(r, 3) for r in range(3)]
print("oblique: voxel", ijk, "at", [round(x, 4) for x in placed], "expected", [round(x, 4) for x in expected])
assert max(abs(p - e) for p, e in zip(placed, expected)) < 1e-4, (placed, expected)
direction = image.GetDirectionMatrix()
assert max(abs(direction.GetElement(r, c) - qform.GetElement(r, c)) for r in range(3) for c in range(3)) < 1e-5
assert abs(direction.Determinant() - 1.0) < 1e-6 and not math.isnan(direction.Determinant())

# Both matrices, disagreeing (as in many atlases): the sform, marked as meant, wins.
shifted = vtkMatrix4x4()
shifted.Identity()
shifted.SetElement(0, 3, 100.0)
both = os.path.join(out_dir, "both.nii.gz")
writer = vtkNIFTIImageWriter()
writer.SetInputData(written)
writer.SetQFormMatrix(qform)
writer.SetSFormMatrix(shifted)
writer.SetFileName(both)
writer.Write()
reader = OpenDataFile(both)
image = servermanager.Fetch(reader)
print("qform and sform: origin", image.GetOrigin(), "direction[0][0]", image.GetDirectionMatrix().GetElement(0, 0))
assert max(abs(o - e) for o, e in zip(image.GetOrigin(), (100.0, 0.0, 0.0))) < 1e-6, image.GetOrigin()
assert image.GetDirectionMatrix().GetElement(0, 0) == 1.0

# The same reader, a file without orientation next: axis-aligned at the origin again, not the
# previous file's rotation.
plain = os.path.join(out_dir, "plain.nii")
writer = vtkNIFTIImageWriter()
writer.SetInputData(written)
writer.SetFileName(plain)
writer.Write()
reader = OpenDataFile(oblique)
reader.UpdatePipeline()
reader.FileName = plain
image = servermanager.Fetch(reader)
d = image.GetDirectionMatrix()
print("after the oblique file, a plain one: origin", image.GetOrigin(), "direction diagonal",
      [d.GetElement(i, i) for i in range(3)])
assert all(abs(d.GetElement(i, j) - (1.0 if i == j else 0.0)) < 1e-9 for i in range(3) for j in range(3))

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
bounds = info.GetBounds()
print("Colin27 bounds (sform, MNI):", bounds)
assert max(abs(b - e) for b, e in zip(bounds, (-90, 90, -125, 91, -71, 109))) < 1e-6, bounds
