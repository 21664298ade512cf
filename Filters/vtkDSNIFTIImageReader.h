// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkDSNIFTIImageReader
 * @brief   vtkNIFTIImageReader that places the image where the file says: the qform/sform
 *          orientation becomes the image's direction matrix and origin.
 *
 * VTK's vtkNIFTIImageReader reads the voxels and the spacing but leaves the image axis-aligned
 * at the origin; the file's orientation is only offered as GetQFormMatrix()/GetSFormMatrix().
 * This reader applies it, so surfaces land in scanner (or template) coordinates and line up with
 * other data there, and oblique scans keep their orientation. The sform is used when the file
 * marks it as meant (sform_code > 0: templates and atlases keep their standard space there) and
 * it is a rotation (orthonormal, positive determinant, to 1e-4); otherwise the qform when
 * qform_code > 0; otherwise the image stays axis-aligned at the origin, as with VTK's reader. Both
 * matrices map VTK's data coordinates (origin + index x spacing, slices already reordered for qfac)
 * to the file's world, so world = R (origin + ijk spacing) + t: the output's direction matrix is R
 * and its origin R origin + t.
 *
 * Before VTK's reader runs, the file is checked (dsNiftiHeader.h), because VTK's reader trusts
 * the header: an unknown datatype or absurd dims crash or abort the process, a truncated file is
 * read in part. Refused with an error naming the field, and an empty output: a datatype VTK does
 * not read or a bitpix that does not match it; dim[0] outside 1..7, a dim not positive; data
 * (the product of the dims times the bytes per voxel) beyond the file (a gzip stream is
 * decompressed up to the data's end to tell, so a .nii.gz takes twice as long to read) or beyond
 * MaximumDataSize; a negative vox_offset or one beyond the file; a non-finite pixdim,
 * quatern/qoffset (qform_code > 0) or srow (sform_code > 0); a file that is not NIfTI-1, NIfTI-2 or
 * Analyze 7.5 at all. Accepted with a warning: pixdim 0 or negative on a used spatial axis, read
 * with spacing 1 there. Both byte orders. An error while VTK reads (e.g. a damaged gzip stream)
 * also leaves the output empty, so nothing downstream runs on part of a file.
 *
 * The plugin's "NIfTI Image Reader (Deformable Surface)" is this class.
 */
#ifndef vtkDSNIFTIImageReader_h
#define vtkDSNIFTIImageReader_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "vtkNIFTIImageReader.h"

#include <string> // for the file names

class DEFORMABLESURFACEFILTERS_EXPORT vtkDSNIFTIImageReader : public vtkNIFTIImageReader
{
public:
  static vtkDSNIFTIImageReader* New();
  vtkTypeMacro(vtkDSNIFTIImageReader, vtkNIFTIImageReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Which of the file's matrices placed the image after the last update: "qform", "sform" or
   * "none" (axis-aligned at the origin).
   */
  const char* GetOrientationSource() const { return this->OrientationSource; }

  ///@{
  /**
   * The largest data a file may describe, in bytes (the product of its dims times the bytes per
   * voxel, every dimension counted); larger is refused before anything is allocated. A fixed
   * number, not the machine's free memory, so a file gets the same verdict everywhere; a
   * negative value counts as 0. Default 17 179 869 184 (16 GiB).
   */
  vtkSetMacro(MaximumDataSize, vtkIdType);
  vtkGetMacro(MaximumDataSize, vtkIdType);
  ///@}

protected:
  vtkDSNIFTIImageReader() = default;
  ~vtkDSNIFTIImageReader() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  /// The checks of dsurf::CheckNiftiFile on the files VTK's reader would open, its warnings
  /// reported; false (and an error) when the file must not be read. `unitSpacing`: the axes
  /// whose pixdim is not positive.
  bool CheckFile(bool unitSpacing[3]);
  /// The header and data files VTK's reader opens (by its rules: FileNames, or a .hdr beside an
  /// .img, .gz or not); false when it has no name to go by (it then says so itself).
  bool FilesToRead(std::string& headerFile, std::string& dataFile);
  /// An empty output and no extent, so nothing downstream runs on a previous or partial image.
  static void ClearOutput(vtkInformation* outInfo);
  /// The rotation R (row-major) and translation t of the usable matrix; false when none is.
  bool FileOrientation(double rotation[9], double translation[3]);
  const char* OrientationSource = "none";
  vtkIdType MaximumDataSize = vtkIdType(16) << 30;

  vtkDSNIFTIImageReader(const vtkDSNIFTIImageReader&) = delete;
  void operator=(const vtkDSNIFTIImageReader&) = delete;
};

#endif
