# SPDX-License-Identifier: BSD-3-Clause
"""The invariants every surface the module's filters produce must keep, for the Python tests
(the C++ tests use Testing/Cxx/DSSurfaceInvariants.h, with the same checks):

- finite coordinates, triangles only, every stored point used;
- a closed start stays closed, 2-manifold (each edge in two triangles, each vertex one fan),
  consistently oriented like the start, with the start's Euler characteristic;
- the "SelfIntersections" field (DeformableSurface) within what the test allows (0 by default);
- the inputs unchanged, bit for bit (InputGuard: a fingerprint of the image's geometry and point
  arrays, of a poly data's points, cells and point arrays, taken before and compared after).

Plain vtkmodules and numpy: it runs under /usr/bin/python3, pvpython and pvbatch alike.
A failed check raises AssertionError naming the label and the number that broke it."""
import hashlib

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkTriangleFilter


def _triangles(poly):
    """The (n, 3) point IDs of poly's triangles and the number of its other cells."""
    polys = poly.GetPolys()
    offsets = vtk_to_numpy(polys.GetOffsetsArray()) if polys.GetNumberOfCells() else numpy.zeros(1, int)
    conn = vtk_to_numpy(polys.GetConnectivityArray()) if polys.GetNumberOfCells() else numpy.zeros(0, int)
    sizes = numpy.diff(offsets)
    tri = sizes == 3
    starts = offsets[:-1][tri]
    ids = numpy.stack([conn[starts], conn[starts + 1], conn[starts + 2]], axis=1) if tri.any() \
        else numpy.zeros((0, 3), dtype=numpy.int64)
    others = int((~tri).sum()) + poly.GetNumberOfStrips() + poly.GetNumberOfVerts() + poly.GetNumberOfLines()
    return ids.astype(numpy.int64), others


def surface_facts(poly):
    """Topology, finiteness and signed volume of poly's triangles, as a dict."""
    tri, others = _triangles(poly)
    n = poly.GetNumberOfPoints()
    x = vtk_to_numpy(poly.GetPoints().GetData()).astype(float) if n else numpy.zeros((0, 3))
    directed = numpy.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]) if len(tri) \
        else numpy.zeros((0, 2), dtype=numpy.int64)
    d_unique, d_count = numpy.unique(directed, axis=0, return_counts=True)
    undirected = numpy.sort(directed, axis=1)
    u_unique, u_count = numpy.unique(undirected, axis=0, return_counts=True)
    used = numpy.unique(tri)
    # A manifold vertex: its triangles form one fan (following prev -> next visits them all).
    fans = {}
    for t in tri.tolist():
        for j in range(3):
            fans.setdefault(t[j], {})[t[(j + 2) % 3]] = t[(j + 1) % 3]
    not_one_fan = 0
    for v, next_of in fans.items():
        start = next(iter(next_of))
        cur, steps = start, 0
        while True:
            if cur not in next_of:
                break
            cur = next_of[cur]
            steps += 1
            if cur == start or steps > len(next_of):
                break
        not_one_fan += 0 if (cur == start and steps == len(next_of)) else 1
    volume = 0.0
    if len(tri) and numpy.isfinite(x).all():
        p0, p1, p2 = x[tri[:, 0]], x[tri[:, 1]], x[tri[:, 2]]
        volume = float(numpy.einsum("ij,ij->i", p0, numpy.cross(p1, p2)).sum() / 6.0)
    return dict(triangles=len(tri), other_cells=others, points=n, used_points=len(used),
                non_finite_points=int((~numpy.isfinite(x)).any(axis=1).sum()),
                edges=len(u_unique), edges_not_twice=int((u_count != 2).sum()),
                directed_edges_repeated=int((d_count > 1).sum()), vertices_not_one_fan=not_one_fan,
                euler=len(used) - len(u_unique) + len(tri), signed_volume=volume)


def start_facts(start):
    """surface_facts of a start surface as Deformable Surface sees it: polygons and strips as
    triangles, points closer than 1e-6 of the bounding box merged (ParaView's Box has each face
    apart)."""
    faces = vtkPolyData()
    faces.SetPoints(start.GetPoints())
    faces.SetPolys(start.GetPolys())
    faces.SetStrips(start.GetStrips())
    tri = vtkTriangleFilter()
    tri.SetInputData(faces)
    merged = vtkCleanPolyData()
    merged.SetInputConnection(tri.GetOutputPort())
    merged.SetTolerance(1e-6)
    merged.ConvertPolysToLinesOff()
    merged.Update()
    return surface_facts(merged.GetOutput())


def _check(ok, label, what, facts):
    if not ok:
        raise AssertionError("%s: %s (%s)" % (label, what, facts))


def check_closed_manifold(facts, label, euler=None, outward=True):
    """The checks every valid closed surface passes; euler None skips that one."""
    _check(facts["triangles"] > 0, label, "surface has triangles", facts)
    _check(facts["other_cells"] == 0, label, "only triangles", facts)
    _check(facts["non_finite_points"] == 0, label, "finite coordinates", facts)
    _check(facts["edges_not_twice"] == 0, label, "closed: every edge in exactly two triangles", facts)
    _check(facts["directed_edges_repeated"] == 0, label, "consistently oriented", facts)
    _check(facts["vertices_not_one_fan"] == 0, label, "manifold vertices: one fan each", facts)
    _check(facts["used_points"] == facts["points"], label, "every stored point used", facts)
    if outward:
        _check(facts["signed_volume"] > 0, label, "outward orientation: signed volume > 0", facts)
    if euler is not None:
        _check(facts["euler"] == euler, label, "Euler characteristic %s expected" % euler, facts)


def check_surface(start, output, label, allow_self_intersections=0):
    """The invariants of `output` produced from the start surface `start` (see the module
    docstring); returns the output's facts. An open start gives an output that is finite,
    triangles only and consistently oriented."""
    s, f = start_facts(start), surface_facts(output)
    print("%s: start %d triangles, Euler %d, volume %.6g -> output %d triangles, Euler %d, volume %.6g"
          % (label, s["triangles"], s["euler"], s["signed_volume"], f["triangles"], f["euler"],
             f["signed_volume"]))
    if s["triangles"] > 0 and s["edges_not_twice"] == 0:
        check_closed_manifold(f, label, euler=s["euler"], outward=False)
        _check((f["signed_volume"] > 0) == (s["signed_volume"] > 0), label, "orientation as the start's", f)
    else:
        _check(f["triangles"] > 0, label, "surface has triangles", f)
        _check(f["other_cells"] == 0, label, "only triangles", f)
        _check(f["non_finite_points"] == 0, label, "finite coordinates", f)
        _check(f["directed_edges_repeated"] == 0, label, "consistently oriented", f)
        _check(f["used_points"] == f["points"], label, "every stored point used", f)
    selfx = output.GetFieldData().GetArray("SelfIntersections")
    if selfx is not None:
        _check(selfx.GetValue(0) <= allow_self_intersections, label,
               "SelfIntersections %d <= %d" % (selfx.GetValue(0), allow_self_intersections), f)
    return f


def _hash_array(h, array):
    if array is None:
        h.update(b"-")
        return
    h.update((array.GetName() or "").encode())
    h.update(numpy.ascontiguousarray(vtk_to_numpy(array)).tobytes())


def fingerprint(data):
    """A digest of what a filter must leave unchanged in its input."""
    h = hashlib.sha256()
    if isinstance(data, vtkImageData):
        h.update(numpy.array(data.GetExtent(), dtype=numpy.int64).tobytes())
        h.update(numpy.array(data.GetSpacing() + data.GetOrigin()).tobytes())
        h.update(numpy.array([data.GetDirectionMatrix().GetElement(i // 3, i % 3) for i in range(9)]).tobytes())
    if isinstance(data, vtkPolyData):
        _hash_array(h, data.GetPoints().GetData() if data.GetPoints() else None)
        for cells in (data.GetVerts(), data.GetLines(), data.GetPolys(), data.GetStrips()):
            _hash_array(h, cells.GetOffsetsArray())
            _hash_array(h, cells.GetConnectivityArray())
    if data is not None and data.IsA("vtkDataSet"):
        pd = data.GetPointData()
        for i in range(pd.GetNumberOfArrays()):
            _hash_array(h, pd.GetArray(i))
    return h.hexdigest()


class InputGuard:
    """Fingerprints its inputs when made; check() raises if any changed since."""

    def __init__(self, *inputs):
        self.inputs = [(d, fingerprint(d)) for d in inputs if d is not None]

    def check(self, label):
        for data, digest in self.inputs:
            if fingerprint(data) != digest:
                raise AssertionError("%s: input %s changed" % (label, data.GetClassName()))
        print("%s: %d input(s) unchanged" % (label, len(self.inputs)))


def update_proxy(proxy, inputs, label, time=None):
    """ParaView: UpdatePipeline of `proxy` with the data of its input proxies (this process's
    objects) fingerprinted before and compared after. Distributed, the filters ask their inputs
    for other pieces than UpdatePipeline does (the whole image on every rank), so the inputs
    re-execute and a fingerprint proves nothing: there the serial runs carry the check."""
    from paraview.modules.vtkRemotingCore import vtkProcessModule
    update = (lambda p: p.UpdatePipeline(time)) if time is not None else (lambda p: p.UpdatePipeline())
    if vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions() > 1:
        update(proxy)
        print("%s: distributed, inputs not fingerprinted" % label)
        return
    for p in inputs:
        update(p)
    if any(p.GetClientSideObject() is None for p in inputs):
        # Client-server: the data live on the server; a fetched copy of each input before and
        # after stands for them (fetching does not re-execute an up-to-date pipeline).
        from paraview import servermanager
        before = [fingerprint(servermanager.Fetch(p)) for p in inputs]
        update(proxy)
        if [fingerprint(servermanager.Fetch(p)) for p in inputs] != before:
            raise AssertionError("%s: an input changed on the server" % label)
        print("%s: %d input(s) unchanged (fetched from the server)" % (label, len(inputs)))
        return
    guard = InputGuard(*[p.GetClientSideObject().GetOutputDataObject(0) for p in inputs])
    update(proxy)
    guard.check(label)


def update_filter(algorithm, label):
    """VTK: Update of `algorithm` with every input's data fingerprinted before (its producer
    updated first) and compared after."""
    inputs = []
    for port in range(algorithm.GetNumberOfInputPorts()):
        for c in range(algorithm.GetNumberOfInputConnections(port)):
            algorithm.GetInputAlgorithm(port, c).Update()
            inputs.append(algorithm.GetInputDataObject(port, c))
    guard = InputGuard(*inputs)
    algorithm.Update()
    guard.check(label)
