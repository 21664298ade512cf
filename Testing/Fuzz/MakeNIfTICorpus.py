# SPDX-License-Identifier: BSD-3-Clause
"""Writes the seed corpus of FuzzNIfTIReader (Testing/Fuzz/corpus/NIfTIReader): small valid
files written by VTK's own NIfTI writer, and the nine spoiled files that once crashed or fooled the reader, made from one of
them (one header field changed at its nifti1.h offset). Each seed is one mode byte (0: the file
as it is, 1: to be gzipped by the fuzzer, 2: already a gzip stream) and the file's bytes.

Run with a Python that has VTK (e.g. /usr/bin/python3 Testing/Fuzz/MakeNIfTICorpus.py)."""
import gzip
import os
import struct
import tempfile

from vtkmodules.vtkCommonMath import vtkMatrix4x4
from vtkmodules.vtkImagingCore import vtkImageCast, vtkRTAnalyticSource
from vtkmodules.vtkImagingSources import vtkImageCanvasSource2D
from vtkmodules.vtkIOImage import vtkNIFTIImageWriter

out_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus", "NIfTIReader")


def volume(extent, scalar_type, components=1):
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(*extent)
    cast = vtkImageCast()
    cast.SetInputConnection(source.GetOutputPort())
    cast.SetOutputScalarType(scalar_type)
    cast.Update()
    image = cast.GetOutput()
    if components > 1:
        canvas = vtkImageCanvasSource2D()
        canvas.SetExtent(*extent)
        canvas.SetNumberOfScalarComponents(components)
        canvas.SetScalarTypeToUnsignedChar()
        canvas.SetDrawColor(0, 0, 0, 0)  # the canvas starts uninitialized: clear it first
        canvas.FillBox(extent[0], extent[1], extent[2], extent[3])
        canvas.SetDrawColor(200, 100, 50, 255)
        canvas.FillBox(0, extent[1] // 2, 0, extent[3] // 2)
        canvas.Update()
        image = canvas.GetOutput()
    return image


def nifti_bytes(image, version=1, qform=None):
    with tempfile.TemporaryDirectory() as scratch:
        path = os.path.join(scratch, "seed.nii")
        writer = vtkNIFTIImageWriter()
        writer.SetInputData(image)
        writer.SetNIFTIVersion(version)
        if qform is not None:
            writer.SetQFormMatrix(qform)
            writer.SetSFormMatrix(qform)
        writer.SetFileName(path)
        writer.Write()
        with open(path, "rb") as f:
            return f.read()


def put(data, offset, fmt, value):
    data = bytearray(data)
    struct.pack_into("<" + fmt, data, offset, value)
    return bytes(data)


def save(name, mode, data):
    with open(os.path.join(out_dir, name), "wb") as f:
        f.write(bytes([mode]) + data)


os.makedirs(out_dir, exist_ok=True)
VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_FLOAT = 3, 4, 10
placed = vtkMatrix4x4()
placed.SetElement(0, 3, -12.0)
placed.SetElement(2, 3, 4.5)

save("valid-uint8", 0, nifti_bytes(volume((0, 3, 0, 2, 0, 1), VTK_UNSIGNED_CHAR)))
save("valid-float-2d", 0, nifti_bytes(volume((0, 5, 0, 4, 0, 0), VTK_FLOAT)))
save("valid-rgb", 0, nifti_bytes(volume((0, 2, 0, 1, 0, 0), VTK_UNSIGNED_CHAR, 3)))  # one slice: FillBox draws on one
save("valid-nifti2", 0, nifti_bytes(volume((0, 2, 0, 2, 0, 2), VTK_SHORT), version=2))
base = nifti_bytes(volume((0, 9, 0, 9, 0, 5), VTK_SHORT), qform=placed)  # 1 200 bytes of data
save("valid-int16-placed-gz", 1, base)
save("valid-int16-gzip-stream", 2, gzip.compress(base, mtime=0))

# The nine spoiled cases, on the int16 file (offsets of nifti1.h).
save("bad-datatype-1234", 0, put(base, 70, "h", 1234))
huge = base[:352 + 1000]
for axis in (1, 2, 3):
    huge = put(huge, 40 + 2 * axis, "h", 30000)
save("bad-dims-30000-cubed-gz", 1, huge)
save("bad-truncated-gz", 1, base[:-500])
save("bad-negative-dim", 0, put(base, 44, "h", -10))
save("bad-nan-pixdim", 0, put(base, 80, "f", float("nan")))
save("bad-nan-sform", 1, put(base, 300, "f", float("nan")))
save("bad-vox-offset-beyond", 0, put(base, 108, "f", 1.0e6))
save("bad-not-nifti", 0, b"This is a text file that someone named .nii by mistake.\n" * 8)
save("bad-pixdim-zero", 0, put(base, 84, "f", 0.0))
