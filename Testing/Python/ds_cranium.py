# SPDX-License-Identifier: BSD-3-Clause
"""The real head CT of Debian's invesalius-examples as a volume ParaView opens.

Cranium.inv3 is InVesalius's project file: a gzipped tar whose main.plist gives the voxels'
type, shape (z, y, x) and spacing, and whose matrix.dat holds them raw (int16 HU, x fastest).
write_metaimage() extracts matrix.dat and writes a MetaImage header beside it (origin 0, the
file's own voxel order: y grows towards the face, z towards the vertex), which OpenDataFile
reads with ParaView's MetaImage reader."""
import os
import plistlib
import tarfile

CRANIUM = "/usr/share/doc/invesalius-examples/examples/Cranium.inv3"


def write_metaimage(folder, project=CRANIUM):
    """Extracts the CT into `folder` and returns the path of its .mhd header."""
    os.makedirs(folder, exist_ok=True)
    with tarfile.open(project, "r:gz") as tar:
        members = {os.path.basename(m.name): m for m in tar.getmembers() if m.isfile()}
        info = plistlib.loads(tar.extractfile(members["main.plist"]).read())
        matrix = info["matrix"]
        if matrix["dtype"] != "int16":
            raise RuntimeError("%s: voxels of type %s, not int16" % (project, matrix["dtype"]))
        raw = os.path.join(folder, "cranium.raw")
        with open(raw, "wb") as out:
            out.write(tar.extractfile(members[matrix["filename"]]).read())
    nz, ny, nx = matrix["shape"]
    header = os.path.join(folder, "cranium.mhd")
    with open(header, "w") as out:
        out.write("ObjectType = Image\nNDims = 3\nDimSize = %d %d %d\n" % (nx, ny, nz))
        out.write("ElementSpacing = %s\n" % " ".join(repr(float(s)) for s in info["spacing"]))
        out.write("Offset = 0 0 0\nElementType = MET_SHORT\nElementByteOrderMSB = False\n")
        out.write("ElementDataFile = cranium.raw\n")
    return header
