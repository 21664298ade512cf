# SPDX-License-Identifier: BSD-3-Clause
# ParaView: LoadPlugin, run ScaleSpaceGradient on the Wavelet source, check the
# arrays it adds and their ranges.
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

LoadPlugin(os.environ["DS_PLUGIN"], ns=globals())

wavelet = Wavelet()  # 21^3, RTData float, extent -10..10
ssg = ScaleSpaceGradient(Input=wavelet)
ssg.Scalars = ["POINTS", "RTData"]
print("defaults: Sigma", ssg.Sigma, "SigmaFraction", ssg.SigmaFraction,
      "EdgeWeight", ssg.EdgeWeight, "ImageWeight", ssg.ImageWeight,
      "NormalizePotential", ssg.NormalizePotential)
assert abs(ssg.SigmaFraction - 1.0 / 6.0) < 1e-6
ssg.UpdatePipeline()

info = ssg.GetDataInformation()
assert info.GetNumberOfPoints() == 21 ** 3, info.GetNumberOfPoints()
pd = ssg.PointData
names = set(pd.keys())
print("point arrays:", sorted(names))
for required in ("RTData", "Potential", "Force"):
    assert required in names, required
assert pd["Force"].GetNumberOfComponents() == 3
assert pd["Potential"].GetNumberOfComponents() == 1

prange = pd["Potential"].GetRange()
print("Potential range", prange)
# Normalised: P = -|grad G*f| / max, so the minimum is -1 and nothing exceeds 0.
assert abs(prange[0] + 1.0) < 1e-5, prange
assert prange[1] <= 0.0 and prange[1] > -1.0, prange
fmag = pd["Force"].GetRange(-1)
print("|Force| range", fmag)
assert fmag[1] > 0.0

# The field data records the sigma used: 1/6 of the mean extent (21 voxels of 1).
out = servermanager.Fetch(ssg)
sigma = out.GetFieldData().GetArray("Sigma").GetValue(0)
print("Sigma used", sigma)
assert abs(sigma - 21.0 / 6.0) < 1e-5, sigma  # XML default is 0.1666667
assert out.GetPointData().GetArray("Force").GetDataType() == 10  # VTK_FLOAT
assert out.GetPointData().GetArray("Potential").GetDataType() == 10

# Image term only, no normalisation, a fixed sigma: P = -(G*f) stays within the data range.
ssg.EdgeWeight = 0.0
ssg.ImageWeight = 1.0
ssg.NormalizePotential = 0
ssg.Sigma = 1.5
ssg.UpdatePipeline()
rt = wavelet.PointData["RTData"].GetRange()
p2 = ssg.PointData["Potential"].GetRange()
print("RTData range", rt, "-> Potential range", p2)
assert -p2[1] >= rt[0] - 1e-3 and -p2[0] <= rt[1] + 1e-3
assert (-p2[0]) - (-p2[1]) < rt[1] - rt[0]  # smoothing shrinks the range
print("pvpython_scale_space: OK")
sys.exit(0)
