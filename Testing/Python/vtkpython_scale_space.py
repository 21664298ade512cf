# SPDX-License-Identifier: BSD-3-Clause
# VTK Python (plain vtkmodules): the wrapped filter on a synthetic ball, checking
# arrays, the normalised potential range and the direction of the force.
import math
import sys

from vtkmodules.vtkImagingSources import vtkImageEllipsoidSource
from deformablesurface import vtkImageScaleSpaceGradient

src = vtkImageEllipsoidSource()  # uint8 ball: 255 inside, 0 outside
src.SetWholeExtent(0, 47, 0, 47, 0, 47)
src.SetCenter(24, 24, 24)
src.SetRadius(12, 12, 12)
src.SetInValue(255)
src.SetOutValue(0)
src.SetOutputScalarTypeToUnsignedChar()

f = vtkImageScaleSpaceGradient()
f.SetInputConnection(src.GetOutputPort())
f.SetSigma(2.0)
f.SetNumberOfThreads(2)
f.Update()
out = f.GetOutput()
pd = out.GetPointData()
P, F = pd.GetArray("Potential"), pd.GetArray("Force")
assert P is not None and F is not None
assert F.GetNumberOfComponents() == 3
lo, hi = P.GetRange()
print("Potential range", lo, hi)
assert abs(lo + 1.0) < 1e-6 and hi <= 0.0

# Force at (24 +/- 8, 24, 24) (inside) points outward, at 24 +/- 16 (outside) inward.
def force_at(i, j, k):
    return F.GetTuple3(out.ComputePointId((i, j, k)))

for i, sign in ((32, +1), (16, -1), (40, -1), (8, +1)):
    fx = force_at(i, 24, 24)[0]
    print("Force_x at i=%d: %g" % (i, fx))
    assert fx * sign > 0, (i, fx)
print("vtkpython_scale_space: OK")
sys.exit(0)
