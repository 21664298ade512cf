# SPDX-License-Identifier: BSD-3-Clause
"""How Examples/colin27_wm_clicks.csv was chosen, on the image alone, as a user
looking for white matter would: voxels of Colin27 (mricron-data ch2.nii.gz, read with the
plugin's reader conventions: world = the file's sform, MNI mm) whose T1 lies in 100-125 (white
matter) and at least 6 mm from any voxel outside 85-140 (away from grey matter, CSF and
everything else); of those, 50 in an order drawn with the fixed seed 24, each kept when it lies
at least 15 mm from every click kept before (spread over the white matter).

    /usr/bin/python3 Testing/Benchmarks/colin27_wm_clicks.py > Examples/colin27_wm_clicks.csv
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkImagingGeneral import vtkImageEuclideanDistance
from vtkmodules.vtkIOImage import vtkNIFTIImageReader

HEAD = "/usr/share/mricron/templates/ch2.nii.gz"
WHITE = (100, 125)       # the click's own voxel
SURROUND = (85, 140)     # every voxel within MARGIN of the click
MARGIN, SPACING, COUNT, SEED = 6.0, 15.0, 50, 24


def read_head():
    """The T1 as [k, j, i] and the sform's (identity rotation) translation: the world of the
    plugin's vtkDSNIFTIImageReader, whose origin is the sform's translation here."""
    reader = vtkNIFTIImageReader()
    reader.SetFileName(HEAD)
    reader.Update()
    image = reader.GetOutput()
    sform = reader.GetSFormMatrix()
    rotation = [[sform.GetElement(r, c) for c in range(3)] for r in range(3)]
    if not np.allclose(rotation, np.eye(3)) or image.GetSpacing() != (1.0, 1.0, 1.0):
        sys.exit("%s: expected a 1 mm, unrotated sform" % HEAD)
    nx, ny, nz = image.GetDimensions()
    t1 = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(nz, ny, nx)
    return t1, [sform.GetElement(r, 3) for r in range(3)]


def distance_outside(t1):
    """Distance (mm) of every voxel to the nearest voxel outside SURROUND (beyond the image's
    border counts as outside: the volume is padded by one voxel of it)."""
    inside = np.pad((t1 >= SURROUND[0]) & (t1 <= SURROUND[1]), 1).astype(np.float64)
    image = vtkImageData()
    image.SetDimensions(inside.shape[2], inside.shape[1], inside.shape[0])
    image.GetPointData().SetScalars(numpy_to_vtk(inside.ravel() * 1e6, deep=1))
    edt = vtkImageEuclideanDistance()  # squared distance to the nearest 0 voxel
    edt.SetInputData(image)
    edt.InitializeOn()
    edt.ConsiderAnisotropyOn()
    edt.Update()
    squared = vtk_to_numpy(edt.GetOutput().GetPointData().GetScalars()).reshape(inside.shape)
    return np.sqrt(squared[1:-1, 1:-1, 1:-1])


def main():
    t1, origin = read_head()
    far = distance_outside(t1)
    candidates = np.argwhere((t1 >= WHITE[0]) & (t1 <= WHITE[1]) & (far >= MARGIN))
    rng = np.random.default_rng(SEED)
    kept = []
    for k, j, i in candidates[rng.permutation(len(candidates))]:
        p = np.array([origin[0] + i, origin[1] + j, origin[2] + k], dtype=float)
        if all(np.linalg.norm(p - q) >= SPACING for q in kept):
            kept.append(p)
            if len(kept) == COUNT:
                break
    print("x,y,z")
    for p in kept:
        print("%.1f,%.1f,%.1f" % tuple(p))
    print("%d candidates, %d clicks" % (len(candidates), len(kept)), file=sys.stderr)


if __name__ == "__main__":
    main()
