// SPDX-License-Identifier: BSD-3-Clause
// A DICOM series as a volume: the headers of a folder's files, grouped by Series Instance UID,
// one series chosen, its slices sorted along the slice normal and the volume placed in the
// plugin's world frame. Plain C++ on GDCM's core (gdcmMSFF), no pipeline types.
//
// Geometry (DICOM PS3.3 C.7.6.2.1.1): pixel (c, r) of a slice lies at
//   IPP + c * PixelSpacing[1] * RowCosines + r * PixelSpacing[0] * ColumnCosines
// in the patient's LPS frame. Slices are ordered by n . IPP with n = RowCosines x ColumnCosines
// (never by file name or Instance Number, which scanners number in either direction). The
// plugin's world is the NIfTI reader's (vtkDSNIFTIImageReader): NIfTI's RAS, so LPS x and y are
// negated; a subject's DICOM and NIfTI then line up.
#ifndef dsDicomSeries_h
#define dsDicomSeries_h

#include "DeformableSurfaceFiltersModule.h" // for export macro

#include <string>
#include <vector>

namespace dsurf
{
namespace dicom
{
/// What one file's header says (everything before its Pixel Data).
struct DEFORMABLESURFACEFILTERS_EXPORT SliceHeader
{
  std::string File;
  std::string SeriesUID, SeriesDescription;
  std::string TransferSyntaxUID, TransferSyntaxName;
  bool HasPosition = false, HasOrientation = false;
  double Position[3] = { 0, 0, 0 };             ///< Image Position (Patient), LPS mm
  double Orientation[6] = { 1, 0, 0, 0, 1, 0 }; ///< row then column direction cosines, LPS
  double PixelSpacing[2] = { 1, 1 };            ///< between rows, between columns (mm)
  unsigned int Rows = 0, Columns = 0, Frames = 1;
  unsigned int BitsAllocated = 0, BitsStored = 0, PixelRepresentation = 0, SamplesPerPixel = 1;
  double Slope = 1, Intercept = 0; ///< Rescale Slope / Intercept (CT: to Hounsfield units)
  long long PixelDataBytes = -2;   ///< native Pixel Data's length; -1 compressed; -2 none
  long long FileBytes = 0;
};

enum class HeaderStatus
{
  Ok,
  NotDicom, ///< no "DICM" preamble, or no series: skipped when scanning a folder
  Damaged   ///< claims to be DICOM (the "DICM" preamble) but is cut short or cannot be parsed
};

/// Reads one file's header; error says why when not Ok.
DEFORMABLESURFACEFILTERS_EXPORT HeaderStatus ReadHeader(
  const std::string& file, SliceHeader& header, std::string& error);

/// True when the transfer syntax's pixel data GDCM can decode (native, JPEG baseline,
/// extended and lossless, JPEG-LS, JPEG 2000, RLE); others (MPEG, JPIP, ...) are refused.
DEFORMABLESURFACEFILTERS_EXPORT bool SupportedTransferSyntax(const std::string& uid);

struct DEFORMABLESURFACEFILTERS_EXPORT Series
{
  std::string UID, Description;
  std::vector<SliceHeader> Slices;
};

/// The series of a folder's DICOM files (not recursing), largest first. Files that are not DICOM
/// are skipped (listed in `skipped`); a damaged one is an error (it would otherwise show as a
/// missing slice).
DEFORMABLESURFACEFILTERS_EXPORT bool ScanFolder(const std::string& folder,
  std::vector<Series>& series, std::vector<std::string>& skipped, std::string& error);

/// Which series to read: the one of `file` when given, else the one whose description is
/// `description` when given, else the largest. -1 and error when none fits.
DEFORMABLESURFACEFILTERS_EXPORT int ChooseSeries(const std::vector<Series>& series,
  const std::string& file, const std::string& description, std::string& error);

/// A series stacked into a volume in the plugin's world frame (RAS, see above).
struct DEFORMABLESURFACEFILTERS_EXPORT Volume
{
  int Dimensions[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  double Origin[3] = { 0, 0, 0 };
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 }; ///< row-major: column j is axis j
  std::vector<SliceHeader> Slices;                     ///< in slice order (increasing n . IPP)
  std::vector<std::string> Warnings;
};

/// Checks that the slices form one volume (same size, orientation, pixel spacing and pixel
/// format; no two at one position; no missing slice), sorts them and places the volume. Uneven
/// steps and a gantry tilt are kept as warnings: the slices are stacked at their mean step
/// along the normal, not resampled.
DEFORMABLESURFACEFILTERS_EXPORT bool StackSeries(
  const Series& series, Volume& volume, std::string& error);
} // namespace dicom
} // namespace dsurf

#endif
