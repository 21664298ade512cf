"""The plugin loads through PV_PLUGIN_PATH alone (no LoadPlugin call), the way a user
installs it for the GUI, and every filter appears in paraview.simple."""
import os
import sys

assert os.environ.get("PV_PLUGIN_PATH"), "ctest must set PV_PLUGIN_PATH"
import paraview.simple as simple  # noqa: E402

wanted = ["ScaleSpaceGradient", "DeformableSurface", "DelaunaySeedSurface"]
missing = [name for name in wanted if not hasattr(simple, name)]
print("found:", [name for name in wanted if name not in missing])
if missing:
    sys.exit("not loaded through PV_PLUGIN_PATH: %s" % missing)
