# SPDX-License-Identifier: BSD-3-Clause
"""vtkDSSeedPoints in plain VTK Python (/usr/bin/python3), the API a C++ or Python user calls
without ParaView: AddPoint and RemoveAllPoints, the indexed setters the ParaView property uses,
the output (one point and one vertex per seed point, in order, double precision, the ObjectId
array), a piece other than 0 (empty, for MPI), and bad input (an error, an empty output)."""
import sys

from vtkmodules.vtkCommonCore import vtkCommand

from deformablesurface import vtkDSSeedPoints

failures = []


def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what)
    if not ok:
        failures.append(what)


class Errors:
    """Counts the ErrorEvents of an algorithm (its vtkErrorMacro)."""

    def __init__(self, obj):
        self.count = 0
        obj.AddObserver(vtkCommand.ErrorEvent, self)

    def __call__(self, caller, event):
        self.count += 1


def run(source):
    source.Update()
    out = source.GetOutput()
    ids = out.GetPointData().GetArray("ObjectId")
    return ([out.GetPoint(i) for i in range(out.GetNumberOfPoints())],
            [ids.GetValue(i) for i in range(ids.GetNumberOfTuples())] if ids else None, out)


source = vtkDSSeedPoints()
errors = Errors(source)
source.AddPoint(1.0, 2.0, 3.0)
source.AddPoint(4.0, 5.0, 6.5, 2)
points, ids, out = run(source)
check(points == [(1.0, 2.0, 3.0), (4.0, 5.0, 6.5)] and ids == [0, 2],
      "AddPoint: %s, ObjectId %s" % (points, ids))
check(out.GetNumberOfVerts() == 2 and out.GetPoints().GetData().GetDataTypeAsString() == "double",
      "one vertex per point (%d), double coordinates (%s)" % (out.GetNumberOfVerts(), out.GetPoints().GetData().GetDataTypeAsString()))

# The property's way: the count, then each coordinate; no ObjectIds: every point object 0.
source.RemoveAllPoints()
source.SetNumberOfPointCoordinates(6)
for i, v in enumerate([0.1, 0.2, 0.3, -1.0, -2.0, -3.0]):
    source.SetPointCoordinate(i, v)
points, ids, _ = run(source)
check(points == [(0.1, 0.2, 0.3), (-1.0, -2.0, -3.0)] and ids == [0, 0],
      "indexed coordinates, no ObjectIds: %s, ObjectId %s" % (points, ids))
source.SetNumberOfObjectIds(2)
source.SetObjectId(1, 7)
check(run(source)[1] == [0, 7], "SetObjectId reaches the ObjectId array")

# MPI: only piece 0 holds the points.
source.UpdatePiece(1, 2, 0)
check(source.GetOutput().GetNumberOfPoints() == 0, "piece 1 of 2 is empty")
source.UpdatePiece(0, 2, 0)
check(source.GetOutput().GetNumberOfPoints() == 2, "piece 0 of 2 holds both points")

# Bad input: an error and an empty output each time.
for what, setup in (("4 coordinates", lambda s: (s.SetNumberOfPointCoordinates(4), s.SetNumberOfObjectIds(0))),
                    ("a NaN", lambda s: (s.SetNumberOfPointCoordinates(3), s.SetPointCoordinate(1, float("nan")))),
                    ("an infinity", lambda s: s.SetPointCoordinate(1, float("inf"))),
                    ("3 ObjectIds for 1 point", lambda s: (s.SetPointCoordinate(1, 0.0), s.SetNumberOfObjectIds(3)))):
    setup(source)
    before = errors.count
    source.UpdatePiece(0, 1, 0)
    check(errors.count > before and source.GetOutput().GetNumberOfPoints() == 0, "%s: error, empty output" % what)
source.SetNumberOfObjectIds(0)
check(run(source)[0] == [(0.1, 0.0, 0.3)], "fixed again: the point is back")
sys.exit(1 if failures else 0)
