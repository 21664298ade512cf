// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkDSDICOMSeriesReader
 * @brief   Reads a DICOM series (a folder of slice files) into one vtkImageData, placed where
 *          the files say, in the world frame of vtkDSNIFTIImageReader.
 *
 * FileName is a folder or any one file of a series. The folder's files are grouped by Series
 * Instance UID; the series read is the one of the named file, else the one whose Series
 * Description equals SeriesDescription (when set), else the largest. Files that are not DICOM
 * are skipped. Built on GDCM's core libraries (gdcmMSFF): native, JPEG (baseline,
 * extended, lossless), JPEG-LS, JPEG 2000 and RLE pixel data are decoded; other transfer syntaxes
 * (MPEG, JPIP, ...) are refused with an error naming the syntax. Compressed pixel data is decoded
 * in a child process (on POSIX systems): the system's decoders can crash on damaged data
 * (OpenJPEG did on a JPEG 2000 codestream with two bytes swapped), which then gives an error.
 *
 * Placement (DICOM PS3.3 C.7.6.2.1.1): slices are sorted by their Image Position (Patient)
 * projected on the slice normal (row x column cosines), never by file name or Instance Number.
 * Image Orientation (Patient) gives the direction matrix (columns: row direction, column
 * direction, normal), the first slice's Image Position the origin, Pixel Spacing the in-plane
 * spacing and the positions' mean step the slice spacing. Uneven steps or a gantry tilt (the
 * positions drifting off the normal) give a warning saying by how much; the slices are stacked
 * along the normal at the mean step, not resampled. The output frame is the plugin's NIfTI
 * reader's: NIfTI's RAS, i.e. DICOM's LPS with x and y negated, so one subject's DICOM and
 * NIfTI (e.g. converted with dcm2niix) line up in ParaView.
 *
 * Values: Rescale Slope and Intercept are applied (CT in Hounsfield units), in the smallest VTK
 * scalar type holding every value the pixel format can store exactly: an integer type when the
 * slope and intercept are whole numbers, else float. The point-data array is "DICOMImage".
 *
 * Bad input (no series, a damaged or truncated file, a missing slice: a gap in the positions,
 * two slices at one position, files of one series that disagree in size, orientation or pixel
 * format, an unsupported transfer syntax) gives an error naming the file and an empty output.
 *
 * The plugin's "DICOM Series Reader (Deformable Surface)" is this class. Present only when the
 * module was built with GDCM (DEFORMABLESURFACE_USE_GDCM).
 */
#ifndef vtkDSDICOMSeriesReader_h
#define vtkDSDICOMSeriesReader_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <memory> // for std::unique_ptr

class DEFORMABLESURFACEFILTERS_EXPORT vtkDSDICOMSeriesReader : public vtkImageAlgorithm
{
public:
  static vtkDSDICOMSeriesReader* New();
  vtkTypeMacro(vtkDSDICOMSeriesReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// A folder of DICOM files, or any one file of the series to read.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// With a folder: read the series whose Series Description (0008,103E) is this; empty (the
  /// default): the series with the most slices.
  vtkSetStringMacro(SeriesDescription);
  vtkGetStringMacro(SeriesDescription);
  ///@}

  /// 1 when `name` is a DICOM file or a folder holding one, else 0 (ParaView's reader factory).
  int CanReadFile(const char* name);

  ///@{
  /// The series found by the last update (largest first): their number and descriptions.
  int GetNumberOfSeries();
  const char* GetSeriesDescriptionOf(int series);
  ///@}

  /// The transfer syntax of the series read (its name), "" before a successful update.
  const char* GetTransferSyntax();

  /// Warnings of the last update (uneven steps, gantry tilt), one per line; "" when none.
  const char* GetPlacementWarnings();

protected:
  vtkDSDICOMSeriesReader();
  ~vtkDSDICOMSeriesReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  /// Scans, chooses and stacks the series; false (the reason in the state) on bad input.
  bool FindVolume();

  char* FileName = nullptr;
  char* SeriesDescription = nullptr;
  struct State;
  std::unique_ptr<State> Internal;

  vtkDSDICOMSeriesReader(const vtkDSDICOMSeriesReader&) = delete;
  void operator=(const vtkDSDICOMSeriesReader&) = delete;
};

#endif
