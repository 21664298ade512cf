# SPDX-License-Identifier: BSD-3-Clause
"""The one-click workflow on a DICOM folder, as a user runs it in pvpython: the Colin27 head
(ch2.nii.gz) written as a JPEG 2000-compressed DICOM series (one file per slice, GDCM's writer,
by the test tool DICOMFromNIfTI), opened with OpenDataFile on the folder after LoadPlugin (the
plugin's DICOM Series Reader), one click in the white matter (Examples/colin27_click.csv) ->
Table To Points -> Delaunay Seed Surface -> Deformable Surface with the README's region force
(IntensityRange 62-130, so RegionWeight 1). The surface must be closed, and the same as the one the
plugin's NIfTI reader gives for the NIfTI file: the DICOM image has its voxels and its place.
Skipped (exit 77) when the plugin was built without GDCM (no DS_DICOM_FROM_NIFTI)."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager  # noqa: E402
from paraview.simple import CSVReader, LoadPlugin, OpenDataFile, TableToPoints  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

import ds_invariants  # noqa: E402

converter = os.environ.get("DS_DICOM_FROM_NIFTI")
if not converter:
    print("built without GDCM: no DICOM reader to test")
    sys.exit(77)
HEAD = "/usr/share/mricron/templates/ch2.nii.gz"
CLICK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples", "colin27_click.csv")
folder = os.path.join(os.environ.get("DS_TEST_OUTPUT", "."), "dicom_one_click", "colin27")
subprocess.run(["rm", "-rf", folder], check=True)
subprocess.run([converter, HEAD, folder, "jpeg2000"], check=True)

LoadPlugin(os.environ["DS_PLUGIN"], ns=globals())


def one_click(path):
    """The workflow on one volume; returns (image, surface, seed) as fetched data."""
    volume = OpenDataFile(path)
    points = TableToPoints(Input=CSVReader(FileName=[CLICK]), XColumn="x", YColumn="y", ZColumn="z")
    seed = DelaunaySeedSurface(Input=points)  # noqa: F821 (from LoadPlugin)
    surface = DeformableSurface(Input=volume, InitialSurface=seed)  # noqa: F821
    surface.IntensityRange = [62.0, 130.0]
    surface.UpdatePipeline()
    return volume, servermanager.Fetch(volume), servermanager.Fetch(surface, arg1=0), \
        servermanager.Fetch(seed, arg1=0)


reader, dicom, surface, seed = one_click(folder)
print("OpenDataFile(folder) ->", reader.GetXMLName(), dicom.GetDimensions(), dicom.GetScalarTypeAsString())
assert reader.GetXMLName() == "DSDICOMSeriesReader", reader.GetXMLName()
facts = ds_invariants.check_surface(seed, surface, "one click on the DICOM folder")
assert facts["triangles"] > 1000 and facts["edges_not_twice"] == 0, facts

_, nifti, nifti_surface, _ = one_click(HEAD)
assert dicom.GetDimensions() == nifti.GetDimensions(), (dicom.GetDimensions(), nifti.GetDimensions())
assert (vtk_to_numpy(dicom.GetPointData().GetScalars()) == vtk_to_numpy(nifti.GetPointData().GetScalars())).all()
place = max([abs(a - b) for a, b in zip(dicom.GetOrigin(), nifti.GetOrigin())] +
            [abs(dicom.GetDirectionMatrix().GetElement(i, j) - nifti.GetDirectionMatrix().GetElement(i, j))
             for i in range(3) for j in range(3)])
print("DICOM vs NIfTI: voxels equal, largest placement difference %.3g" % place)
assert place < 1e-4, place
a = vtk_to_numpy(surface.GetPoints().GetData())
b = vtk_to_numpy(nifti_surface.GetPoints().GetData())
print("surfaces: %d and %d points" % (len(a), len(b)))
assert a.shape == b.shape, (a.shape, b.shape)
print("largest distance between their points: %.3g mm" % abs(a - b).max())
assert abs(a - b).max() < 1e-3, abs(a - b).max()
