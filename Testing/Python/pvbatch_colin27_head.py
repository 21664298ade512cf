# SPDX-License-Identifier: BSD-3-Clause
# pvbatch (private Xvfb): the README's main job, the brain in the whole Colin27 head
# (ch2.nii.gz, mricron-data), checked with numbers against the brain mask ch2bet > 0 (a
# reference only: the filter never sees it). Two starts, both from Examples/ (chosen on the
# image): 44 points picked ~3 mm outside the brain on six slices -> Delaunay Seed Surface ->
# Deformable Surface with every default; and one click in the white matter -> a 5 mm seed
# sphere -> Deformable Surface with the IntensityRange read off the image (a click given its
# range pulls with RegionWeight 1).
#
# Measured (Release, the 2-core machine of docs/RESULTS.md): picks 1.1-1.4 s,
# 11 113 vertices, one closed surface, 0 self-intersections, vertex -> mask boundary mean 0.60,
# 95 % 2.19 mm, volume +3.3 %; click 0.8-0.9 s, 17 549 vertices, mean 0.83, 95 % 3.20 mm,
# volume +3.2 % (six other clicks 4 mm away: 14 667-19 527 vertices, docs/RESULTS.md). The goals,
# asserted below: picks mean <= 1.0, 95 % <= 3.0, volume within 5 %; click mean <= 1.5, volume
# within 8 %, its levels after the first ending before 1 000 sweeps. The solve time is not
# asserted (it depends on the machine's load); its main term is: the click's vertices stay
# below 25 000 (54 684 when the grown seed, whose edges follow its growth rather than sigma, was
# split at every coarse level; 31 364 when split to sigma after the region force had faded:
# docs/METHOD.md §9.3).
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "Examples"))
sys.path.insert(0, here)
import demo  # noqa: E402
import ds_scoring  # noqa: E402
import ds_invariants  # noqa: E402

demo.load_plugin(os.environ.get("DS_PLUGIN"))
failures = []


def check(name, ok, value):
    print("%-62s %s" % (name, "ok" if ok else "FAILED (%s)" % (value,)))
    if not ok:
        failures.append(name)


runs = []
for start in ("picks", "click"):
    try:
        result = demo.segment_head("colin27", start)
    except RuntimeError as error:
        raise SystemExit("FAIL: %s (the test setup installs mricron-data)" % error)
    # The shared invariants (finite, closed 2-manifold oriented like the seed, its Euler
    # characteristic, SelfIntersections 0) on the surface against its seed.
    ds_invariants.check_surface(result["seed_polydata"], result["polydata"], start)
    m = ds_scoring.measure_head(result, iso=False)
    runs.append((start, m))
    volume_error = m["surface_volume"] / m["mask_volume"] - 1.0
    check(start + ": one closed 2-manifold piece, genus 0",
          (m["regions"], m["boundary_edges"], m["nonmanifold_edges"], m["euler"]) == (1, 0, 0, 2),
          (m["regions"], m["boundary_edges"], m["nonmanifold_edges"], m["euler"]))
    check(start + ": no self-intersections", m["self_intersections"] == 0, m["self_intersections"])
    if start == "picks":
        check("picks: vertex -> mask boundary mean <= 1.0 mm", m["dist_mean"] <= 1.0, m["dist_mean"])
        check("picks: vertex -> mask boundary 95% <= 3.0 mm", m["dist_p95"] <= 3.0, m["dist_p95"])
        check("picks: closer to the brain than the seed was (mean)", m["dist_mean"] < 0.5 * m["seed_mean"],
              (m["dist_mean"], m["seed_mean"]))
        check("picks: |volume / mask volume - 1| <= 5%", abs(volume_error) <= 0.05, volume_error)
    else:
        check("click: vertex -> mask boundary mean <= 1.5 mm", m["dist_mean"] <= 1.5, m["dist_mean"])
        check("click: |volume / mask volume - 1| <= 8%", abs(volume_error) <= 0.08, volume_error)
        check("click: vertices <= 25 000 (no split below sigma, below 2 sigma once faded)",
              m["vertices"] <= 25000, m["vertices"])
        # A level that steps in place at the range's end rests (docs/METHOD.md §9.7): the second
        # level grows for ~300 sweeps, then stepped in place to the 2 000-sweep cap. The first
        # may reach the cap: it grows all along.
        table = result["table"]
        levels = [table.GetColumnByName("Level").GetValue(i) for i in range(table.GetNumberOfRows())]
        later = [levels.count(level) for level in sorted(set(levels)) if level > 0]
        check("click: every level after the first ends before 1 000 sweeps",
              bool(later) and max(later) < 1000, later)
for start, m in runs:
    print("%s: %.2f s, %d vertices, mean %.2f, 95%% %.2f, max %.1f mm, volume %+.1f%%"
          % (start, m["seconds"], m["vertices"], m["dist_mean"], m["dist_p95"], m["dist_max"],
             100.0 * (m["surface_volume"] / m["mask_volume"] - 1.0)))
if failures:
    raise SystemExit("FAILED: " + "; ".join(failures))
print("all checks passed")
