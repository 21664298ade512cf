# SPDX-License-Identifier: BSD-3-Clause
"""Where the heads' clicks end for a given cap of sweeps per level (docs/METHOD.md §9.7, "Why a
click's first level may end at the cap"): the README's Colin27 click and the KmeansTest click
(Examples/ds_scoring.py's HEADS: their clicks and typed ranges), every other default, solved
with MaxSweepsPerLevel at each CAP. Prints a row per head and cap: the mean distance from the
surface to the brain mask's boundary and back, the enclosed volume over the mask's, the sweeps
and the intersecting pairs.

    PYTHONPATH=build/lib/python3/dist-packages pvpython Testing/Benchmarks/head_clicks_sweep_cap.py \\
        build/lib/paraview-5.11/plugins/DeformableSurface/DeformableSurface.so [CAP ...]
"""
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "Examples"))
from paraview import servermanager  # noqa: E402

import demo  # noqa: E402
import ds_scoring  # noqa: E402


def main(plugin, caps):
    demo.load_plugin(plugin)
    print("| head | MaxSweepsPerLevel | surface -> mask | mask -> surface | volume / mask | sweeps | "
          "self-int. |")
    print("|---|---|---|---|---|---|---|")
    for head in ("colin27", "kmeans"):
        result = demo.segment_head(head, "click")
        for cap in caps:
            demo.solve(result["surface"], {"MaxSweepsPerLevel": cap})
            result["polydata"] = servermanager.Fetch(result["surface"], idx=0)
            m = ds_scoring.measure_head(result, iso=False)
            print("| %s | %d | %.3f mm | %.3f mm | %.3f | %d | %d |" % (
                head, cap, m["dist_mean"], m["back_mean"], m["surface_volume"] / m["mask_volume"],
                m["sweeps"], m["self_intersections"]), flush=True)


if __name__ == "__main__":
    main(sys.argv[1], [int(c) for c in sys.argv[2:]] or [2000, 3000, 4000, 6000])
