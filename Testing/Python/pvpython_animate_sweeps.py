# SPDX-License-Identifier: BSD-3-Clause
# pvpython: AnimateSweeps gives ParaView time steps (0, 20, 40 ... sweeps) that the animation
# scene picks up, and the surface at time 40 says 40 sweeps.
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paraview import servermanager  # noqa: E402
from paraview.simple import Calculator, GetAnimationScene, GetTimeKeeper, LoadPlugin, Sphere, Wavelet  # noqa: E402

import ds_invariants  # noqa: E402

LoadPlugin(os.environ["DS_PLUGIN"], ns=globals())
wavelet = Wavelet(WholeExtent=[-24, 24, -24, 24, -24, 24])
ball = Calculator(Input=wavelet, ResultArrayName="ball",
                  Function="1/(1+exp(2*(sqrt(coordsX^2+coordsY^2+coordsZ^2)-12)))")
start = Sphere(Radius=16.0, ThetaResolution=24, PhiResolution=24)
ds = DeformableSurface(Input=ball, InitialSurface=start, AnimateSweeps=1)  # noqa: F821
ds.Scalars = ["POINTS", "ball"]
ds_invariants.update_proxy(ds, [ball, start], "AnimateSweeps at time 40", time=40.0)
steps = list(ds.TimestepValues)
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
print("%d time steps %s ..., scene %g to %g" % (len(steps), steps[:3], scene.StartTime, scene.EndTime))
assert steps[:3] == [0.0, 20.0, 40.0], steps[:3]
assert len(GetTimeKeeper().TimestepValues) == len(steps)
surface = servermanager.Fetch(ds)
assert surface.GetFieldData().GetArray("Sweeps").GetTuple1(0) == 40
ds_invariants.check_surface(servermanager.Fetch(start), surface, "the surface at time 40")
print("pvpython_animate_sweeps: all checks passed")
