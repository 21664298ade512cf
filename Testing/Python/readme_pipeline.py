# SPDX-License-Identifier: BSD-3-Clause
"""Shared by pvpython_readme_pipeline.py and mpi_readme_pipeline.py (not a test by itself).

The README's pvpython pipeline exactly as a user types it -- OpenDataFile, Box,
DeformableSurface(Input=volume, InitialSurface=box) -- on a ball phantom saved as NIfTI,
VTK XML image (.vti) and MetaImage (.mhd). OpenDataFile's reader has not run when
DeformableSurface is made, so its Scalars domain is empty and the property stays ''; the
filter must then take the image's active scalars (or its only point array) by itself.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager  # noqa: E402
from paraview.simple import Box, LoadPlugin, OpenDataFile  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersCore import vtkArrayCalculator
from vtkmodules.vtkIOImage import vtkMetaImageWriter, vtkNIFTIImageWriter
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter  # noqa: E402

import ds_invariants  # noqa: E402

N = 40             # voxels per axis, spacing 1, origin 0
CENTER = 19.5      # the grid centre
RADIUS = 12.0
TOLERANCE = 0.3    # mean |distance to the sphere| allowed, voxels


def load_plugin():
    """LoadPlugin as the README does; its proxies (DeformableSurface) land in this module."""
    LoadPlugin(os.environ["DS_PLUGIN"], ns=globals())


def write_phantoms(directory):
    """A bright ball (float, named 'density'), written in three formats; returns the paths."""
    grid = vtkImageData()
    grid.SetDimensions(N, N, N)
    calc = vtkArrayCalculator()
    calc.SetInputData(grid)
    calc.SetAttributeTypeToPointData()
    calc.AddCoordinateScalarVariable("x", 0)
    calc.AddCoordinateScalarVariable("y", 1)
    calc.AddCoordinateScalarVariable("z", 2)
    calc.SetFunction("100/(1+exp(2*(sqrt((x-%g)^2+(y-%g)^2+(z-%g)^2)-%g)))"
                     % (CENTER, CENTER, CENTER, RADIUS))
    calc.SetResultArrayName("density")
    calc.SetResultArrayType(10)  # float
    calc.Update()
    image = calc.GetOutput()
    image.GetPointData().SetActiveScalars("density")
    os.makedirs(directory, exist_ok=True)
    paths = []
    for name, writer in (("ball.nii", vtkNIFTIImageWriter()),
                         ("ball.vti", vtkXMLImageDataWriter()),
                         ("ball.mhd", vtkMetaImageWriter())):
        path = os.path.join(directory, name)
        writer.SetInputData(image)
        writer.SetFileName(path)
        if name.endswith(".vti"):
            writer.SetDataModeToBinary()  # inline: Debian's expat cannot read raw appended data
        if name.endswith(".mhd"):
            writer.SetCompression(False)
        writer.Write()
        paths.append(path)
    return paths


def readme_pipeline(path):
    """The README's lines, with this phantom's bounds for the Box."""
    volume = OpenDataFile(path)
    box = Box(XLength=N, YLength=N, ZLength=N, Center=[CENTER] * 3)   # encloses the volume
    surface = DeformableSurface(Input=volume, InitialSurface=box)  # noqa: F821 (from LoadPlugin)
    ds_invariants.update_proxy(surface, [volume, box], os.path.basename(path))
    ds_invariants.check_surface(servermanager.Fetch(box), servermanager.Fetch(surface, arg1=0),
                                os.path.basename(path))
    return surface


def score(polydata):
    """(points, mean |r - RADIUS|) of a surface."""
    n = polydata.GetNumberOfPoints()
    if n == 0:
        return 0, float("inf")
    total = 0.0
    for i in range(n):
        p = polydata.GetPoint(i)
        total += abs(math.sqrt(sum((c - CENTER) ** 2 for c in p)) - RADIUS)
    return n, total / n


def run_all(directory, piece_voxels=None):
    """Runs the pipeline on every format; returns {file name: (scalars property, points, mean)}.
    A dict given as piece_voxels receives {file name: the output's PieceVoxels field data (the
    voxels each process held when the image was solved in pieces), or None without it}."""
    results = {}
    for path in write_phantoms(directory):
        surface = readme_pipeline(path)
        data = servermanager.Fetch(surface, arg1=0)
        results[os.path.basename(path)] = (list(surface.Scalars),) + score(data)
        if piece_voxels is not None:
            held = data.GetFieldData().GetArray("PieceVoxels")
            piece_voxels[os.path.basename(path)] = (
                None if held is None else [held.GetValue(r) for r in range(held.GetNumberOfTuples())])
    return results
