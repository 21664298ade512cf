// SPDX-License-Identifier: BSD-3-Clause
// The checks a NIfTI file passes before VTK's vtkNIFTIImageReader reads it. VTK's reader trusts
// the header: an unknown datatype, absurd dims or a vox_offset beyond the file crash or abort it,
// a truncated file is read in part. Here the header is read as VTK reads it (the same version
// and byte-order rules), every field VTK uses is checked, and the data's length is checked
// against the file (a gzip stream is read to the data's end: its trailer holds the length only
// modulo 2^32). Layouts: nifti1.h and nifti2.h of the NIfTI Data Format Working Group. Plain C++.
#ifndef dsNiftiHeader_h
#define dsNiftiHeader_h

#include "DeformableSurfaceFiltersModule.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dsurf
{
/// The fields of a NIfTI-1, NIfTI-2 or Analyze 7.5 header that VTK's reader uses, in native
/// byte order and widened (NIfTI-1 keeps int16 dims and float pixdim; NIfTI-2 int64 and double).
struct NiftiHeader
{
  int Version = 0;      // 0: Analyze 7.5, 1: NIfTI-1, 2: NIfTI-2
  int HeaderSize = 0;   // 348 or 540
  bool Swapped = false; // written in the other byte order than this machine's
  int DataType = 0;
  int BitPix = 0;
  int64_t Dim[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
  double PixDim[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
  double VoxOffset = 0;
  int QFormCode = 0, SFormCode = 0;
  double Quatern[3] = { 0, 0, 0 }; // quatern_b, _c, _d
  double QOffset[3] = { 0, 0, 0 }; // qoffset_x, _y, _z
  double SRow[3][4] = { { 0, 0, 0, 0 }, { 0, 0, 0, 0 }, { 0, 0, 0, 0 } };
};

/// Bytes of the first header bytes a version needs: 348 for NIfTI-1 and Analyze, 540 for NIfTI-2.
constexpr std::size_t NiftiHeaderBytes = 540;

/// Decodes the header at the start of `bytes` (the file's first `size` bytes, at least 348
/// wanted, 540 for NIfTI-2). Returns "" or why this is not a header VTK's reader can take.
DEFORMABLESURFACEFILTERS_EXPORT std::string ParseNiftiHeader(
  const unsigned char* bytes, std::size_t size, NiftiHeader& header);

/// Bytes per voxel of a datatype VTK's reader knows (nifti1.h codes); 0 for any other.
DEFORMABLESURFACEFILTERS_EXPORT int NiftiBytesPerVoxel(int datatype);

/// What the checks found: an error (the file must not be read), warnings, and the spatial axes
/// whose spacing is replaced by 1 (pixdim 0 or negative).
struct NiftiVerdict
{
  std::string Error;
  std::vector<std::string> Warnings;
  bool UnitSpacing[3] = { false, false, false };
  uint64_t DataSize = 0; // bytes of the data the dims describe (all of them, not only the 3-D part)
};

/// The field checks of a decoded header, without the file: datatype and bitpix, dim[0] in 1..7,
/// positive dims within VTK's int indices, the data size within `maximumDataSize`, a finite
/// non-negative vox_offset, finite pixdim, quatern/qoffset (qform_code > 0) and srow
/// (sform_code > 0); pixdim 0 or negative on a spatial axis gives a warning and spacing 1.
DEFORMABLESURFACEFILTERS_EXPORT NiftiVerdict CheckNiftiHeader(
  const NiftiHeader& header, uint64_t maximumDataSize);

/// The whole check of a file as VTK's reader would read it: the header from `headerFile`, the
/// data from `dataFile` at vox_offset (the same file for .nii; .hdr and .img for a pair), gzipped
/// or not. The data must fit in the file: for a plain file its size, for a gzip stream the
/// length found by decompressing it up to the data's end (no further).
DEFORMABLESURFACEFILTERS_EXPORT NiftiVerdict CheckNiftiFile(
  const std::string& headerFile, const std::string& dataFile, uint64_t maximumDataSize);
} // namespace dsurf

#endif
