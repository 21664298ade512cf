// SPDX-License-Identifier: BSD-3-Clause
// Writes a volume as a DICOM series (one CT Image Storage file per slice) with GDCM's
// gdcm::ImageWriter, for the DICOM reader's tests: geometry given in DICOM's own LPS frame,
// optional rescale, file names and Instance Numbers in any order, any transfer syntax GDCM can
// encode. GDCM writes decimal strings to their full 16 characters (gdcmElement.h, to_string).
#ifndef DICOMSeriesWriter_h
#define DICOMSeriesWriter_h

#include "gdcmAttribute.h"
#include "gdcmImage.h"
#include "gdcmImageChangeTransferSyntax.h"
#include "gdcmImageWriter.h"
#include "gdcmUIDGenerator.h"

#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkType.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace dstest
{
struct DicomSeriesSpec
{
  std::string Folder;
  std::string Description = "volume";
  std::string SeriesUID;            ///< generated when empty
  double Position[3] = { 0, 0, 0 }; ///< Image Position (Patient) of slice 0, LPS mm
  double Row[3] = { 1, 0, 0 };      ///< Image Orientation (Patient): along a row (LPS)
  double Column[3] = { 0, 1, 0 };   ///< along a column (LPS)
  double Spacing[3] = { 1, 1, 1 };  ///< between columns, between rows, between slices
  std::vector<double> SliceOffsets; ///< per slice along the normal; empty: k * Spacing[2]
  double Drift[3] = { 0, 0, 0 };    ///< added per slice to the position (a gantry tilt)
  double Slope = 1, Intercept = 0;  ///< written as Rescale Slope / Intercept
  gdcm::TransferSyntax::TSType Syntax = gdcm::TransferSyntax::ExplicitVRLittleEndian;
  std::vector<int> FileIndex;      ///< file name number of slice k; empty: k
  std::vector<int> InstanceNumber; ///< Instance Number of slice k; empty: k + 1
  std::vector<int> SkipSlices;     ///< slices not written (a partial series)
};

/// A DICOM spec placing the slices where `placed` (in the plugin's RAS world) has them: DICOM's
/// LPS is RAS with x and y negated (PS3.3 C.7.6.2.1.1; NIfTI-1 header, qform/sform).
inline DicomSeriesSpec DicomSpecFromWorld(vtkImageData* placed, const std::string& folder)
{
  DicomSeriesSpec s;
  s.Folder = folder;
  const double flip[3] = { -1, -1, 1 };
  vtkMatrix3x3* d = placed->GetDirectionMatrix();
  for (int i = 0; i < 3; ++i)
  {
    s.Position[i] = flip[i] * placed->GetOrigin()[i];
    s.Row[i] = flip[i] * d->GetElement(i, 0);
    s.Column[i] = flip[i] * d->GetElement(i, 1);
    s.Spacing[i] = placed->GetSpacing()[i];
  }
  return s;
}

/// The normal Row x Column.
inline void DicomNormal(const DicomSeriesSpec& s, double n[3])
{
  n[0] = s.Row[1] * s.Column[2] - s.Row[2] * s.Column[1];
  n[1] = s.Row[2] * s.Column[0] - s.Row[0] * s.Column[2];
  n[2] = s.Row[0] * s.Column[1] - s.Row[1] * s.Column[0];
}

inline void PutText(
  gdcm::DataSet& ds, uint16_t group, uint16_t element, const gdcm::VR& vr, std::string value)
{
  if (value.size() % 2)
  {
    value += vr == gdcm::VR::UI ? '\0' : ' ';
  }
  gdcm::DataElement de(gdcm::Tag(group, element));
  de.SetVR(vr);
  de.SetByteValue(value.data(), static_cast<uint32_t>(value.size()));
  ds.Replace(de);
}

/// The file of slice k of a series.
inline std::string DicomSliceFile(const DicomSeriesSpec& s, int k)
{
  const int index = s.FileIndex.empty() ? k : s.FileIndex[k];
  return s.Folder + "/slice" + std::to_string(1000 + index).substr(1) + ".dcm";
}

/// Writes the slices of `volume` (unsigned char or unsigned short scalars; its own placement is
/// ignored: the spec's is written). Returns "" or what failed.
inline std::string WriteDicomSeries(vtkImageData* volume, DicomSeriesSpec& s)
{
  std::filesystem::create_directories(s.Folder);
  gdcm::UIDGenerator uids;
  if (s.SeriesUID.empty())
  {
    s.SeriesUID = uids.Generate();
  }
  const std::string study = uids.Generate();
  int dims[3];
  volume->GetDimensions(dims);
  const bool wide = volume->GetScalarType() == VTK_UNSIGNED_SHORT;
  const size_t sliceBytes = size_t(dims[0]) * dims[1] * (wide ? 2 : 1);
  double normal[3];
  DicomNormal(s, normal);
  for (int k = 0; k < dims[2]; ++k)
  {
    if (std::find(s.SkipSlices.begin(), s.SkipSlices.end(), k) != s.SkipSlices.end())
    {
      continue;
    }
    gdcm::ImageWriter writer;
    gdcm::Image& image = writer.GetImage();
    image.SetNumberOfDimensions(2);
    image.SetDimension(0, static_cast<unsigned int>(dims[0]));
    image.SetDimension(1, static_cast<unsigned int>(dims[1]));
    image.SetPixelFormat(
      gdcm::PixelFormat(wide ? gdcm::PixelFormat::UINT16 : gdcm::PixelFormat::UINT8));
    image.SetPhotometricInterpretation(gdcm::PhotometricInterpretation::MONOCHROME2);
    image.SetTransferSyntax(gdcm::TransferSyntax::ExplicitVRLittleEndian);
    gdcm::DataElement pixels(gdcm::Tag(0x7fe0, 0x0010));
    pixels.SetByteValue(static_cast<const char*>(volume->GetScalarPointer(0, 0, k)),
      static_cast<uint32_t>(sliceBytes));
    image.SetDataElement(pixels);
    const double offset = s.SliceOffsets.empty() ? k * s.Spacing[2] : s.SliceOffsets[k];
    double position[3], cosines[6];
    for (int i = 0; i < 3; ++i)
    {
      position[i] = s.Position[i] + offset * normal[i] + k * s.Drift[i];
      cosines[i] = s.Row[i];
      cosines[3 + i] = s.Column[i];
    }
    image.SetOrigin(position);
    image.SetOrigin(2, position[2]);
    image.SetDirectionCosines(cosines);
    image.SetSpacing(0, s.Spacing[0]);
    image.SetSpacing(1, s.Spacing[1]);
    image.SetSpacing(2, s.Spacing[2]);
    image.SetSlope(s.Slope);
    image.SetIntercept(s.Intercept);

    gdcm::DataSet& ds = writer.GetFile().GetDataSet();
    PutText(ds, 0x0008, 0x0016, gdcm::VR::UI, "1.2.840.10008.5.1.4.1.1.2"); // CT Image Storage
    PutText(ds, 0x0008, 0x0018, gdcm::VR::UI, uids.Generate());
    PutText(ds, 0x0008, 0x0060, gdcm::VR::CS, "CT");
    PutText(ds, 0x0008, 0x103e, gdcm::VR::LO, s.Description);
    PutText(ds, 0x0020, 0x000d, gdcm::VR::UI, study);
    PutText(ds, 0x0020, 0x000e, gdcm::VR::UI, s.SeriesUID);
    PutText(ds, 0x0020, 0x0013, gdcm::VR::IS,
      std::to_string(s.InstanceNumber.empty() ? k + 1 : s.InstanceNumber[k]));

    if (s.Syntax != gdcm::TransferSyntax::ExplicitVRLittleEndian)
    {
      gdcm::ImageChangeTransferSyntax change;
      change.SetTransferSyntax(s.Syntax);
      change.SetInput(image);
      if (!change.Change())
      {
        return "GDCM cannot encode slice " + std::to_string(k) + " as " +
          gdcm::TransferSyntax::GetTSString(s.Syntax);
      }
      writer.SetImage(change.GetOutput());
    }
    const std::string file = DicomSliceFile(s, k);
    writer.SetFileName(file.c_str());
    if (!writer.Write())
    {
      return "GDCM cannot write " + file;
    }
  }
  return "";
}
} // namespace dstest

#endif
