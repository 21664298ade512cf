# SPDX-License-Identifier: BSD-3-Clause
# The outputs of Deformable Surface carry exactly the documented arrays, and every document
# gives the same list in the order of the output: the class comment
# (vtkDeformableSurfaceFilter.h), the ParaView help (the proxy's XML documentation) and the
# README each say "point arrays A, B (what), ... and field data C, D, ... and, with the region
# force, E". Plain VTK Python (/usr/bin/python3).
import os
import re
import sys

from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.util.numpy_support import numpy_to_vtk
import numpy as np

from deformablesurface import vtkDeformableSurfaceFilter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ds_invariants  # noqa: E402

POINT_ARRAYS = {"Normals", "Displacement", "ExternalForce", "ErrorIndicator", "RefinementLevel", "VertexLabel"}
FIELD_ARRAYS = {"Sweeps", "Levels", "InitialSubdivisions", "FinalMeanCorrection", "SelfIntersections",
                "InitialSigma", "Sigma", "Converged", "StopReason", "WarmStart", "FrontLevels",
                "KeptApartLevels"}
REGION_FIELD = {"IntensityRange", "RegionWeight"}  # only with the region force
TABLE_COLUMNS = {"Sweep", "Level", "Sigma", "Vertices", "Triangles", "MeanCorrection", "MaxCorrection"}

n, c, r = 32, 15.5, 8.0
z, y, x = np.mgrid[0:n, 0:n, 0:n].astype(float)
values = 1.0 / (1.0 + np.exp(2.0 * (np.sqrt((x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2) - r)))
image = vtkImageData()
image.SetDimensions(n, n, n)
array = numpy_to_vtk(values.ravel().astype(np.float32), deep=1)
array.SetName("density")
image.GetPointData().SetScalars(array)
start = vtkSphereSource()
start.SetCenter(c, c, c)
start.SetRadius(11.0)

failures = []
for region in (0.0, 0.3):
    f = vtkDeformableSurfaceFilter()
    f.SetInputData(0, image)
    f.SetInitialSurfaceConnection(start.GetOutputPort())
    f.SetRegionWeight(region)
    ds_invariants.update_filter(f, "RegionWeight %g" % region)
    out = f.GetOutput()
    ds_invariants.check_surface(start.GetOutput(), out, "RegionWeight %g" % region)
    point_list = [out.GetPointData().GetArrayName(i) for i in range(out.GetPointData().GetNumberOfArrays())]
    field_list = [out.GetFieldData().GetArrayName(i) for i in range(out.GetFieldData().GetNumberOfArrays())]
    output_order = {"points": point_list, "field": field_list}  # the region-force run's, last
    points, field = set(point_list), set(field_list)
    table = f.GetConvergenceTable()
    columns = {table.GetColumnName(i) for i in range(table.GetNumberOfColumns())}
    expected_field = FIELD_ARRAYS | (REGION_FIELD if region > 0 else set())
    for what, got, want in (("point arrays", points, POINT_ARRAYS), ("field data", field, expected_field),
                            ("table columns", columns, TABLE_COLUMNS)):
        print("RegionWeight %g, %s: %s" % (region, what, sorted(got)))
        if got != want:
            failures.append("RegionWeight %g %s: extra %s, missing %s" % (region, what, sorted(got - want),
                                                                           sorted(want - got)))



def documented_lists(text):
    """(point arrays, field data, region-force field data) of the sentence "point arrays ...",
    in the document's order; explanations in parentheses, markup and line breaks ignored."""
    text = re.sub(r"\s+", " ", text.replace("`", "").replace("*", "").replace("///", ""))
    text = text[text.index("point arrays"):]
    while "(" in text:  # innermost parentheses first
        text = re.sub(r"\([^()]*\)", "", text)
    points, rest = text[len("point arrays"):].split(" field data ", 1)
    field, rest = rest.split("with the region force,", 1)
    names = lambda part: re.findall(r"\b[A-Z][A-Za-z]+\b", part)
    region = re.split(r";|\.|, and ", rest, maxsplit=1)[0]  # the list ends with its clause
    return names(points), names(field), names(region)


root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
documents = {"class comment": os.path.join(root, "Filters", "vtkDeformableSurfaceFilter.h"),
             "ParaView help (XML)": os.path.join(root, "xml", "DeformableSurface.xml"),
             "README": os.path.join(root, "README.md")}
for name, path in documents.items():
    with open(path) as f:
        text = f.read()
    if name.startswith("class"):
        text = text.replace(" * ", " ")
    lists = documented_lists(text)
    print("%s: %s" % (name, lists))
    want = (output_order["points"], [a for a in output_order["field"] if a not in REGION_FIELD], sorted(REGION_FIELD))
    if lists != want:
        failures.append("%s lists %s, the output has %s" % (name, lists, want))
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
