# SPDX-License-Identifier: BSD-3-Clause
"""Bad input on one rank only, in distributed ParaView: run as
    mpiexec -n 2 pvbatch mpi_bad_piece.py
Rank 1 alone gets a bad piece (a NaN point, nothing, points without polygons, a non-manifold
fin; an image without scalars; NaN seed points) while rank 0's piece is good. Every collective
call must be reached on every rank: each case must return on all ranks (the ctest TIMEOUT of
this test is the hang guard, and each case's per-rank report is itself a collective update), the
error must be reported (on rank 0, which delivers the surface; a bad piece of the image, which
every rank reads in pieces, fails every rank), and the outputs must be empty on every rank, or,
where the bad piece adds nothing (an empty piece of the surface, points without polygons),
rank 0's surface must keep the invariants of ds_invariants.py. A good run
afterwards must still work: no rank is left out of step."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from paraview.modules.vtkRemotingCore import vtkProcessModule  # noqa: E402
from vtkmodules.util.misc import calldata_type  # noqa: E402
from vtkmodules.util.vtkConstants import VTK_STRING  # noqa: E402
from vtkmodules.vtkFiltersSources import vtkSphereSource  # noqa: E402

import ds_invariants  # noqa: E402
from ds_mpi import per_rank  # noqa: E402

simple.LoadPlugin(os.environ["DS_PLUGIN"])
n_ranks = vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
print("ranks:", n_ranks)
assert n_ranks >= 2, "run this test under mpiexec with at least 2 processes"

EXTENT = [-16, 16, -16, 16, -16, 16]
BALL = "255/(1+exp(sqrt(coordsX^2+coordsY^2+coordsZ^2)-8))"

# Rank 0 always makes the good start (a sphere of radius 12 around the ball); rank 1 makes
# the piece named by MODE.
SURFACE = """
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
out = self.GetOutputDataObject(0)
mode = "sphere" if rank == 0 else MODE
s = vtkSphereSource()
s.SetRadius(12)
s.SetThetaResolution(16)
s.SetPhiResolution(16)
s.Update()
if mode == "sphere":
    out.ShallowCopy(s.GetOutput())
elif mode == "nan":
    out.DeepCopy(s.GetOutput())
    out.GetPoints().SetPoint(3, float("nan"), 0.0, 0.0)
elif mode == "points only":
    out.SetPoints(s.GetOutput().GetPoints())
elif mode == "non-manifold":
    pts = vtkPoints()
    for x in ((-2, -2, 0), (2, -2, 0), (0, 2, 0), (0, -6, 0), (0, -2, 4)):
        pts.InsertNextPoint(x)
    polys = vtkCellArray()
    for third in (2, 3, 4):
        polys.InsertNextCell(3, (0, 1, third))
    out.SetPoints(pts)
    out.SetPolys(polys)
"""

# The ball image, its arrays removed on the ranks in STRIP.
STRIP = """
from vtkmodules.vtkParallelCore import vtkMultiProcessController
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
out = self.GetOutputDataObject(0)
out.ShallowCopy(self.GetInputDataObject(0, 0))
if rank in STRIP:
    out.GetPointData().Initialize()
"""

# Seed points: cube corners on rank 0 unless EMPTY0, three NaN points on rank 1.
SEED_POINTS = """
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkCommonCore import vtkPoints
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
out = self.GetOutputDataObject(0)
pts = vtkPoints()
if rank == 0 and not EMPTY0:
    for c in range(8):
        pts.InsertNextPoint(10.0 * (c & 1), 10.0 * ((c >> 1) & 1), 10.0 * (c >> 2))
elif rank == 1:
    for i in range(3):
        pts.InsertNextPoint(float("nan"), i, 0.0)
out.SetPoints(pts)
"""


class Messages:
    """The errors and warnings of the rank-0 object behind a proxy."""

    def __init__(self, proxy):
        self.errors, self.warnings = [], []
        obj = proxy.GetClientSideObject()
        obj.AddObserver("ErrorEvent", self.on_error)
        obj.AddObserver("WarningEvent", self.on_warning)

    @calldata_type(VTK_STRING)
    def on_error(self, obj, event, text):
        self.errors.append(text)

    @calldata_type(VTK_STRING)
    def on_warning(self, obj, event, text):
        self.warnings.append(text)


def rank0_sphere():
    s = vtkSphereSource()
    s.SetRadius(12)
    s.SetThetaResolution(16)
    s.SetPhiResolution(16)
    s.Update()
    return s.GetOutput()


def ball_image(strip_ranks):
    wavelet = simple.Wavelet(WholeExtent=EXTENT)
    ball = simple.Calculator(Input=wavelet, ResultArrayName="ball", Function=BALL)
    return simple.ProgrammableFilter(Input=ball, Script="STRIP = %r\n" % (strip_ranks,) + STRIP)


def check_case(label, proxy, messages, error, surface_on_rank0, start=None):
    """Asserts the error text (or none), and the per-rank outputs: empty everywhere, or a
    surface on rank 0 only (keeping the invariants against `start`) with the others empty."""
    ranks = per_rank(proxy)
    print("%s: per rank (points, cells) %s; errors %s; warnings %s"
          % (label, ranks, messages.errors, messages.warnings))
    assert sorted(ranks) == list(range(n_ranks)), label + ": every rank reported"
    if error:
        assert len(messages.errors) == 1 and error in messages.errors[0], \
            "%s: one error saying %r, got %s" % (label, error, messages.errors)
    else:
        assert not messages.errors, "%s: no error, got %s" % (label, messages.errors)
    for r, (points, cells) in ranks.items():
        if r == 0 and surface_on_rank0:
            assert points > 0 and cells > 0, label + ": a surface on rank 0"
        else:
            assert points == 0 and cells == 0, "%s: rank %d empty, got %s" % (label, r, (points, cells))
    if surface_on_rank0 and start is not None:
        ds_invariants.check_surface(start, servermanager.Fetch(proxy), label)


def deform(label, mode, error, surface_on_rank0, strip_ranks=()):
    image = ball_image(list(strip_ranks))
    surface = simple.ProgrammableSource(OutputDataSetType="vtkPolyData", Script="MODE = %r\n" % mode + SURFACE)
    ds = simple.DeformableSurface(Input=image, InitialSurface=surface, MaxLevels=1, MaxSweepsPerLevel=200)
    ds.Scalars = ["POINTS", "ball"]
    messages = Messages(ds)
    check_case(label, ds, messages, error, surface_on_rank0, rank0_sphere())
    for p in (ds, surface, image):
        simple.Delete(p)


def seed(label, empty0, error, surface_on_rank0):
    points = simple.ProgrammableSource(OutputDataSetType="vtkPolyData",
                                       Script="EMPTY0 = %r\n" % empty0 + SEED_POINTS)
    s = simple.DelaunaySeedSurface(Input=points)
    messages = Messages(s)
    check_case(label, s, messages, error, surface_on_rank0)
    if surface_on_rank0:
        facts = ds_invariants.surface_facts(servermanager.Fetch(s))
        ds_invariants.check_closed_manifold(facts, label, euler=2)
        assert facts["triangles"] == 12, label + ": the cube's 12 triangles"
    simple.Delete(s)
    simple.Delete(points)


deform("a NaN point in rank 1's piece", "nan", "non-finite point coordinate", False)
deform("a non-manifold fin as rank 1's piece", "non-manifold", "not a manifold triangle mesh", False)
deform("an empty piece on rank 1", "empty", None, True)
deform("points without polygons on rank 1", "points only", None, True)
# The image goes in pieces (every rank solves): rank 1's bad piece fails every rank.
deform("an image without scalars on rank 1 only", "empty", "another process's piece of the image",
       False, strip_ranks=[1])
deform("an image without scalars on every rank", "empty", "no point arrays", False, strip_ranks=[0, 1])
seed("seed: NaN points on rank 1, cube corners on rank 0", False, None, True)
seed("seed: NaN points on rank 1, nothing on rank 0", True, "No point with finite coordinates", False)
# After all that, the ranks are still in step: a good run works.
deform("a good run afterwards", "empty", None, True)
print("mpi_bad_piece: all checks passed")
