# SPDX-License-Identifier: BSD-3-Clause
"""Where the spine phantom's one-voxel cortex puts a one-click surface (docs/RESULTS.md).

    build/bin/BenchObjects --write DIR spine
    pvpython Testing/Benchmarks/spine_cortex.py DIR

Reads DIR/spine_image.vti and DIR/spine_ours.vtp and prints, in voxels (3 mm) outward from the
middle body's true side (the ellipse of Testing/Cxx/ObjectPhantoms.h, semi-axes 21 x 16 mm about
(48.35, 42.35)), averaged over 72 directions on three mid-height slices (z 87, 90, 93 mm):
- the maximum of |grad(G_sigma * f)| along the ray at sigma 2/3 voxel (sigma's floor), 1 and 1.4;
- the last crossing of the range's lower end (the IntensityRange field of the surface) by the
  image itself, linearly interpolated, where the region speed changes sign;
- the surface's side vertices (more than 4 mm from the body's top and bottom): their mean offset.
"""
import os
import sys

import numpy as np
from scipy import ndimage
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader

CENTRE, SEMI, SPACING = (48.35, 42.35), (21.0, 16.0), 3.0
BOTTOM = 10.8 + 2 * 33.0  # the middle body's bottom, mm
TOP = BOTTOM + 27.0


def read(reader, path):
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def main(directory):
    image = read(vtkXMLImageDataReader(), os.path.join(directory, "spine_image.vti"))
    surface = read(vtkXMLPolyDataReader(), os.path.join(directory, "spine_ours.vtp"))
    nx, ny, nz = image.GetDimensions()
    f = vtk_to_numpy(image.GetPointData().GetScalars()).astype(float).reshape(nz, ny, nx)
    low = surface.GetFieldData().GetArray("IntensityRange").GetTuple2(0)[0]
    t = np.linspace(0.6, 1.4, 801)
    rays = []
    for angle in np.linspace(0, 2 * np.pi, 72, endpoint=False):
        c, s = np.cos(angle), np.sin(angle)
        radius = np.hypot(SEMI[0] * c, SEMI[1] * s) / SPACING  # the true side, voxels
        for z in (87.0, 90.0, 93.0):
            index = np.array([np.full_like(t, z / SPACING), (CENTRE[1] + SEMI[1] * s * t) / SPACING,
                              (CENTRE[0] + SEMI[0] * c * t) / SPACING])
            rays.append((index, radius))
    for sigma in (2.0 / 3.0, 1.0, 1.4):
        g = np.sqrt(sum(d * d for d in np.gradient(ndimage.gaussian_filter(f, sigma))))
        offsets = [(t[np.argmax(ndimage.map_coordinates(g, i, order=1))] - 1) * r for i, r in rays]
        print("edge maximum at sigma %.2f voxel: %.3f voxel outside" % (sigma, np.mean(offsets)))
    crossings = []
    for index, radius in rays:
        inside = np.nonzero(ndimage.map_coordinates(f, index, order=1) > low)[0]
        crossings.append((t[inside[-1]] - 1) * radius)
    print("image at the range's lower end (%.1f): %.3f voxel outside" % (low, np.mean(crossings)))
    points = vtk_to_numpy(surface.GetPoints().GetData())
    side = (points[:, 2] > BOTTOM + 4) & (points[:, 2] < TOP - 4)
    u = (points[side, 0] - CENTRE[0]) / SEMI[0]
    w = (points[side, 1] - CENTRE[1]) / SEMI[1]
    angle = np.arctan2(w, u)
    radius = np.hypot(SEMI[0] * np.cos(angle), SEMI[1] * np.sin(angle)) / SPACING
    offset = (np.hypot(u, w) - 1) * radius
    print("surface's sides (%d vertices): %.3f voxel outside" % (side.sum(), offset.mean()))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
