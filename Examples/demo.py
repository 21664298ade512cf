"""The main job of the README: segment the brain in a real MRI volume and write out the
surface, the convergence table and a picture, with the accuracy measured against the truth.

    xvfb-run -a pvbatch Examples/demo.py --plugin <DeformableSurface.so> --output out/

Data (Debian package mricron-data): the Colin27 T1 head template ch2.nii.gz (181x217x181,
1 mm, uint8) and ch2bet.nii.gz, the same brain skull-stripped (brain voxels keep their T1
value, everything else is 0).

The job: ParaView's Box source, sized to the image bounds, deforms onto the brain of
ch2bet - the paper's "brain from MRI" with an initial surface that needs no knowledge of
the object. The hierarchy does the work: at sigma = 1/6 of the volume extent the box
only feels the brain as a blob, each refinement halves sigma and lets the finer mesh
follow finer detail.

Every filter parameter is the default: the start box is split once (SubdivideInitialSurface)
to 48 triangles, and the levels run until sigma reaches its floor, 2/3 of the 1 mm voxel (from
sigma_0 = extent/6 = 32 mm: 7 levels), refined where the cortex has detail (~30 000 vertices).

Truth: the boundary of the brain mask (ch2bet > 0), the 0.5 iso-surface of that binary
volume. The numbers: distance of every surface vertex to it (how well the surface sits on
the boundary) and of every mask-boundary point to the surface (how much of the boundary
the smooth surface leaves out: the sulci it bridges), the enclosed volume against the mask
volume, and for comparison what an iso-surface of the same volume gives.

Output (in --output): brain_surface.vtp, brain_convergence.csv, brain.png, brain_summary.txt.
The .vtp files are written with inline (base64) data: Debian 12's expat (2.5.0+deb12u5)
cannot read VTK's raw appended XML data back (VTK issue 19258).
"""
import argparse
import os
import sys
import time

from paraview import servermanager
from paraview import simple

TEMPLATES = "/usr/share/mricron/templates"
BRAIN = os.path.join(TEMPLATES, "ch2bet.nii.gz")
HEAD = os.path.join(TEMPLATES, "ch2.nii.gz")

# The non-default filter properties of the job: none (see the module docstring).
SOLVER_SETTINGS = {}


def require_data():
    missing = [p for p in (BRAIN, HEAD) if not os.path.exists(p)]
    if missing:
        raise RuntimeError("missing %s: install the Debian package mricron-data "
                           "(scripts/install-deps.sh does)" % ", ".join(missing))


def load_plugin(path=None):
    path = path or os.environ.get("DS_PLUGIN")
    if path:
        simple.LoadPlugin(path)
    elif not hasattr(simple, "DeformableSurface"):
        simple.LoadDistributedPlugin("DeformableSurface")
    if not hasattr(simple, "DeformableSurface"):
        raise RuntimeError("DeformableSurface plugin not loaded: pass --plugin or set DS_PLUGIN")


# ParaView 5.11 has no reader for .nii.gz (its AnalyzeNIfTI plugin reads only plain .nii);
# the DeformableSurface plugin adds one (vtkDSNIFTIImageReader), which OpenDataFile picks. It
# places the image by its qform/sform: Colin27 in MNI coordinates (x -90..90, y -125..91,
# z -71..109 mm), and so the surfaces. The scalar array is called "NIFTI".
def nifti_source(path):
    reader = simple.OpenDataFile(path)
    if reader is None or reader.GetXMLName() != "DSNIfTIImageReader":
        raise RuntimeError("%s: the plugin's NIfTI reader did not open it" % path)
    return reader


def segment_brain(settings=None, inset=0.0):
    """The pipeline: ch2bet -> DeformableSurface(start = Box at the image bounds, shrunk by
    inset mm on every side). settings: filter properties (default SOLVER_SETTINGS). Returns a dict with the proxies, the fetched surface, table and image, and the time."""
    require_data()
    brain = nifti_source(BRAIN)
    brain.UpdatePipeline()
    b = brain.GetDataInformation().GetBounds()
    box = simple.Box(XLength=b[1] - b[0] - 2 * inset, YLength=b[3] - b[2] - 2 * inset,
                     ZLength=b[5] - b[4] - 2 * inset,
                     Center=[0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])])
    surface = simple.DeformableSurface(Input=brain, InitialSurface=box)
    surface.Scalars = ["POINTS", "NIFTI"]
    for name, value in (settings or SOLVER_SETTINGS).items():
        setattr(surface, name, value)
    t0 = time.time()
    surface.UpdatePipeline()
    seconds = time.time() - t0
    return {"brain": brain, "box": box, "surface": surface, "seconds": seconds,
            "polydata": servermanager.Fetch(surface, arg1=0),
            "table": servermanager.Fetch(surface, idx=1),
            "image": servermanager.Fetch(brain)}


# ---------------------------------------------------------------- the whole head

EXAMPLES = os.path.dirname(os.path.abspath(__file__))
ITK_DATA = "/usr/share/doc/insighttoolkit5-examples/examples/Data"

# Whole heads with their references. picks: ~40 points a user picked on a few slices, ~3 mm
# outside the brain; click: one point picked in the white matter. Both chosen on the image
# (never on the mask), in the world coordinates the plugin's reader gives (the file's
# qform/sform: MNI millimetres for Colin27). range: the IntensityRange a user gives with the click, read off the
# image by probing tissues: Colin27 CSF around the brain 41-55, cortex 78-91, white matter
# 108-117, skull marrow 145-166 -> midway between CSF and cortex, and between white matter and
# marrow; KmeansTest dark CSF and bone 1-45 (ventricles 13-21), cortex 70-85, white matter
# 104-112, marrow and fat 150-230 -> the same rule.
HEADS = {
    "colin27": {"label": "Colin27 (ch2.nii.gz, 181x217x181, 1 mm)",
                "image": HEAD, "mask": BRAIN,
                "picks": os.path.join(EXAMPLES, "colin27_picks.csv"),
                "click": os.path.join(EXAMPLES, "colin27_click.csv"),
                "range": [62.0, 130.0], "iso": 62.0},
    "kmeans": {"label": "ITK KmeansTest (128x128x62, 2x2x3 mm)",
               "image": os.path.join(ITK_DATA, "KmeansTest_T1UCharRaw.nii.gz"),
               "mask": os.path.join(ITK_DATA, "KmeansTest_T1RawSkullStrip.nii.gz"),
               "picks": os.path.join(EXAMPLES, "kmeans_picks.csv"),
               "click": os.path.join(EXAMPLES, "kmeans_click.csv"),
               "range": [48.0, 130.0], "iso": 48.0},
}

# The non-default filter properties per start, and why:
#   picks  none: the default region force (RegionWeight 0.3, its range estimated from inside
#          and just outside the seed) tells the brain from scalp and skull, whose edges are as
#          strong as its own (edge force alone: mean 2.2 mm, see the README).
#   click  RegionWeight 1 and the user's IntensityRange: the 5 mm seed sphere has to grow
#          ~65 mm through the brain, and one click says nothing about where the brain ends.
HEAD_SETTINGS = {"picks": {},
                 "click": {"RegionWeight": 1.0}}


def segment_head(case, start):
    """The whole-head pipeline: the head volume, the picked points from a CSV (CSV Reader ->
    Table To Points) -> Delaunay Seed Surface -> Deformable Surface. case: a key of HEADS;
    start: "picks" or "click". Returns the proxies, fetched data and the solve time."""
    head = HEADS[case]
    for path in (head["image"], head["mask"]):
        if not os.path.exists(path):
            raise RuntimeError("missing %s: scripts/install-deps.sh installs mricron-data and "
                               "insighttoolkit5-examples" % path)
    image = nifti_source(head["image"])
    image.UpdatePipeline()
    table = simple.CSVReader(FileName=[head[start]])
    points = simple.TableToPoints(Input=table, XColumn="x", YColumn="y", ZColumn="z")
    seed = simple.DelaunaySeedSurface(Input=points)
    seed.UpdatePipeline()
    surface = simple.DeformableSurface(Input=image, InitialSurface=seed)
    surface.Scalars = ["POINTS", "NIFTI"]
    for name, value in HEAD_SETTINGS[start].items():
        setattr(surface, name, value)
    if start == "click":
        surface.IntensityRange = head["range"]
    t0 = time.time()
    surface.UpdatePipeline()
    seconds = time.time() - t0
    return {"case": case, "start": start, "image_proxy": image, "points": points, "seed": seed,
            "surface": surface, "seconds": seconds,
            "polydata": servermanager.Fetch(surface, arg1=0),
            "table": servermanager.Fetch(surface, idx=1),
            "image": servermanager.Fetch(image),
            "seed_polydata": servermanager.Fetch(seed, arg1=0)}


def measure_head(result, iso=True):
    """measure() against the head's brain mask, the seed's own distance, and (iso) the
    iso-surface of the head at the CSF/cortex level for comparison."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    head = HEADS[result["case"]]
    m = measure(result, head["mask"], (head["iso"],) if iso else ())
    seed_points = vtk_to_numpy(result["seed_polydata"].GetPoints().GetData())
    m.update({"seed_" + k: v for k, v in _percentiles(_distances(result["truth"], seed_points)).items()})
    m["seed_volume"] = _volume(result["seed_polydata"])
    return m


def head_summary(case, runs):
    """Lines for one head: each start's numbers and the iso-surface."""
    lines = [HEADS[case]["label"] + ", brain mask boundary as the reference:"]
    for start, m in runs:
        lines.append(
            "  %-6s seed %.1f mm from the brain (mean; 95%% %.1f) -> %.2f s, %d levels, %d vertices, "
            "%d region(s), %d self-intersections; vertex -> mask boundary mean %.2f, 95%% %.2f, "
            "max %.1f mm; volume %+.1f%% of the mask's"
            % (start, m["seed_mean"], m["seed_p95"], m["seconds"], m["levels"], m["vertices"],
               m["regions"], m["self_intersections"], m["dist_mean"], m["dist_p95"], m["dist_max"],
               100.0 * (m["surface_volume"] / m["mask_volume"] - 1.0)))
    iso = runs[0][1]["iso"][0]
    lines.append("  iso-surface of the head at %g (vtkFlyingEdges3D): %d pieces, %d triangles; the "
                 "largest (%d triangles) lies %.1f mm from the brain on average (95%% %.1f)"
                 % (iso["value"], iso["regions"], iso["triangles"], iso["largest_triangles"],
                    iso["largest_dist_mean"], iso["largest_dist_p95"]))
    return lines


# ---------------------------------------------------------------- measuring (plain VTK)

def _percentiles(values):
    import numpy as np
    v = np.abs(np.asarray(values, dtype=float))
    return {"mean": float(v.mean()), "median": float(np.median(v)),
            "p95": float(np.percentile(v, 95)), "max": float(v.max())}


def _min_angles(polydata):
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkFiltersVerdict import vtkMeshQuality
    quality = vtkMeshQuality()
    quality.SetInputData(polydata)
    quality.SetTriangleQualityMeasureToMinAngle()
    quality.Update()
    angles = vtk_to_numpy(quality.GetOutput().GetCellData().GetArray("Quality"))
    return {"median": float(np.median(angles)), "p5": float(np.percentile(angles, 5)),
            "below10": float((angles < 10.0).mean())}


def _regions(polydata):
    from vtkmodules.vtkFiltersCore import vtkPolyDataConnectivityFilter
    connectivity = vtkPolyDataConnectivityFilter()
    connectivity.SetInputData(polydata)
    connectivity.SetExtractionModeToAllRegions()
    connectivity.Update()
    return connectivity.GetNumberOfExtractedRegions()


def _topology(polydata):
    from vtkmodules.vtkFiltersCore import vtkFeatureEdges
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    counts = {}
    for kind in ("Boundary", "NonManifold"):
        edges = vtkFeatureEdges()
        edges.SetInputData(polydata)
        edges.BoundaryEdgesOff()
        edges.FeatureEdgesOff()
        edges.ManifoldEdgesOff()
        edges.NonManifoldEdgesOff()
        getattr(edges, kind + "EdgesOn")()
        edges.Update()
        counts[kind] = edges.GetOutput().GetNumberOfLines()
    # Every edge once (E of the Euler characteristic V - E + F), from the triangle list.
    cells = vtk_to_numpy(polydata.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    pairs = np.sort(np.concatenate([cells[:, [0, 1]], cells[:, [1, 2]], cells[:, [2, 0]]]), axis=1)
    n_edges = len(np.unique(pairs, axis=0))
    euler = polydata.GetNumberOfPoints() - n_edges + polydata.GetNumberOfPolys()
    return {"boundary_edges": counts["Boundary"], "nonmanifold_edges": counts["NonManifold"],
            "euler": euler, "regions": _regions(polydata)}


def _volume(polydata):
    from vtkmodules.vtkFiltersCore import vtkMassProperties
    mass = vtkMassProperties()
    mass.SetInputData(polydata)
    mass.Update()
    return mass.GetVolume()


def _iso_surface(image, value):
    from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
    iso = vtkFlyingEdges3D()
    iso.SetInputData(image)
    iso.SetValue(0, value)
    iso.ComputeNormalsOff()
    iso.ComputeGradientsOff()
    iso.Update()
    return iso.GetOutput()


def _distances(polydata, points):
    """Signed distance (negative inside) of each point to the closed surface polydata."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.vtkFiltersCore import vtkImplicitPolyDataDistance
    distance = vtkImplicitPolyDataDistance()
    distance.SetInput(polydata)
    values = vtkDoubleArray()
    distance.FunctionValue(numpy_to_vtk(np.ascontiguousarray(points, dtype=float), deep=1), values)
    return vtk_to_numpy(values).copy()


def _read_nifti(path):
    """A NIfTI volume read in plain VTK with the plugin's reader class (the reference masks:
    scored against, never fed to the filter)."""
    from deformablesurface import vtkDSNIFTIImageReader
    reader = vtkDSNIFTIImageReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def measure(result, mask_path=None, iso_values=(0.5, 40.0)):
    """Accuracy against the mask boundary (mask_path > 0, or the image itself > 0 for the
    skull-stripped ch2bet), mesh quality and topology of the surface, and the same statistics
    for iso-surfaces of the volume. Returns a flat dict of numbers."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkFiltersCore import vtkTriangleFilter

    surface = result["polydata"]
    image = result["image"]
    reference = _read_nifti(mask_path) if mask_path else image
    t1 = vtk_to_numpy(reference.GetPointData().GetScalars())
    mask = vtkImageData()
    mask.CopyStructure(image)
    mask.GetPointData().SetScalars(numpy_to_vtk((t1 > 0).astype(np.float32), deep=1))
    truth = _iso_surface(mask, 0.5)
    result["truth"] = truth

    # Vertices -> mask boundary: every vertex. Mask boundary -> surface: every 8th point of
    # the 0.5 iso-surface (~44k of 355k; the statistics are the same, the time is 1/8).
    to_truth = _distances(truth, vtk_to_numpy(surface.GetPoints().GetData()))
    to_surface = _distances(surface, vtk_to_numpy(truth.GetPoints().GetData())[::8])
    # The surface with its signed distance (mm, negative inside the mask) as a point array:
    # what the picture colours by and what brain_surface.vtp carries.
    annotated = surface.NewInstance()
    annotated.ShallowCopy(surface)
    signed = numpy_to_vtk(to_truth, deep=1)
    signed.SetName("DistanceToMask")
    annotated.GetPointData().AddArray(signed)
    result["annotated"] = annotated

    fd = surface.GetFieldData()
    m = {"seconds": result["seconds"],
         "levels": int(fd.GetArray("Levels").GetTuple1(0)),
         "sweeps": int(fd.GetArray("Sweeps").GetTuple1(0)),
         "final_sigma": fd.GetArray("Sigma").GetTuple1(0),
         "self_intersections": int(fd.GetArray("SelfIntersections").GetTuple1(0)),
         "vertices": surface.GetNumberOfPoints(), "triangles": surface.GetNumberOfPolys(),
         "mask_volume": float((t1 > 0).sum()) * np.prod(image.GetSpacing()),
         "surface_volume": _volume(surface),
         "dist_signed_mean": float(to_truth.mean())}
    m.update({"dist_" + k: v for k, v in _percentiles(to_truth).items()})
    m.update({"back_" + k: v for k, v in _percentiles(to_surface).items()})
    m.update({"angle_" + k: v for k, v in _min_angles(surface).items()})
    m.update(_topology(surface))

    # What an iso-surface of the same volume gives: the mask boundary itself (ch2bet > 0:
    # every stray voxel of the skull stripping is a fragment) and a T1 level between CSF
    # and grey matter.
    m["iso"] = []
    for value in iso_values:
        iso = _iso_surface(image, value)
        triangles = vtkTriangleFilter()
        triangles.SetInputData(iso)
        triangles.Update()
        stats = {"value": value, "triangles": iso.GetNumberOfPolys(), "regions": _regions(iso)}
        stats.update({"angle_" + k: v for k, v in _min_angles(triangles.GetOutput()).items()})
        if mask_path:
            # The piece a user would keep: the largest; how far it lies from the brain.
            largest = _largest_region(iso)
            stats["largest_triangles"] = largest.GetNumberOfPolys()
            points = vtk_to_numpy(largest.GetPoints().GetData())[::16]
            stats.update({"largest_dist_" + k: v
                          for k, v in _percentiles(_distances(truth, points)).items()})
        m["iso"].append(stats)
    return m


def _largest_region(polydata):
    from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkPolyDataConnectivityFilter
    connectivity = vtkPolyDataConnectivityFilter()
    connectivity.SetInputData(polydata)
    connectivity.SetExtractionModeToLargestRegion()
    clean = vtkCleanPolyData()  # only the region's own points
    clean.SetInputConnection(connectivity.GetOutputPort())
    clean.Update()
    return clean.GetOutput()


def summary(m):
    lines = [
        "Colin27 brain (ch2bet.nii.gz, 181x217x181, 1 mm) from the box around the volume",
        "  solve            %.2f s, %d levels, %d sweeps, final sigma %.2f mm"
        % (m["seconds"], m["levels"], m["sweeps"], m["final_sigma"]),
        "  surface          %d vertices, %d triangles, %d region(s), Euler characteristic %d,"
        " %d boundary / %d non-manifold edges, %d self-intersections"
        % (m["vertices"], m["triangles"], m["regions"], m["euler"], m["boundary_edges"],
           m["nonmanifold_edges"], m["self_intersections"]),
        "  vertex -> mask boundary   mean %.2f  median %.2f  95%% %.2f  max %.2f mm"
        "  (signed mean %+.2f: inside is negative)"
        % (m["dist_mean"], m["dist_median"], m["dist_p95"], m["dist_max"], m["dist_signed_mean"]),
        "  mask boundary -> surface  mean %.2f  median %.2f  95%% %.2f  max %.2f mm"
        "  (the sulci the smooth surface bridges)"
        % (m["back_mean"], m["back_median"], m["back_p95"], m["back_max"]),
        "  enclosed volume  %.0f cm3 (mask %.0f cm3, %+.1f%%)"
        % (m["surface_volume"] / 1000.0, m["mask_volume"] / 1000.0,
           100.0 * (m["surface_volume"] / m["mask_volume"] - 1.0)),
        "  triangle min angle  median %.1f deg, 5th percentile %.1f deg, %.2f%% below 10 deg"
        % (m["angle_median"], m["angle_p5"], 100.0 * m["angle_below10"]),
        "iso-surfaces of the same volume (vtkFlyingEdges3D):"]
    for iso in m["iso"]:
        lines.append("  ch2bet = %-4g     %d triangles, %d regions, min angle median %.1f deg,"
                     " %.1f%% below 10 deg"
                     % (iso["value"], iso["triangles"], iso["regions"], iso["angle_median"],
                        100.0 * iso["angle_below10"]))
    return "\n".join(lines)


# ---------------------------------------------------------------- picture

def _caption(view, text, location="Upper Left Corner"):
    label = simple.Text(Text=text)
    display = simple.Show(label, view)
    display.WindowLocation = location
    display.FontSize = 11
    display.Justification = "Left"
    display.Color = [0.9, 0.9, 0.9]


def _centre(proxy):
    """The centre of a source's bounds (the NIfTI reader places images where their file says:
    Colin27 in MNI coordinates), so pictures are set up relative to the head."""
    proxy.UpdatePipeline()
    b = proxy.GetDataInformation().GetBounds()
    return [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]


def _at(c, dx, dy, dz):
    return [c[0] + dx, c[1] + dy, c[2] + dz]


def _distance_mesh(producer, view, limit, title, c):
    """The surface in 3-D in `view`, with edges, coloured by DistanceToMask in [-limit, limit]
    with a horizontal colour bar, seen from the left front above the brain."""
    mesh = simple.Show(producer, view)
    mesh.SetRepresentationType("Surface With Edges")
    mesh.EdgeColor = [0.25, 0.25, 0.3]
    simple.ColorBy(mesh, ("POINTS", "DistanceToMask"))
    lut = simple.GetColorTransferFunction("DistanceToMask")
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(-limit, limit)
    mesh.SetScalarBarVisibility(view, True)
    bar = simple.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.RangeLabelFormat = "%.0f"
    bar.Orientation = "Horizontal"
    bar.WindowLocation = "Lower Center"
    bar.ScalarBarLength = 0.5
    bar.TitleFontSize = bar.LabelFontSize = 12
    view.CameraFocalPoint = _at(c, 0.0, 0.0, -10.0)
    view.CameraPosition = _at(c, -420.0, -258.0, 170.0)
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 24
    view.ResetCamera(False)
    view.CameraPosition = [f + 0.85 * (p - f) for p, f in zip(view.CameraPosition, view.CameraFocalPoint)]


def _two_views(name):
    """A layout of two render views side by side, dark, without orientation axes."""
    layout = simple.CreateLayout(name)
    left = simple.CreateView("RenderView")
    right = simple.CreateView("RenderView")
    simple.AssignViewToLayout(view=left, layout=layout, hint=0)
    simple.AssignViewToLayout(view=right, layout=layout, hint=0)
    for view in (left, right):
        view.OrientationAxesVisibility = 0
        view.UseColorPaletteForBackground = 0
        view.Background = [0.06, 0.06, 0.08]
    return layout, left, right


def _grey_slice(image, origin, normal, view, top):
    """The image's plane through origin, its own greys (0..top), unlit."""
    cut = simple.Slice(Input=image)
    cut.SliceType = "Plane"
    cut.SliceType.Origin, cut.SliceType.Normal = origin, normal
    shown = simple.Show(cut, view)
    simple.ColorBy(shown, ("POINTS", "NIFTI"))
    grey = simple.GetColorTransferFunction("NIFTI")
    grey.ApplyPreset("Grayscale", True)
    grey.RescaleTransferFunction(0.0, top)
    shown.SetScalarBarVisibility(view, False)
    shown.Ambient, shown.Diffuse = 1.0, 0.0


def _trace(surface, origin, normal, view, colour):
    """Where the surface cuts the plane: a thick line, one unit in front of the slice."""
    trace = simple.Slice(Input=surface)
    trace.SliceType = "Plane"
    trace.SliceType.Origin, trace.SliceType.Normal = origin, normal
    line = simple.Show(trace, view)
    line.ColorArrayName = ["POINTS", ""]
    line.AmbientColor = line.DiffuseColor = colour
    line.Ambient, line.Diffuse = 1.0, 0.0
    line.LineWidth = 3.0
    line.Position = [-n for n in normal]


def render(result, png, size=(1600, 800), metrics=None):
    """Left: a sagittal slice of the full head T1 (ch2.nii.gz) with the line where the
    surface cuts it. Right: the surface mesh coloured by its distance to the mask boundary."""
    head = nifti_source(HEAD)
    surface = simple.TrivialProducer(registrationName="brain surface")
    surface.GetClientSideObject().SetOutput(result["annotated"])
    surface.UpdatePipeline()
    layout, left, right = _two_views("brain")

    # Left: a parasagittal plane through the left hemisphere, the surface's trace on it.
    c = _centre(head)
    x = c[0] - 20.0
    _grey_slice(head, [x, c[1], c[2]], [1.0, 0.0, 0.0], left, 130.0)
    _trace(surface, [x, c[1], c[2]], [1.0, 0.0, 0.0], left, [1.0, 0.55, 0.1])
    left.CameraFocalPoint = [x, c[1], c[2]]
    left.CameraPosition = _at(c, -490.0, 0.0, 0.0)
    left.CameraViewUp = [0.0, 0.0, 1.0]
    left.CameraParallelProjection = 1
    left.ResetCamera(False)
    left.CameraParallelScale = 116.0

    # Right: the mesh in 3-D, coloured by the signed distance to the mask boundary.
    _distance_mesh(surface, right, 2.0, "distance to the mask boundary (mm)", c)
    # Lift the brain clear of the colour bar.
    right.CameraPosition = [right.CameraPosition[0], right.CameraPosition[1], right.CameraPosition[2] - 14.0]
    right.CameraFocalPoint = [right.CameraFocalPoint[0], right.CameraFocalPoint[1],
                              right.CameraFocalPoint[2] - 14.0]

    _caption(left, "Colin27 T1 head (ch2.nii.gz), sagittal slice x = %g mm (MNI)\n"
                   "orange: where the deformable surface cuts it" % x)
    if metrics:
        _caption(right, "from the box around the volume: %.1f s, %d levels\n"
                        "%d vertices, one closed surface, %d self-intersections\n"
                        "vertex to mask boundary: mean %.2f mm, 95%% %.2f mm"
                 % (metrics["seconds"], metrics["levels"], metrics["vertices"],
                    metrics["self_intersections"], metrics["dist_mean"], metrics["dist_p95"]))
    simple.SaveScreenshot(png, layout, ImageResolution=list(size))
    return png


def render_head(picks, click, png, metrics, size=(1600, 800)):
    """Left: a coronal slice of the head with the traces of both surfaces (orange: from the
    picked points, which are drawn where they lie near the slice; cyan: from one click). Right:
    the surface from the picks in 3-D, coloured by its distance to the mask boundary."""
    annotated = simple.TrivialProducer(registrationName="surface from the picks")
    annotated.GetClientSideObject().SetOutput(picks["annotated"])
    annotated.UpdatePipeline()
    layout, left, right = _two_views("head")

    c = _centre(picks["image_proxy"])
    y = c[1] + 2.0  # the coronal slice the user picked on
    plane = ([c[0], y, c[2]], [0.0, 1.0, 0.0])
    _grey_slice(picks["image_proxy"], plane[0], plane[1], left, 140.0)
    for result, colour in ((picks, [1.0, 0.55, 0.1]), (click, [0.2, 0.85, 1.0])):
        _trace(result["surface"], plane[0], plane[1], left, colour)
    near = simple.Clip(Input=picks["points"], ClipType="Plane", Invert=0, Crinkleclip=0)
    near.ClipType.Origin, near.ClipType.Normal = [c[0], y - 1.0, c[2]], [0.0, 1.0, 0.0]
    near = simple.Clip(Input=near, ClipType="Plane", Invert=1)
    near.ClipType.Origin, near.ClipType.Normal = [c[0], y + 1.0, c[2]], [0.0, 1.0, 0.0]
    dots = simple.Show(near, left)
    dots.SetRepresentationType("Points")
    dots.PointSize = 9.0
    dots.RenderPointsAsSpheres = 1
    dots.ColorArrayName = ["POINTS", ""]
    dots.AmbientColor = dots.DiffuseColor = [1.0, 0.2, 0.2]
    dots.Position = [0.0, -2.0, 0.0]
    left.CameraFocalPoint = [c[0], y, c[2]]
    left.CameraPosition = _at(c, 0.0, -508.0, 0.0)
    left.CameraViewUp = [0.0, 0.0, 1.0]
    left.CameraParallelProjection = 1
    left.ResetCamera(False)
    left.CameraParallelScale = 100.0

    _distance_mesh(annotated, right, 3.0, "distance to the brain-mask boundary (mm)", c)

    mp, mc = metrics["picks"], metrics["click"]
    _caption(left, "Colin27 whole head (ch2.nii.gz), coronal slice y = %g mm (MNI)\n"
                   "red: picked points near this slice\n"
                   "orange: surface from %d picked points (mean %.2f mm from the brain)\n"
                   "cyan: surface from one click (mean %.2f mm)"
             % (y, picks["points"].GetDataInformation().GetNumberOfPoints(), mp["dist_mean"],
                mc["dist_mean"]))
    _caption(right, "from the picked points: %.1f s, %d vertices, one closed surface,\n"
                    "%d self-intersections; 95%% of vertices within %.1f mm of the brain"
             % (mp["seconds"], mp["vertices"], mp["self_intersections"], mp["dist_p95"]))
    simple.SaveScreenshot(png, layout, ImageResolution=list(size))
    return png


# ---------------------------------------------------------------- main

def _write_polydata(polydata, path):
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(polydata)
    writer.SetDataModeToBinary()  # inline base64: readable with Debian 12's expat (see top)
    writer.SetCompressorTypeToZLib()
    if not writer.Write():
        raise RuntimeError("could not write " + path)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--plugin", help="path of DeformableSurface.so (default: $DS_PLUGIN)")
    parser.add_argument("--output", default="out", help="output folder (default: out)")
    parser.add_argument("--no-picture", action="store_true", help="skip the PNG")
    parser.add_argument("--skull-stripped", action="store_true",
                        help="the easy case instead: ch2bet.nii.gz from the box around the volume")
    parser.add_argument("--size", type=int, nargs=2, default=[1600, 800], metavar=("W", "H"),
                        help="picture size in pixels (default: 1600 800)")
    args = parser.parse_args(argv)
    try:
        require_data()
    except RuntimeError as error:
        sys.exit("demo: %s" % error)
    os.makedirs(args.output, exist_ok=True)
    from vtkmodules.vtkCommonCore import vtkLogger
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_WARNING)  # not VTK's INFO chatter
    load_plugin(args.plugin)

    if args.skull_stripped:
        return skull_stripped_job(args)
    texts, results = [], {}
    for case in HEADS:
        runs = []
        for start in ("picks", "click"):
            result = segment_head(case, start)
            results[(case, start)] = (result, measure_head(result))
            runs.append((start, results[(case, start)][1]))
        texts.extend(head_summary(case, runs))
    text = "\n".join(texts)
    print(text)

    written = []
    for start in ("picks", "click"):
        result = results[("colin27", start)][0]
        vtp = os.path.join(args.output, "head_brain_%s.vtp" % start)
        _write_polydata(result["annotated"], vtp)
        csv = os.path.join(args.output, "head_convergence_%s.csv" % start)
        simple.SaveData(csv, proxy=simple.OutputPort(result["surface"], 1))
        written += [vtp, csv]
    with open(os.path.join(args.output, "head_summary.txt"), "w") as f:
        f.write(text + "\n")
    written.append(os.path.join(args.output, "head_summary.txt"))
    if not args.no_picture:
        metrics = {start: results[("colin27", start)][1] for start in ("picks", "click")}
        written.append(render_head(results[("colin27", "picks")][0], results[("colin27", "click")][0],
                                   os.path.join(args.output, "head.png"), metrics, args.size))
    for path in written:
        print("wrote", path)
    return results


def skull_stripped_job(args):
    """The easy case: ch2bet (skull-stripped) from the box around the volume."""
    result = segment_brain()
    metrics = measure(result)
    text = summary(metrics)
    print(text)

    vtp = os.path.join(args.output, "brain_surface.vtp")
    _write_polydata(result["annotated"], vtp)
    csv = os.path.join(args.output, "brain_convergence.csv")
    simple.SaveData(csv, proxy=simple.OutputPort(result["surface"], 1))
    with open(os.path.join(args.output, "brain_summary.txt"), "w") as f:
        f.write(text + "\n")
    written = [vtp, csv, os.path.join(args.output, "brain_summary.txt")]
    if not args.no_picture:
        written.append(render(result, os.path.join(args.output, "brain.png"), args.size, metrics))
    for path in written:
        print("wrote", path)
    return metrics


if __name__ == "__main__":
    main(sys.argv[1:])
