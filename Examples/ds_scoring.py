# SPDX-License-Identifier: BSD-3-Clause
"""Scoring the demo's surfaces: the whole-head cases with their reference masks, and the
numbers the demo, the tests and the benchmarks report (distance of every vertex to the mask
boundary, enclosed volume, mesh quality and topology, and what an iso-surface of the same
volume gives). Plain VTK: runs in pvpython, pvbatch and /usr/bin/python3 alike.

The masks are references only: they score a surface, the filter never sees them."""
import os

TEMPLATES = "/usr/share/mricron/templates"
BRAIN = os.path.join(TEMPLATES, "ch2bet.nii.gz")  # Colin27 skull-stripped: brain voxels keep their T1
HEAD = os.path.join(TEMPLATES, "ch2.nii.gz")      # Colin27 T1 whole head, 181x217x181, 1 mm
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



def require_data():
    """Raises RuntimeError naming the missing Colin27 volumes (Debian package mricron-data)."""
    missing = [p for p in (BRAIN, HEAD) if not os.path.exists(p)]
    if missing:
        raise RuntimeError("missing %s: install the Debian package mricron-data "
                           "(scripts/install-deps.sh does)" % ", ".join(missing))


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


def read_nifti(path):
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
    reference = read_nifti(mask_path) if mask_path else image
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
