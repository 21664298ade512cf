// SPDX-License-Identifier: BSD-3-Clause
// Test tool (not a test): writes a NIfTI volume as a DICOM series with GDCM, placed where the
// plugin's NIfTI reader (vtkDSNIFTIImageReader) puts it, so the DICOM reader must give back the
// same image in the same place. Python tests run it to make their DICOM folders.
//
//   DICOMFromNIfTI <in.nii[.gz]> <output folder> [jpeg2000]
//
// unsigned char or unsigned short volumes only (Colin27's ch2.nii.gz is unsigned char); with
// "jpeg2000" the slices are stored JPEG 2000 lossless.
#include "DICOMSeriesWriter.h"
#include "vtkDSNIFTIImageReader.h"

#include "gdcmTrace.h"

#include "vtkNew.h"

#include <cstring>
#include <iostream>

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: " << argv[0] << " <in.nii[.gz]> <output folder> [jpeg2000]" << std::endl;
    return 2;
  }
  gdcm::Trace::WarningOff();
  vtkNew<vtkDSNIFTIImageReader> reader;
  reader->SetFileName(argv[1]);
  reader->Update();
  vtkImageData* volume = reader->GetOutput();
  if (volume->GetScalarType() != VTK_UNSIGNED_CHAR && volume->GetScalarType() != VTK_UNSIGNED_SHORT)
  {
    std::cerr << argv[1] << ": only unsigned char or unsigned short volumes" << std::endl;
    return 1;
  }
  dstest::DicomSeriesSpec spec = dstest::DicomSpecFromWorld(volume, argv[2]);
  spec.Description = std::string("from ") + argv[1];
  if (argc > 3 && std::strcmp(argv[3], "jpeg2000") == 0)
  {
    spec.Syntax = gdcm::TransferSyntax::JPEG2000Lossless;
  }
  const std::string error = dstest::WriteDicomSeries(volume, spec);
  if (!error.empty())
  {
    std::cerr << error << std::endl;
    return 1;
  }
  std::cout << "wrote " << volume->GetDimensions()[2] << " slices to " << argv[2] << std::endl;
  return 0;
}
