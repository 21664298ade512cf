# SPDX-License-Identifier: BSD-3-Clause
# The README's pvpython pipeline, as written, on readers that have not run yet (NIfTI, .vti,
# .mhd): the surface must be found, not an empty output with an error (see readme_pipeline.py).
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import readme_pipeline as rp  # noqa: E402

rp.load_plugin()
out = os.path.join(os.environ.get("DS_TEST_OUTPUT", "."), "readme_pipeline_serial")
failures = []
for name, (scalars, n, mean) in sorted(rp.run_all(out).items()):
    print("%-9s Scalars property %-16s -> %5d points, mean |d| %.3f voxel" % (name, scalars, n, mean))
    if n == 0 or not mean <= rp.TOLERANCE:
        failures.append("%s: %d points, mean |d| %.3f (allowed %.2f)" % (name, n, mean, rp.TOLERANCE))
for f in failures:
    print("FAILED:", f)
sys.exit(1 if failures else 0)
