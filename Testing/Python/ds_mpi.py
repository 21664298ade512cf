# SPDX-License-Identifier: BSD-3-Clause
"""Helpers for the mpi_*.py tests (run under `mpiexec -n 2 pvbatch`): what each rank holds of a
proxy's output, and the errors its filter reports; start_ranks loads the plugin. The script runs on
rank 0; the other ranks serve the proxies."""
import os

from paraview import servermanager, simple
from paraview.modules.vtkRemotingCore import vtkProcessModule
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING


def start_ranks():
    """Loads the plugin (DS_PLUGIN) and returns the number of ranks (at least 2)."""
    simple.LoadPlugin(os.environ["DS_PLUGIN"])
    n_ranks = vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
    print("ranks:", n_ranks)
    assert n_ranks >= 2, "run this test under mpiexec with at least 2 processes"
    return n_ranks


# One vertex per rank carrying that rank's sizes (points/cells, or rows/columns of a table);
# Fetch appends them on rank 0.
PER_RANK = """
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkCommonCore import vtkPoints, vtkIntArray
from vtkmodules.vtkCommonDataModel import vtkCellArray
c = vtkMultiProcessController.GetGlobalController()
inp = self.GetInputDataObject(0, 0)
out = self.GetOutputDataObject(0)
p = vtkPoints()
p.InsertNextPoint(0, 0, 0)
out.SetPoints(p)
verts = vtkCellArray()
verts.InsertNextCell(1)
verts.InsertCellPoint(0)
out.SetVerts(verts)
dataset = inp.IsA("vtkDataSet")
for name, v in (("Rank", c.GetLocalProcessId()),
                ("Points", inp.GetNumberOfPoints() if dataset else inp.GetNumberOfRows()),
                ("Cells", inp.GetNumberOfCells() if dataset else inp.GetNumberOfColumns())):
    a = vtkIntArray()
    a.SetName(name)
    a.InsertNextValue(v)
    out.GetPointData().AddArray(a)
"""


def per_rank(proxy, port=0):
    """{rank: (points, cells)} of what each rank holds of proxy's output `port`. It updates the
    pipeline on every rank, so it also proves that no rank is left waiting."""
    reporter = simple.ProgrammableFilter(Input=simple.OutputPort(proxy, port),
                                         OutputDataSetType="vtkPolyData", Script=PER_RANK)
    data = servermanager.Fetch(reporter)
    pd = data.GetPointData()
    result = {}
    for i in range(data.GetNumberOfPoints()):
        result[int(pd.GetArray("Rank").GetValue(i))] = (
            int(pd.GetArray("Points").GetValue(i)), int(pd.GetArray("Cells").GetValue(i)))
    simple.Delete(reporter)
    return result


class Errors:
    """The error messages proxy's filter reports on this rank (rank 0, where the script runs)."""

    def __init__(self, proxy):
        self.errors = []
        proxy.GetClientSideObject().AddObserver("ErrorEvent", self.on_error)

    @calldata_type(VTK_STRING)
    def on_error(self, obj, event, text):
        self.errors.append(text)
