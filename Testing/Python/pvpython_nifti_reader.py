# SPDX-License-Identifier: BSD-3-Clause
"""ParaView 5.11 has no reader for gzipped NIfTI; the plugin adds one (vtkDSNIFTIImageReader)
so MRI volumes open with OpenDataFile / File > Open. A volume written here round-trips
exactly; an oblique one (a qform turned 30 degrees about z and 10 about x, and shifted) lands
where the file says (a known voxel's world position, the direction matrix); and the Colin27
template of the demo opens with its known size, range and place (its sform: MNI coordinates).
The header checks of the reader change nothing of a valid file: Colin27, ITK's KmeansTest, the
oblique file and the others read as with VTK's own reader (voxels, spacing, origin, direction);
its Maximum Data Size property refuses a file above it with an empty output. Colin27 with a
spoiled datatype, and cut in half, leave the reader and Deformable Surface empty (the path a user
takes: OpenDataFile, then the filter with a box)."""
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

# The header checks change nothing of a valid file: each file read through the plugin gives the
# same voxels (a hash of the scalars' bytes), spacing, origin and direction as VTK's own
# vtkNIFTIImageReader, unchecked, placed by the rule the plugin documents (the sform when
# sform_code > 0 and it is a rotation, else the qform when qform_code > 0 and it is one;
# world = R (origin + ijk spacing) + t). Same run, so no number is hard-coded.
import hashlib  # noqa: E402
from vtkmodules.vtkIOImage import vtkNIFTIImageReader  # noqa: E402


def rotation_and_shift(matrix):
    r = [[matrix.GetElement(i, j) for j in range(3)] for i in range(3)]
    ok = all(abs(sum(r[a][k] * r[b][k] for k in range(3)) - (a == b)) < 1e-4 for a in range(3) for b in range(3))
    det = (r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
           + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]))
    return (r, [matrix.GetElement(i, 3) for i in range(3)]) if ok and det > 0 else None


def unchecked(path):
    """VTK's reader alone: voxels, spacing, and the placement the plugin's rule gives."""
    plain = vtkNIFTIImageReader()
    plain.SetFileName(path)
    plain.Update()
    header = plain.GetNIFTIHeader()
    placed = None
    if header.GetSFormCode() > 0:
        placed = rotation_and_shift(plain.GetSFormMatrix())
    if placed is None and header.GetQFormCode() > 0:
        placed = rotation_and_shift(plain.GetQFormMatrix())
    r, t = placed if placed else ([[float(i == j) for j in range(3)] for i in range(3)], [0.0, 0.0, 0.0])
    o = plain.GetOutput().GetOrigin()
    origin = [sum(r[i][k] * o[k] for k in range(3)) + t[i] for i in range(3)]
    return plain.GetOutput(), origin, [r[i][j] for i in range(3) for j in range(3)]


def scalars_hash(image):
    values = vtk_to_numpy(image.GetPointData().GetScalars())
    return hashlib.sha256(values.tobytes()).hexdigest(), str(values.dtype)


kmeans = "/usr/share/doc/insighttoolkit5-examples/examples/Data/KmeansTest_T1UCharRaw.nii.gz"
roundtrip = os.path.join(out_dir, "roundtrip.nii.gz")
for volume in ("/usr/share/mricron/templates/ch2.nii.gz", kmeans, oblique, both, roundtrip, plain):
    if not os.path.exists(volume):
        sys.exit("%s is missing: the test command installs it, so the setup is broken" % volume)
    reader = OpenDataFile(volume)
    if reader is None or reader.GetXMLName() != "DSNIfTIImageReader":
        sys.exit("OpenDataFile did not pick the plugin's NIfTI reader for %s" % volume)
    checked = servermanager.Fetch(reader)
    expected, origin, direction = unchecked(volume)
    got_direction = [checked.GetDirectionMatrix().GetElement(i, j) for i in range(3) for j in range(3)]
    print("%s: dims %s, scalars %s, spacing %s, origin %s" % (os.path.basename(volume), checked.GetDimensions(),
          scalars_hash(checked)[0][:16], checked.GetSpacing(), [round(x, 4) for x in checked.GetOrigin()]))
    assert checked.GetDimensions() == expected.GetDimensions(), (checked.GetDimensions(), expected.GetDimensions())
    assert scalars_hash(checked) == scalars_hash(expected), "the voxels of %s differ from VTK's reader" % volume
    assert checked.GetSpacing() == expected.GetSpacing(), (checked.GetSpacing(), expected.GetSpacing())
    assert max(abs(a - b) for a, b in zip(checked.GetOrigin(), origin)) < 1e-9, (checked.GetOrigin(), origin)
    assert max(abs(a - b) for a, b in zip(got_direction, direction)) < 1e-12, (got_direction, direction)

# The cap is a property of the proxy (advanced): a valid file above it is refused, empty.
reader = OpenDataFile(oblique)
assert reader.MaximumDataSize == 16 * 2**30, reader.MaximumDataSize
reader.MaximumDataSize = 1000
reader.UpdatePipeline()
print("MaximumDataSize 1000 on %d bytes of data: %d points" % (
    a.nbytes, reader.GetDataInformation().GetNumberOfPoints()))
assert reader.GetDataInformation().GetNumberOfPoints() == 0
# Exactly the data's size is allowed (the value reaches the reader as a whole number of bytes).
reader.MaximumDataSize = a.nbytes
reader.UpdatePipeline()
assert reader.GetDataInformation().GetNumberOfPoints() == a.size, reader.GetDataInformation().GetNumberOfPoints()

# A user's path on Colin27 itself: OpenDataFile, then Deformable Surface with a
# box. A spoiled datatype (which killed the process) and a file cut in half (which was solved on
# in part) must both leave the reader and the filter empty, the process alive.
import gzip  # noqa: E402
import struct  # noqa: E402
from paraview.simple import Box  # noqa: E402

with gzip.open("/usr/share/mricron/templates/ch2.nii.gz", "rb") as f:
    colin_bytes = f.read()
spoiled = bytearray(colin_bytes)
struct.pack_into("<h", spoiled, 70, 1234)  # datatype (nifti1.h offset 70)
for name, data in (("colin_datatype_1234.nii", bytes(spoiled)), ("colin_half.nii", colin_bytes[:len(colin_bytes) // 2])):
    bad = os.path.join(out_dir, name)
    with open(bad, "wb") as f:
        f.write(data)
    reader = OpenDataFile(bad)
    box = Box(XLength=180, YLength=216, ZLength=180, Center=[0, -17, 19])
    surface = DeformableSurface(Input=reader, InitialSurface=box)  # noqa: F821 (from LoadPlugin)
    surface.UpdatePipeline()
    points = (reader.GetDataInformation().GetNumberOfPoints(), surface.GetDataInformation().GetNumberOfPoints())
    print("%s: reader %d points, Deformable Surface %d points" % (name, points[0], points[1]))
    assert points == (0, 0), points
