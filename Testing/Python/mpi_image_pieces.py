# SPDX-License-Identifier: BSD-3-Clause
"""DeformableSurface with the image in pieces (docs/METHOD.md §9.8): run as
    mpiexec -n 2 pvbatch mpi_image_pieces.py     (and -n 3)
A capsule phantom (32 x 32 x 240 floats, noise) is written as a .vti and as a .pvti of 3 pieces
and read by ParaView's XML readers; the start is a box near the capsule, with Sigma 2.5 voxels
and RegionWeight 0 (every other property default), and for the .pvti also with every default
(sigma_0 from the start and the intensity range estimated, both from the pieces).
Asserted, for each file:
- every rank held at least its share (field data PieceVoxels) and less than the whole image: its
  slab and the ghost layers the request allows for (11 with Sigma 2.5; 13 with every default,
  the sampled Gaussian's largest radius and one, as sigma_0 from the start is not known when
  the pieces are asked for); with every default the levels include sigma between 3 and 9
  voxels, the recursive Gaussian passed from piece to piece;
- the surface equals the serial filter's on the whole image and the same gathered start: same
  vertex count, coordinates to 1e-6 relative; it is delivered once (rank 0; the others and their
  convergence tables are empty); it lies on the capsule (mean distance below 0.2 voxel; 0.4
  with every default, whose result spreads over 0.21-0.32 voxel with the noise's seed);
- a ball in a 44 x 46 x 48 image (bricks on 3 ranks) with every default: the serial surface
  exactly, no rank holding the whole image;
- a rank whose piece of the image has no scalars makes every rank fail with an error, none left
  waiting (the ctest timeout is the hang guard), and a good run afterwards still works."""
import builtins
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy  # noqa: E402
from paraview import servermanager, simple  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
from vtkmodules.vtkIOParallelXML import vtkXMLPImageDataWriter  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter  # noqa: E402

from deformablesurface import vtkDeformableSurfaceFilter  # noqa: E402
from ds_mpi import Errors, per_rank, start_ranks  # noqa: E402

n_ranks = start_ranks()

NX, NY, NZ = 32, 32, 240
# Sigma given and the region force off: no rank holds the whole image.
SETTINGS = dict(Sigma=2.5, RegionWeight=0.0)
out_dir = os.environ.get("DS_TEST_OUTPUT", ".")
os.makedirs(out_dir, exist_ok=True)


def phantom():
    k, j, i = numpy.mgrid[0:NZ, 0:NY, 0:NX].astype(float)
    z = numpy.clip(k, 50.0, 190.0)
    d = numpy.sqrt((i - 15.5) ** 2 + (j - 15.5) ** 2 + (k - z) ** 2)
    noise = numpy.random.default_rng(4711).uniform(-5.0, 5.0, d.shape)
    values = 100.0 / (1.0 + numpy.exp(2.0 * (d - 9.0))) + noise
    image = vtkImageData()
    image.SetDimensions(NX, NY, NZ)
    image.SetSpacing(1.0, 1.0, 1.0)
    array = numpy_to_vtk(values.astype(numpy.float32).ravel(), deep=1)
    array.SetName("capsule")
    image.GetPointData().SetScalars(array)
    return image


image = phantom()
vti = os.path.join(out_dir, "mpi_image_pieces_%d.vti" % n_ranks)
pvti = os.path.join(out_dir, "mpi_image_pieces_%d.pvti" % n_ranks)
writer = vtkXMLImageDataWriter()
writer.SetInputData(image)
writer.SetFileName(vti)
writer.Write()
pwriter = vtkXMLPImageDataWriter()
pwriter.SetInputData(image)
pwriter.SetFileName(pvti)
pwriter.SetController(None)  # written by this process alone
pwriter.SetNumberOfPieces(3)
pwriter.SetStartPiece(0)
pwriter.SetEndPiece(2)
pwriter.Write()

# Rank 1 strips the scalars of its piece when STRIP is set.
STRIP = """
from vtkmodules.vtkParallelCore import vtkMultiProcessController
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
out = self.GetOutputDataObject(0)
out.ShallowCopy(self.GetInputDataObject(0, 0))
if STRIP and rank == 1:
    out.GetPointData().Initialize()
"""


def serial(start, settings, path=None):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path or vti)
    reader.Update()
    f = vtkDeformableSurfaceFilter()
    f.SetController(None)
    f.SetInputData(0, reader.GetOutput())
    f.SetInitialSurfaceData(start)
    for key, value in settings.items():
        getattr(f, "Set" + key)(value)
    f.Update()
    sigmas = f.GetOutputDataObject(1).GetColumnByName("Sigma")
    return f.GetOutput(), sorted({sigmas.GetValue(i) for i in range(sigmas.GetNumberOfTuples())})


def check_file(path, settings):
    reader = simple.OpenDataFile(path)
    box = simple.Box(XLength=24.0, YLength=24.0, ZLength=168.0, Center=[15.5, 15.5, 119.5])
    ds = simple.DeformableSurface(Input=reader, InitialSurface=box, **settings)
    ds.Scalars = ["POINTS", "capsule"]
    errors = Errors(ds)
    surface_ranks = per_rank(ds)
    table_ranks = per_rank(ds, 1)
    distributed = servermanager.Fetch(ds)
    start = servermanager.Fetch(box)
    reference, sigmas = serial(start, settings)
    fd = distributed.GetFieldData()
    held = [fd.GetArray("PieceVoxels").GetValue(r) for r in range(n_ranks)]
    whole = fd.GetArray("ImageVoxels").GetValue(0)
    n = distributed.GetNumberOfPoints()
    worst = 0.0
    if n == reference.GetNumberOfPoints():
        for v in range(n):
            a, b = distributed.GetPoint(v), reference.GetPoint(v)
            size = builtins.max(1e-300, builtins.sum(x * x for x in b) ** 0.5)
            worst = builtins.max(worst, builtins.sum((a[c] - b[c]) ** 2 for c in range(3)) ** 0.5 / size)
    name = os.path.basename(path) + (" (every default)" if not settings else "")
    distance = 0.0
    for v in range(n):
        x, y, z = distributed.GetPoint(v)
        zc = builtins.min(190.0, builtins.max(50.0, z))
        distance += builtins.abs(((x - 15.5) ** 2 + (y - 15.5) ** 2 + (z - zc) ** 2) ** 0.5 - 9.0) / n
    print("%s: mean distance to the capsule %.3f voxel" % (name, distance))
    print("%s: %d ranks held %s of %d voxels; %d vertices (serial %d), max relative difference %.3g;"
          " surface per rank %s, table per rank %s; errors %s"
          % (name, n_ranks, held, whole, n, reference.GetNumberOfPoints(), worst, surface_ranks,
             table_ranks, errors.errors))
    assert not errors.errors, name + ": no error"
    assert whole == NX * NY * NZ
    assert builtins.all(whole / n_ranks <= h <= whole for h in held), name + ": every rank held its share"
    ghosts = 13 if not settings else 11
    slab = NX * NY * (NZ - 1) / n_ranks  # a rank's share of the cells along z
    print("%s: levels' sigma %s voxels" % (name, ["%.2f" % s for s in sigmas]))
    assert builtins.all(h <= slab + NX * NY * (2 * ghosts + 2) for h in held), \
        name + ": each rank held its slab and %d ghost layers at most" % ghosts
    assert builtins.max(held) < whole, name + ": less than the whole image"
    assert settings or builtins.any(3.0 <= s < 9.0 for s in sigmas), \
        name + ": a level with the recursive Gaussian, in pieces"
    assert n == reference.GetNumberOfPoints() > 0, name + ": the serial vertex count"
    assert distributed.GetNumberOfPolys() == reference.GetNumberOfPolys()
    assert worst <= 1e-6, name + ": the serial coordinates to 1e-6 relative"
    # With every default the capsule's mean distance depends on its noise: over the seeds 4711
    # to 4718 it spreads over 0.21-0.32 voxel (0.19-0.35 before the sweeps kept the umbrellas,
    # which changed only the rounding), this seed 0.25; with Sigma 2.5 and no region force it
    # stays below 0.2.
    assert distance <= (0.2 if settings else 0.4), name + ": on the capsule"
    assert surface_ranks[0][0] == n and builtins.all(
        p == 0 and c == 0 for r, (p, c) in surface_ranks.items() if r != 0), name + ": delivered once"
    assert table_ranks[0][0] > 0 and builtins.all(
        rows == 0 for r, (rows, _) in table_ranks.items() if r != 0), name + ": one convergence table"
    for p in (ds, box, reader):
        simple.Delete(p)


def check_bricks():
    """A ball in a 44 x 46 x 48 image with every default: on 3 ranks VTK's block mode cuts z,
    then y (bricks), so the recursive Gaussian passes its state along two axes."""
    k, j, i = numpy.mgrid[0:48, 0:46, 0:44].astype(float)
    d = numpy.sqrt((i - 21.5) ** 2 + (j - 22.5) ** 2 + (k - 23.5) ** 2)
    noise = numpy.random.default_rng(4712).uniform(-5.0, 5.0, d.shape)
    ball = vtkImageData()
    ball.SetDimensions(44, 46, 48)
    array = numpy_to_vtk((100.0 / (1.0 + numpy.exp(2.0 * (d - 12.0))) + noise).astype(numpy.float32).ravel(), deep=1)
    array.SetName("ball")
    ball.GetPointData().SetScalars(array)
    path = os.path.join(out_dir, "mpi_image_pieces_ball_%d.vti" % n_ranks)
    w = vtkXMLImageDataWriter()
    w.SetInputData(ball)
    w.SetFileName(path)
    w.Write()
    reader = simple.OpenDataFile(path)
    box = simple.Box(XLength=32.0, YLength=32.0, ZLength=32.0, Center=[21.5, 22.5, 23.5])
    ds = simple.DeformableSurface(Input=reader, InitialSurface=box)
    ds.Scalars = ["POINTS", "ball"]
    errors = Errors(ds)
    distributed = servermanager.Fetch(ds)
    reference, sigmas = serial(servermanager.Fetch(box), {}, path)
    held = [distributed.GetFieldData().GetArray("PieceVoxels").GetValue(r) for r in range(n_ranks)]
    n = distributed.GetNumberOfPoints()
    same = n == reference.GetNumberOfPoints() > 0 and builtins.all(
        distributed.GetPoint(v) == reference.GetPoint(v) for v in range(n))
    print("ball (every default, levels' sigma %s voxels): %d ranks held %s of %d voxels; %d vertices"
          " (serial %d), identical %s; errors %s"
          % (["%.2f" % s for s in sigmas], n_ranks, held, 44 * 46 * 48, n,
             reference.GetNumberOfPoints(), same, errors.errors))
    assert not errors.errors and same, "ball: the serial surface exactly"
    assert builtins.max(held) < 44 * 46 * 48, "ball: no rank held the whole image"
    assert builtins.any(3.0 <= s < 9.0 for s in sigmas), "ball: a level with the recursive Gaussian"
    for p in (ds, box, reader):
        simple.Delete(p)


def bad_piece(strip):
    reader = simple.OpenDataFile(vti)
    stripped = simple.ProgrammableFilter(Input=reader, Script="STRIP = %r\n" % strip + STRIP)
    box = simple.Box(XLength=24.0, YLength=24.0, ZLength=168.0, Center=[15.5, 15.5, 119.5])
    ds = simple.DeformableSurface(Input=stripped, InitialSurface=box, **SETTINGS)
    ds.Scalars = ["POINTS", "capsule"]
    errors = Errors(ds)
    ranks = per_rank(ds)
    print("rank 1 without scalars: %s; per rank %s; errors on rank 0 %s" % (strip, ranks, errors.errors))
    assert sorted(ranks) == list(range(n_ranks)), "every rank reported"
    if strip:
        assert len(errors.errors) == 1 and "another process's piece" in errors.errors[0], errors.errors
        assert builtins.all(p == 0 for p, _ in ranks.values()), "every output empty"
    else:
        assert not errors.errors and ranks[0][0] > 0
    for p in (ds, box, stripped, reader):
        simple.Delete(p)


check_file(vti, SETTINGS)
check_file(pvti, SETTINGS)
check_file(pvti, {})
check_bricks()
bad_piece(True)
bad_piece(False)  # the ranks are still in step
print("mpi_image_pieces: all checks passed")
