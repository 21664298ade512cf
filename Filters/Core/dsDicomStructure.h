// SPDX-License-Identifier: BSD-3-Clause
// A check of a DICOM file's element structure (PS3.5 §7, PS3.10 §7) before GDCM reads it: the
// preamble and "DICM", then every element's length (sequences, items and encapsulated pixel data
// followed down) within the file. Debian's GDCM is built with its assertions on, and a file cut
// short or with a wild length makes it abort the process (FileMetaInformation::ReadCompat:
// `is.good()`); this check turns such files into an error instead. Plain C++, no GDCM, no VTK.
#ifndef dsDicomStructure_h
#define dsDicomStructure_h

#include "DeformableSurfaceFiltersModule.h" // for export macro

#include <string>

namespace dsurf
{
namespace dicom
{
enum class Structure
{
  Complete,  ///< every element lies within the file
  NotDicom,  ///< no "DICM" after the 128-byte preamble
  Damaged,   ///< "DICM", but an element runs past the end or the structure is broken
  Unwalkable ///< deflated or unknown transfer syntax: its elements cannot be walked
};

/// What the walk found besides completeness.
struct DEFORMABLESURFACEFILTERS_EXPORT FileFacts
{
  std::string TransferSyntax;    ///< the meta header's UID
  long long PixelDataBytes = -2; ///< native Pixel Data's length; -1 encapsulated; -2 none
  long long FileBytes = 0;
};

/// Checks `file`; error says why when not Complete.
DEFORMABLESURFACEFILTERS_EXPORT Structure CheckStructure(
  const std::string& file, FileFacts& facts, std::string& error);
} // namespace dicom
} // namespace dsurf

#endif
