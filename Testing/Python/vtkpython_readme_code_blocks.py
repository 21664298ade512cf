# SPDX-License-Identifier: BSD-3-Clause
# Every Python code block of the README runs as written: blocks that import paraview.simple
# with pvpython, the others with this interpreter (/usr/bin/python3, plain vtkmodules, the
# wrapped package on PYTHONPATH as the README says). They run in a scratch folder where
# "build" is the build tree, so the README's relative plugin path resolves as it does in a
# checkout; each must exit 0 and write the brain.vtp it promises, readable again.
import os
import re
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
readme = os.path.join(here, "..", "..", "README.md")
plugin = os.environ["DS_PLUGIN"]
build = os.path.abspath(os.path.join(os.path.dirname(plugin), *[".."] * 4))

with open(readme) as f:
    blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
assert blocks, "no python blocks in the README"

from vtkmodules.vtkIOXML import vtkXMLPolyDataReader  # noqa: E402

sys.path.insert(0, here)
import ds_invariants  # noqa: E402

failures = []
for i, code in enumerate(blocks):
    scratch = tempfile.mkdtemp(prefix="readme_block_")
    os.symlink(build, os.path.join(scratch, "build"))
    script = os.path.join(scratch, "block.py")
    with open(script, "w") as f:
        f.write(code)
    pv = "paraview.simple" in code
    command = ["pvpython", "--force-offscreen-rendering", script] if pv else [sys.executable, script]
    run = subprocess.run(command, cwd=scratch, capture_output=True, text=True, timeout=300)
    output = os.path.join(scratch, "brain.vtp")
    points = -1
    if os.path.exists(output):
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(output)
        reader.Update()
        points = reader.GetOutput().GetNumberOfPoints()
        # The README's jobs start from a closed box or seed: one closed genus-0 2-manifold.
        label = "README block %d: brain.vtp" % i
        ds_invariants.check_closed_manifold(ds_invariants.surface_facts(reader.GetOutput()), label, euler=2)
    print("block %d (%s): exit %d, brain.vtp with %d points" % (i, "pvpython" if pv else "python3",
                                                                run.returncode, points))
    if run.returncode != 0 or " ERR| " in run.stderr or points <= 0:
        failures.append(i)
        print(run.stdout[-2000:], run.stderr[-2000:])
if failures:
    raise SystemExit("FAILED: README blocks %s" % failures)
print("vtkpython_readme_code_blocks: %d blocks ran" % len(blocks))
