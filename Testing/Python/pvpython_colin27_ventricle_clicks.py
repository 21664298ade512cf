# SPDX-License-Identifier: BSD-3-Clause
"""One click in Colin27's lateral ventricles, every default (Examples/colin27_ventricle_clicks.csv,
solved by Testing/Benchmarks/colin27_ventricle_clicks.py; docs/RESULTS.md). Their front levels
followed the CSF on through its channels and the sulci, growing about 1.6 times a level, and did
not end within ten minutes (660 000 vertices and half a litre at the seventeenth front level);
front levels stop following a front that grows at each of its last three levels (FrontGrows,
docs/METHOD.md §9.3). Where the front branched, the front levels folded the surface (114-187
intersecting pairs at the end); a front level that makes the surface cross itself is undone
(SolveFrontLevel). Checks, per click:
- the range holds the click's CSF (28-30) and ends below the grey matter: lo < 28, 30 < hi < 50;
- the run ends after at most 8 front levels, with fewer than 10 000 vertices;
- the surface is closed and manifold (a sphere's Euler characteristic) and no two of its
  triangles intersect (SelfIntersections 0);
- it encloses 3-15 ml (an adult's lateral ventricle: typically 5-10 ml).
Not checked, because not reached yet: the horns (no reference for them: AAL has no ventricle
label)."""
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "Benchmarks"))
import colin27_ventricle_clicks  # noqa: E402
import ds_invariants  # noqa: E402

failures = []


def check(name, ok, value):
    print("%-62s %s" % (name, "ok" if ok else "FAILED (%s)" % (value,)))
    if not ok:
        failures.append(name)


for r in colin27_ventricle_clicks.solve_clicks(os.environ.get("DS_PLUGIN")):
    where = "(%g, %g, %g)" % tuple(r["centre"])
    print("%s: range %s, %.1f s, %d vertices, %.1f ml, %d intersecting pairs, %d front levels" % (
        where, r["range"], r["seconds"], r["vertices"], r["volume"], r["self_intersections"],
        r["front_levels"]))
    lo, hi = r["range"] if r["range"] else (float("nan"), float("nan"))
    check(where + ": range holds the CSF, ends below grey matter", lo < 28 and 30 < hi < 50, (lo, hi))
    check(where + ": at most 8 front levels", r["front_levels"] <= 8, r["front_levels"])
    check(where + ": fewer than 10 000 vertices", r["vertices"] < 10000, r["vertices"])
    facts = ds_invariants.surface_facts(r["surface"])
    try:
        ds_invariants.check_closed_manifold(facts, where, euler=2)
        check(where + ": closed and manifold", True, None)
    except AssertionError as e:
        check(where + ": closed and manifold", False, e)
    check(where + ": no self-intersection", r["self_intersections"] == 0, r["self_intersections"])
    check(where + ": encloses 3-15 ml", 3.0 <= r["volume"] <= 15.0, r["volume"])
sys.exit(1 if failures else 0)
