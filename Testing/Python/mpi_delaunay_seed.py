# SPDX-License-Identifier: BSD-3-Clause
"""DelaunaySeedSurface in distributed ParaView: run as
    mpiexec -n 2 pvbatch mpi_delaunay_seed.py
The points come from a Wavelet -> Threshold pipeline, which ParaView splits between the ranks
(checked per rank). The seed of the split points must equal the serial seed of the same points
(same triangle count, volume within 1e-9 relative), be computed on rank 0 only (the other ranks
output nothing, so nothing is duplicated), and the intensity rule must see the whole image
although the image proxy alone would be split too."""
import builtins
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager, simple  # noqa: E402
from paraview.modules.vtkRemotingCore import vtkProcessModule  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkDataObject, vtkDataSetAttributes, vtkPolyData  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkMassProperties, vtkThreshold  # noqa: E402
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource  # noqa: E402

from deformablesurface import vtkDelaunaySeedSurface  # noqa: E402
from ds_mpi import per_rank  # noqa: E402
import ds_invariants  # noqa: E402

simple.LoadPlugin(os.environ["DS_PLUGIN"])

n_ranks = vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
print("ranks:", n_ranks)
assert n_ranks >= 2, "run this test under mpiexec with at least 2 processes"

EXTENT = [-8, 8, -8, 8, -8, 8]
THRESHOLD = (160.0, 1000.0)
ALPHA = 1.3

# A deterministic function of the position (not of the point's index), so the seam points that
# two ranks both hold move identically. It breaks the grid's cospherical ties, making the
# Delaunay tetrahedrisation unique whatever the insertion order.
JITTER = """
def jitter(x, y, z):
    h = lambda a, b, c: math.sin(12.9898 * x + 78.233 * y + 37.719 * z + a) * 43758.5453 % 1.0 - 0.5
    return (x + 0.1 * h(0.0, 0, 0), y + 0.1 * h(1.7, 0, 0), z + 0.1 * h(3.1, 0, 0))
"""
exec(JITTER)

PERTURB = "import math\n" + JITTER + """
inp = self.GetInputDataObject(0, 0)
out = self.GetOutputDataObject(0)
out.ShallowCopy(inp)
from vtkmodules.vtkCommonCore import vtkPoints
pts = vtkPoints()
pts.SetDataTypeToDouble()
for i in range(inp.GetNumberOfPoints()):
    pts.InsertNextPoint(jitter(*inp.GetPoint(i)))
out.SetPoints(pts)
"""

# Programmable filters run their scripts in this interpreter on rank 0 and leave numpy's and
# vtk.numpy_interface's names (sum, all, split, round, ...) in the globals: builtins.* below.


def facts(poly):
    """(triangles, edges not shared by exactly two triangles, volume)."""
    edges = {}
    ids = poly.GetPolys().GetConnectivityArray()
    n = poly.GetNumberOfPolys()
    for c in range(n):
        tri = [ids.GetValue(3 * c + j) for j in range(3)]
        for j in range(3):
            key = tuple(sorted((tri[j], tri[(j + 1) % 3])))
            edges[key] = edges.get(key, 0) + 1
    bad = builtins.sum(1 for v in edges.values() if v != 2)
    if n:  # every seed here is closed, manifold, outward and finite
        ds_invariants.check_closed_manifold(ds_invariants.surface_facts(poly), "seed")
    volume = 0.0
    if n:
        mass = vtkMassProperties()
        mass.SetInputData(poly)
        mass.Update()
        volume = mass.GetVolume()
    return n, bad, volume


# --- Distributed pipeline ---------------------------------------------------------------
wavelet = simple.Wavelet(WholeExtent=EXTENT)
threshold = simple.Threshold(Input=wavelet, Scalars=["POINTS", "RTData"],
                             LowerThreshold=THRESHOLD[0], UpperThreshold=THRESHOLD[1])
points = simple.ProgrammableFilter(Input=threshold, OutputDataSetType="vtkUnstructuredGrid",
                                   Script=PERTURB)
input_split = per_rank(points)
print("input points per rank:", input_split)
assert sorted(input_split) == list(range(n_ranks)), "one report per rank"
assert builtins.all(p > 0 for p, _ in input_split.values()), "every rank holds some of the points"

image = simple.Wavelet(WholeExtent=EXTENT)  # a second instance: whole on port 1, split elsewhere
image_split = per_rank(image)
print("image points per rank when a plain filter asks:", image_split)
whole_image = (EXTENT[1] - EXTENT[0] + 1) ** 3
assert builtins.all(p < whole_image for p, _ in image_split.values()), "the image is split between ranks"

seed_alpha = simple.DelaunaySeedSurface(Input=points, Alpha=ALPHA)
seed_image = simple.DelaunaySeedSurface(Input=points, Image=image, UseIntensityRange=1,
                                        IntensityRange=list(THRESHOLD))

# --- Serial reference: the same points built by plain VTK on this process only -------------
rt_source = vtkRTAnalyticSource()
rt_source.SetWholeExtent(*EXTENT)
thr = vtkThreshold()
thr.SetInputConnection(rt_source.GetOutputPort())
thr.SetInputArrayToProcess(0, 0, 0, vtkDataObject.FIELD_ASSOCIATION_POINTS, "RTData")
thr.SetLowerThreshold(THRESHOLD[0])
thr.SetUpperThreshold(THRESHOLD[1])
thr.SetThresholdFunction(vtkThreshold.THRESHOLD_BETWEEN)
thr.Update()
serial_points = vtkPoints()
serial_points.SetDataTypeToDouble()
for i in range(thr.GetOutput().GetNumberOfPoints()):
    serial_points.InsertNextPoint(jitter(*thr.GetOutput().GetPoint(i)))
serial_input = vtkPolyData()
serial_input.SetPoints(serial_points)
print("serial input: %d points; distributed: %d points over %d ranks (seams held twice)"
      % (serial_input.GetNumberOfPoints(), builtins.sum(p for p, _ in input_split.values()), n_ranks))

# The reference really is the same point set: compare the sets of coordinates. (Fetch appends
# the ranks' pieces for vtkPolyData only, so the points travel as a vtkPolyData.)
as_poly = simple.ProgrammableFilter(Input=points, OutputDataSetType="vtkPolyData",
                                    Script="self.GetOutputDataObject(0).SetPoints("
                                           "self.GetInputDataObject(0, 0).GetPoints())")
fetched = servermanager.Fetch(as_poly)
assert fetched.GetNumberOfPoints() == builtins.sum(p for p, _ in input_split.values())
key = lambda x: tuple(builtins.round(v, 9) for v in x)
distributed_set = {key(fetched.GetPoint(i)) for i in range(fetched.GetNumberOfPoints())}
serial_set = {key(serial_input.GetPoint(i)) for i in range(serial_input.GetNumberOfPoints())}
assert distributed_set == serial_set, "serial reference built from other points than ParaView's"
assert builtins.sum(p for p, _ in input_split.values()) > len(serial_set), "seams are held twice"


def serial_seed(**settings):
    f = vtkDelaunaySeedSurface()
    f.SetController(None)  # only this process runs it: no gather
    f.SetInputData(serial_input)
    for name, value in settings.items():
        getattr(f, "Set" + name)(value)
    f.Update()
    return f.GetOutput()


image_for_reference = vtkRTAnalyticSource()
image_for_reference.SetWholeExtent(*EXTENT)
image_for_reference.Update()
cases = [
    ("Alpha %.2f" % ALPHA, seed_alpha, serial_seed(Alpha=ALPHA)),
    ("intensity %g..%g" % THRESHOLD, seed_image,
     serial_seed(ImageData=image_for_reference.GetOutput(), UseIntensityRange=True,
                 IntensityRange=THRESHOLD)),
]
for label, proxy, reference in cases:
    n_ref, bad_ref, vol_ref = facts(reference)
    n, bad, vol = facts(servermanager.Fetch(proxy))
    ranks = per_rank(proxy)
    print("%s: serial %d triangles, volume %.9f; distributed %d triangles, volume %.9f, "
          "relative difference %.2e; triangles per rank %s"
          % (label, n_ref, vol_ref, n, vol, builtins.abs(vol - vol_ref) / vol_ref,
             {r: c for r, (_, c) in sorted(ranks.items())}))
    assert n_ref > 0 and bad_ref == 0, "serial seed is a closed surface"
    assert n == n_ref and bad == 0, "distributed seed has the serial triangle count"
    assert builtins.abs(vol - vol_ref) <= 1e-9 * vol_ref, "distributed seed has the serial volume"
    assert ranks[0][1] == n_ref, "rank 0 holds the whole seed"
    assert builtins.all(c == 0 for r, (_, c) in ranks.items() if r != 0), "other ranks output nothing"
    tets = servermanager.Fetch(proxy, idx=1)
    assert tets.GetNumberOfCells() > 0 and tets.GetCellData().GetArray("TetraId") is not None

# The two rules must not give the same seed by accident of both being the convex hull.
hull = serial_seed()
assert facts(hull)[2] > 1.05 * facts(cases[0][2])[2], "Alpha carves the hull"
assert facts(hull)[2] > 1.05 * facts(cases[1][2])[2], "the intensity rule carves the hull"
print("mpi_delaunay_seed: all checks passed")
