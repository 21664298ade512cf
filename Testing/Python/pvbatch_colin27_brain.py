# SPDX-License-Identifier: BSD-3-Clause
# pvbatch (under xvfb-run): the paper's setting on real data, checked with numbers. Runs the
# pipeline of Examples/demo.py --skull-stripped (Colin27 brain from ch2bet.nii.gz,
# DeformableSurface started from the box around the volume) and checks the surface against the truth, the
# boundary of the brain mask ch2bet > 0.
#
# The volumes come from the Debian package mricron-data, which scripts/install-deps.sh
# installs: if they are missing the setup is broken and this test FAILS (it does not skip).
#
# Measured (Release, Debian 12 / ParaView 5.11, every default): 7 levels (sigma 32 mm halving to
# its floor, 2/3 of a voxel), 462 sweeps, 30 718 vertices, 61 432 triangles, one region, Euler
# characteristic 2, 0 boundary and 0 non-manifold edges, 0 self-intersections; vertex -> mask
# boundary mean 0.24, median 0.18, 95% 0.61, max 7.1 mm; mask boundary -> surface median 0.38,
# 95% 5.6 mm (the sulci the smooth surface bridges); enclosed volume 1729 cm3 vs mask 1737 cm3
# (-0.5 %); triangle min angle 5th percentile 28.3 deg. Iso-surface ch2bet = 0.5: 99 regions, 36.5 % of its triangles with a
# min angle below 10 deg.
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "Examples"))
sys.path.insert(0, here)
import demo  # noqa: E402
import ds_pictures  # noqa: E402
import ds_scoring  # noqa: E402
import ds_invariants  # noqa: E402

try:
    demo.require_data()
except RuntimeError as error:
    raise SystemExit("FAIL: %s. The test setup installs mricron-data; without it the real-data "
                     "check cannot run." % error)

demo.load_plugin(os.environ.get("DS_PLUGIN"))
result = demo.segment_brain()
# The invariants every surface keeps (m's topology checks below say the same in its own terms).
from paraview import servermanager  # noqa: E402
ds_invariants.check_surface(servermanager.Fetch(result["box"]), result["polydata"], "Colin27 brain")
m = ds_scoring.measure(result)
print(ds_scoring.summary(m))

out = os.environ.get("DS_TEST_OUTPUT", ".")
os.makedirs(out, exist_ok=True)
png = ds_pictures.render(result, os.path.join(out, "pvbatch_colin27_brain.png"), (800, 400), m)

failures = []


def check(name, ok, value):
    print("%-58s %s" % (name, "ok" if ok else "FAILED (%s)" % (value,)))
    if not ok:
        failures.append(name)


# Topology: one closed, 2-manifold, sphere-like surface that does not cut itself.
check("one connected region", m["regions"] == 1, m["regions"])
check("no boundary edges (closed)", m["boundary_edges"] == 0, m["boundary_edges"])
check("no non-manifold edges", m["nonmanifold_edges"] == 0, m["nonmanifold_edges"])
check("Euler characteristic 2 (genus 0)", m["euler"] == 2, m["euler"])
check("no self-intersections", m["self_intersections"] == 0, m["self_intersections"])
# The schedule: sigma_0 = extent / 6 = 32 mm halves to its floor, 2/3 mm: levels 0..6;
# vertices in a sensible band for 2-3 mm triangles.
check("7 levels solved", m["levels"] == 7, m["levels"])
check("5000 <= vertices <= 100000", 5000 <= m["vertices"] <= 100000, m["vertices"])
# On the boundary: vertices within a voxel of the mask boundary on average (measured 0.24).
check("vertex -> mask boundary mean <= 0.75 mm", m["dist_mean"] <= 0.75, m["dist_mean"])
check("vertex -> mask boundary median <= 0.6 mm", m["dist_median"] <= 0.6, m["dist_median"])
check("vertex -> mask boundary 95% <= 2.0 mm", m["dist_p95"] <= 2.0, m["dist_p95"])
check("vertex -> mask boundary max <= 15 mm", m["dist_max"] <= 15.0, m["dist_max"])
# Covers the brain: half the mask boundary within 1 mm of the surface (measured 0.38;
# the rest lies in sulci the smooth surface bridges), and the same enclosed volume.
check("mask boundary -> surface median <= 1.0 mm", m["back_median"] <= 1.0, m["back_median"])
volume_error = m["surface_volume"] / m["mask_volume"] - 1.0
check("|enclosed volume / mask volume - 1| <= 5%", abs(volume_error) <= 0.05, volume_error)
# Well-shaped triangles (measured 5th percentile 28.3 deg) where the iso-surface has slivers.
check("min angle 5th percentile >= 25 deg", m["angle_p5"] >= 25.0, m["angle_p5"])
iso = m["iso"][0]
check("iso-surface of the mask is fragmented (>= 20 regions)", iso["regions"] >= 20, iso["regions"])
check("picture written", os.path.getsize(png) > 20000, os.path.getsize(png))

if failures:
    raise SystemExit("FAILED: " + "; ".join(failures))
print("all checks passed")
