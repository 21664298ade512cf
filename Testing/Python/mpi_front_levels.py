# SPDX-License-Identifier: BSD-3-Clause
"""Front levels with the image in pieces (docs/METHOD.md §9.3, MultilevelSolver::FrontTriangles):
run as
    mpiexec -n 2 pvbatch mpi_front_levels.py
A dark ball with a tube three voxels wide sticking out of it along y (40 x 72 x 40 floats, noise)
is written as a .vti and read by ParaView's reader, which splits it between the ranks across the
tube; one click at the ball's centre (a seed sphere of radius 5, as Delaunay Seed Surface makes)
with every default. Each rank samples the front beyond the triangles where it owns the image
(ImagePiece::SampleOwned) and the ranks sum the samples. Asserted:
- the run has front levels (FrontLevels >= 1) and every rank held less than the whole image
  (field data PieceVoxels);
- the surface is the serial filter's on the whole image and the same gathered start exactly (same
  vertices, same coordinates), with the same FrontLevels, and is delivered once (rank 0); at the
  first front levels the surface's neighbourhood lies in rank 0's piece alone, and the ranks must
  still agree on making the force field again (MultilevelSolver::SetUpLevel);
- the tube is followed to within a voxel and a half of its end."""
import builtins
import os
import sys

import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter  # noqa: E402
from deformablesurface import vtkDeformableSurfaceFilter  # noqa: E402
from ds_mpi import Errors, per_rank, start_ranks  # noqa: E402

n_ranks = start_ranks()

NX, NY, NZ = 40, 72, 40
CENTRE = (19.3, 20.3, 19.7)  # the ball's, and the click
RADIUS = 7.0
TUBE_WIDTH, TUBE_LENGTH = 3.0, 22.0  # voxels; its length beyond the ball's surface (rounded tip)
DARK, SURROUND = 20.0, 70.0
out_dir = os.environ.get("DS_TEST_OUTPUT", ".")
os.makedirs(out_dir, exist_ok=True)


def tube_axis_distance(x, y, z):
    """Distance from the tube's axis segment (the ball's centre to the tip less the radius)."""
    tip = CENTRE[1] + RADIUS + TUBE_LENGTH - 0.5 * TUBE_WIDTH
    return numpy.sqrt((x - CENTRE[0]) ** 2 + (y - numpy.clip(y, CENTRE[1], tip)) ** 2 + (z - CENTRE[2]) ** 2)


def phantom():
    """The ball and tube, their edges blurred over about a voxel, with noise of s.d. 4."""
    k, j, i = numpy.mgrid[0:NZ, 0:NY, 0:NX].astype(float)
    ball = numpy.sqrt((i - CENTRE[0]) ** 2 + (j - CENTRE[1]) ** 2 + (k - CENTRE[2]) ** 2) - RADIUS
    tube = tube_axis_distance(i, j, k) - 0.5 * TUBE_WIDTH
    inside = 1.0 / (1.0 + numpy.exp(3.0 * numpy.minimum(ball, tube)))
    noise = numpy.random.default_rng(2504).normal(0.0, 4.0, inside.shape)
    values = SURROUND + (DARK - SURROUND) * inside + noise
    image = vtkImageData()
    image.SetDimensions(NX, NY, NZ)
    array = numpy_to_vtk(values.astype(numpy.float32).ravel(), deep=1)
    array.SetName("T1")
    image.GetPointData().SetScalars(array)
    return image


def field(poly, name):
    a = poly.GetFieldData().GetArray(name)
    return [a.GetValue(i) for i in range(a.GetNumberOfTuples())] if a else None


def tube_reach(poly):
    """The farthest vertex near the tube's axis, beyond the ball's surface (voxels)."""
    reach = -1e300
    for v in range(poly.GetNumberOfPoints()):
        x, y, z = poly.GetPoint(v)
        if tube_axis_distance(x, y, z) < TUBE_WIDTH + 1.0:
            reach = builtins.max(reach, y - CENTRE[1] - RADIUS)
    return reach


path = os.path.join(out_dir, "mpi_front_levels_%d.vti" % n_ranks)
writer = vtkXMLImageDataWriter()
writer.SetInputData(phantom())
writer.SetFileName(path)
writer.Write()

image = simple.OpenDataFile(path)
click = simple.Sphere(Center=list(CENTRE), Radius=5.0, ThetaResolution=16, PhiResolution=16)
ds = simple.DeformableSurface(Input=image, InitialSurface=click)
ds.Scalars = ["POINTS", "T1"]
errors = Errors(ds)
surface_ranks = per_rank(ds)
distributed = servermanager.Fetch(ds)
start = servermanager.Fetch(click)

reader = vtkXMLImageDataReader()
reader.SetFileName(path)
serial = vtkDeformableSurfaceFilter()
serial.SetController(None)
serial.SetInputConnection(0, reader.GetOutputPort())
serial.SetInitialSurfaceData(start)
serial.Update()
reference = serial.GetOutput()

n = distributed.GetNumberOfPoints()
same = n == reference.GetNumberOfPoints() > 0 and builtins.all(
    distributed.GetPoint(v) == reference.GetPoint(v) for v in range(n))
held = field(distributed, "PieceVoxels") or []
front, serial_front = field(distributed, "FrontLevels"), field(reference, "FrontLevels")
reach = tube_reach(distributed)
print("%d ranks held %s of %d voxels; FrontLevels %s (serial %s); %d vertices (serial %d), identical %s;"
      " tube reached %.2f of %g voxels; surface per rank %s; errors %s"
      % (n_ranks, held, NX * NY * NZ, front, serial_front, n, reference.GetNumberOfPoints(), same, reach,
         TUBE_LENGTH, surface_ranks, errors.errors))
assert not errors.errors, "no error"
assert len(held) == n_ranks and builtins.all(0 < h < NX * NY * NZ for h in held), \
    "solved in pieces: every rank held part of the image, none all of it"
assert front and front[0] >= 1, "front levels happened"
assert same, "the serial surface exactly"
assert front == serial_front, "the serial FrontLevels"
assert distributed.GetNumberOfPolys() == reference.GetNumberOfPolys()
assert surface_ranks[0][0] == n and builtins.all(
    p == 0 and c == 0 for r, (p, c) in surface_ranks.items() if r != 0), "delivered once"
assert reach >= TUBE_LENGTH - 1.5, "the tube followed to within a voxel and a half of its end"
print("mpi_front_levels: all checks passed")
