# SPDX-License-Identifier: BSD-3-Clause
"""grab_x11.py DISPLAY OUT.png: a picture of the whole screen of an X display (the Xvfb of
scripts/gui_screenshot.sh), panels included, as a PNG.

Xlib's XGetImage through ctypes and VTK's PNG writer, both on every machine that runs ParaView:
no ImageMagick (`import -window root`) or xwd needed. Run with /usr/bin/python3."""
import ctypes
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter


class XImage(ctypes.Structure):
    # The leading fields of Xlib's XImage (X11/Xlib.h), up to those read here.
    _fields_ = [("width", ctypes.c_int), ("height", ctypes.c_int), ("xoffset", ctypes.c_int),
                ("format", ctypes.c_int), ("data", ctypes.POINTER(ctypes.c_ubyte)),
                ("byte_order", ctypes.c_int), ("bitmap_unit", ctypes.c_int),
                ("bitmap_bit_order", ctypes.c_int), ("bitmap_pad", ctypes.c_int),
                ("depth", ctypes.c_int), ("bytes_per_line", ctypes.c_int),
                ("bits_per_pixel", ctypes.c_int), ("red_mask", ctypes.c_ulong),
                ("green_mask", ctypes.c_ulong), ("blue_mask", ctypes.c_ulong)]


def grab(display_name):
    """The screen as an (height, width, 3) uint8 RGB array, top row first."""
    x = ctypes.CDLL("libX11.so.6")
    x.XOpenDisplay.restype = ctypes.c_void_p
    x.XDefaultRootWindow.restype = ctypes.c_ulong
    x.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
    x.XGetImage.restype = ctypes.POINTER(XImage)
    x.XGetImage.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int, ctypes.c_uint,
                            ctypes.c_uint, ctypes.c_ulong, ctypes.c_int]
    for name in ("XDisplayWidth", "XDisplayHeight"):
        getattr(x, name).argtypes = [ctypes.c_void_p, ctypes.c_int]
    display = x.XOpenDisplay(display_name.encode())
    if not display:
        sys.exit("cannot open display %s" % display_name)
    width, height = x.XDisplayWidth(display, 0), x.XDisplayHeight(display, 0)
    z_pixmap, all_planes = 2, 0xFFFFFFFF
    image = x.XGetImage(display, x.XDefaultRootWindow(display), 0, 0, width, height, all_planes, z_pixmap)
    if not image or image.contents.bits_per_pixel != 32:
        sys.exit("expected a 24-bit screen (32 bits per pixel)")
    row = image.contents.bytes_per_line
    raw = np.ctypeslib.as_array(image.contents.data, shape=(height * row,)).copy()
    red, green, blue = (image.contents.red_mask, image.contents.green_mask, image.contents.blue_mask)
    pixels = raw.reshape(height, row)[:, : 4 * width].view(np.uint32).reshape(height, width)
    rgb = np.stack([(pixels & mask) >> (int(mask).bit_length() - 8) for mask in (red, green, blue)], axis=-1)
    return rgb.astype(np.uint8)


def write_png(rgb, path):
    height, width, _ = rgb.shape
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    # VTK's rows run bottom-up.
    image.GetPointData().SetScalars(numpy_to_vtk(np.ascontiguousarray(rgb[::-1]).reshape(-1, 3), deep=1))
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    write_png(grab(sys.argv[1]), sys.argv[2])
