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
 * The plugin's "NIfTI Image Reader (Deformable Surface)" is this class.
 */
#ifndef vtkDSNIFTIImageReader_h
#define vtkDSNIFTIImageReader_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "vtkNIFTIImageReader.h"

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

protected:
  vtkDSNIFTIImageReader() = default;
  ~vtkDSNIFTIImageReader() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  /// The rotation R (row-major) and translation t of the usable matrix; false when none is.
  bool FileOrientation(double rotation[9], double translation[3]);
  const char* OrientationSource = "none";

  vtkDSNIFTIImageReader(const vtkDSNIFTIImageReader&) = delete;
  void operator=(const vtkDSNIFTIImageReader&) = delete;
};

#endif
