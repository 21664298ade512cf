# SPDX-License-Identifier: BSD-3-Clause
"""Segment the brain in a whole-head MRI: the job of ./scripts/demo.sh (the README's picture).

    xvfb-run -a pvbatch Examples/demo.py --plugin <DeformableSurface.so> --output out/

(`./scripts/demo.sh` builds the plugin and runs this.) The volume is the Colin27 T1 head,
/usr/share/mricron/templates/ch2.nii.gz (Debian package mricron-data). Two starts, both chosen
on the image as a user would:

- picks: the points of Examples/colin27_picks.csv, clicked on six slices ~3 mm outside the
  brain -> Delaunay Seed Surface -> Deformable Surface with every default;
- click: the one point of Examples/colin27_click.csv, in the white matter -> a 5 mm seed
  sphere -> Deformable Surface with the brain's IntensityRange (a click so given pulls with
  RegionWeight 1).

The same two runs are made on ITK's KmeansTest head (insighttoolkit5-examples). Each surface is
scored against the boundary of its brain mask, which the filter never sees (Examples/ds_scoring.py).

Writes into --output: head_brain_picks.vtp and head_brain_click.vtp (the Colin27 surfaces, with
their signed distance to the mask boundary as the point array DistanceToMask),
head_convergence_picks.csv and head_convergence_click.csv (one row per sweep),
head_summary.txt (the numbers of both heads) and head.png (the picture).
--skull-stripped runs the easy case instead: the skull-stripped ch2bet.nii.gz from a box around
the volume, every default, writing brain_surface.vtp, brain_convergence.csv, brain_summary.txt
and brain.png.

The .vtp files have inline (base64) data: Debian 12's expat cannot read VTK's raw appended
XML data back (VTK issue 19258).
"""
import argparse
import os
import sys
import time

from paraview import servermanager
from paraview import simple

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ds_scoring  # noqa: E402
from ds_scoring import HEADS, require_data  # noqa: E402,F401 (require_data: for the tests)

# The filter properties each start sets; everything else is default. The picks need none: the
# region force (on by default) estimates the brain's intensities from inside and just outside
# the seed. One click says nothing about where the brain ends: the user gives the range read
# off the image (HEADS), through which the region force grows the 5 mm sphere (a click given
# its range pulls with RegionWeight 1, the default 0.3 being for starts near their object).
HEAD_SETTINGS = {"picks": {}, "click": {}}


def load_plugin(path=None):
    path = path or os.environ.get("DS_PLUGIN")
    if path:
        simple.LoadPlugin(path)
    elif not hasattr(simple, "DeformableSurface"):
        simple.LoadDistributedPlugin("DeformableSurface")
    if not hasattr(simple, "DeformableSurface"):
        raise RuntimeError("DeformableSurface plugin not loaded: pass --plugin or set DS_PLUGIN")


def nifti_source(path):
    """OpenDataFile picks the plugin's NIfTI reader (ParaView 5.11 has none for .nii.gz); it
    places the image where the file says (Colin27 in MNI millimetres); its array is NIFTI."""
    reader = simple.OpenDataFile(path)
    if reader is None or reader.GetXMLName() != "DSNIfTIImageReader":
        raise RuntimeError("%s: the plugin's NIfTI reader did not open it" % path)
    return reader


def solve(surface, settings):
    """Sets the properties, runs the filter, returns the seconds it took."""
    surface.Scalars = ["POINTS", "NIFTI"]
    for name, value in settings.items():
        setattr(surface, name, value)
    t0 = time.time()
    surface.UpdatePipeline()
    return time.time() - t0


def segment_head(case, start):
    """CSV Reader -> Table To Points -> Delaunay Seed Surface -> Deformable Surface on the head
    HEADS[case] from its "picks" or its "click". Returns the proxies, the fetched data and the
    solve time."""
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
    settings = dict(HEAD_SETTINGS[start], **({"IntensityRange": head["range"]} if start == "click" else {}))
    seconds = solve(surface, settings)
    return {"case": case, "start": start, "image_proxy": image, "points": points, "seed": seed,
            "surface": surface, "seconds": seconds,
            "polydata": servermanager.Fetch(surface, arg1=0),
            "table": servermanager.Fetch(surface, idx=1),
            "image": servermanager.Fetch(image),
            "seed_polydata": servermanager.Fetch(seed, arg1=0)}


def segment_brain(settings=None, inset=0.0):
    """The easy case: ch2bet -> Deformable Surface from a Box at the image bounds (shrunk by inset
    mm on every side), every default unless settings say otherwise."""
    require_data()
    brain = nifti_source(ds_scoring.BRAIN)
    brain.UpdatePipeline()
    b = brain.GetDataInformation().GetBounds()
    box = simple.Box(XLength=b[1] - b[0] - 2 * inset, YLength=b[3] - b[2] - 2 * inset,
                     ZLength=b[5] - b[4] - 2 * inset,
                     Center=[0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])])
    surface = simple.DeformableSurface(Input=brain, InitialSurface=box)
    seconds = solve(surface, settings or {})
    return {"brain": brain, "box": box, "surface": surface, "seconds": seconds,
            "polydata": servermanager.Fetch(surface, arg1=0),
            "table": servermanager.Fetch(surface, idx=1),
            "image": servermanager.Fetch(brain)}


def write_outputs(result, vtp, csv):
    """The surface with DistanceToMask (inline data, readable with Debian 12's expat) and the
    convergence table."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(vtp)
    writer.SetInputData(result["annotated"])
    writer.SetDataModeToBinary()
    writer.SetCompressorTypeToZLib()
    if not writer.Write():
        raise RuntimeError("could not write " + vtp)
    simple.SaveData(csv, proxy=simple.OutputPort(result["surface"], 1))
    return [vtp, csv]


def head_job(args):
    """Both heads from both starts; the Colin27 surfaces, tables and picture written."""
    import ds_pictures
    texts, results = [], {}
    for case in HEADS:
        for start in ("picks", "click"):
            result = segment_head(case, start)
            results[(case, start)] = (result, ds_scoring.measure_head(result))
        texts.extend(ds_scoring.head_summary(case, [(s, results[(case, s)][1]) for s in ("picks", "click")]))
    text = "\n".join(texts)
    print(text)
    written = []
    for start in ("picks", "click"):
        written += write_outputs(results[("colin27", start)][0],
                                 os.path.join(args.output, "head_brain_%s.vtp" % start),
                                 os.path.join(args.output, "head_convergence_%s.csv" % start))
    written.append(os.path.join(args.output, "head_summary.txt"))
    with open(written[-1], "w") as f:
        f.write(text + "\n")
    if not args.no_picture:
        metrics = {start: results[("colin27", start)][1] for start in ("picks", "click")}
        written.append(ds_pictures.render_head(results[("colin27", "picks")][0], results[("colin27", "click")][0],
                                               os.path.join(args.output, "head.png"), metrics, args.size))
    return results, written


def skull_stripped_job(args):
    """The easy case: ch2bet (skull-stripped) from the box around the volume."""
    import ds_pictures
    result = segment_brain()
    metrics = ds_scoring.measure(result)
    text = ds_scoring.summary(metrics)
    print(text)
    written = write_outputs(result, os.path.join(args.output, "brain_surface.vtp"),
                            os.path.join(args.output, "brain_convergence.csv"))
    written.append(os.path.join(args.output, "brain_summary.txt"))
    with open(written[-1], "w") as f:
        f.write(text + "\n")
    if not args.no_picture:
        written.append(ds_pictures.render(result, os.path.join(args.output, "brain.png"), args.size, metrics))
    return metrics, written


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
    results, written = (skull_stripped_job if args.skull_stripped else head_job)(args)
    for path in written:
        print("wrote", path)
    return results


if __name__ == "__main__":
    main(sys.argv[1:])
