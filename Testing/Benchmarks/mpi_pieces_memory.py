# SPDX-License-Identifier: BSD-3-Clause
"""Peak memory per rank of a distributed solve (docs/SCALING.md, "Across processes"): run as
    pvbatch mpi_pieces_memory.py DIR --write [--large]   (once: writes DIR/ball512[_large].vti)
    mpiexec -n N /usr/bin/time -f "rank peak %M KB, %e s" pvbatch mpi_pieces_memory.py DIR [--large]
A 512^3 uint16 ball (radius 128, or 215 with --large: a surface spanning most of the image, so
that the fine levels' box fills most of each piece; object 2000 on a background of 1000,
Gaussian noise of s.d. 100, seed 7) read by ParaView's XML reader, each rank its piece; a Box
around the whole volume, every default. Prints per rank the voxels it held (field data
PieceVoxels, on rank 0) and the surface's vertices; GNU time prints each rank's peak RSS."""
import os
import sys
import time

import numpy
from paraview import servermanager, simple
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

N = 512
LARGE = "--large" in sys.argv
RADIUS = 215.0 if LARGE else 128.0
out_dir = sys.argv[1]
path = os.path.join(out_dir, "ball512_large.vti" if LARGE else "ball512.vti")
if "--write" in sys.argv:
    rng = numpy.random.default_rng(7)
    c = 0.5 * (N - 1)
    z, y, x = numpy.ogrid[:N, :N, :N]
    inside = (x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2 <= RADIUS ** 2
    values = numpy.where(inside, 2000.0, 1000.0) + rng.normal(0.0, 100.0, (N, N, N))
    image = vtkImageData()
    image.SetDimensions(N, N, N)
    array = numpy_to_vtk(numpy.clip(values, 0, 65535).astype(numpy.uint16).ravel(), deep=1)
    array.SetName("density")
    image.GetPointData().SetScalars(array)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()
    print("wrote", path)
    sys.exit(0)

plugin = os.environ.get("DS_PLUGIN")
simple.LoadPlugin(plugin) if plugin else simple.LoadDistributedPlugin("DeformableSurface")
reader = simple.XMLImageDataReader(FileName=[path])
box = simple.Box(XLength=N - 2, YLength=N - 2, ZLength=N - 2, Center=[0.5 * (N - 1)] * 3)
surface = simple.DeformableSurface(Input=reader, InitialSurface=box)
surface.Scalars = ["POINTS", "density"]
t0 = time.time()
surface.UpdatePipeline()
seconds = time.time() - t0
data = servermanager.Fetch(surface, arg1=0)
held = data.GetFieldData().GetArray("PieceVoxels")
print("%.1f s, %d vertices, voxels held per rank: %s" % (
    seconds, data.GetNumberOfPoints(),
    held and [int(held.GetValue(i)) for i in range(held.GetNumberOfTuples())]))
