// SPDX-License-Identifier: BSD-3-Clause
// The values of a DICOM slice: its pixel data decoded by GDCM (native or compressed: JPEG,
// JPEG-LS, JPEG 2000, RLE) and mapped through Rescale Slope and Intercept (PS3.3 C.11.1.1.2),
// so CT comes out in Hounsfield units. Plain C++ on GDCM's core, no pipeline types.
#ifndef dsDicomPixels_h
#define dsDicomPixels_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsDicomSeries.h"

#include <string>
#include <vector>

namespace dsurf
{
namespace dicom
{
/// The smallest VTK scalar type (vtkType.h) holding slope * s + intercept exactly for every
/// value s the slices' pixel format can store (Bits Stored, Pixel Representation): an integer
/// type when every slope and intercept is a whole number, else float (double beyond 16 bits).
/// Taken from the format, not the values, so it is known before the pixels are read.
DEFORMABLESURFACEFILTERS_EXPORT int OutputScalarType(const std::vector<SliceHeader>& slices);

/// Decodes one slice and writes its Columns x Rows values, rescaled, as `scalarType` to `out`
/// (row by row, as stored). False, with the reason, when the file is truncated, damaged or its
/// pixel data does not match its header.
DEFORMABLESURFACEFILTERS_EXPORT bool ReadSlice(
  const SliceHeader& slice, int scalarType, void* out, std::string& error);
} // namespace dicom
} // namespace dsurf

#endif
