// SPDX-License-Identifier: BSD-3-Clause
// vtkDSDICOMSeriesReader on series written here with GDCM from a crop of Colin27 (64 x 64 x 20
// voxels of /usr/share/mricron/templates/ch2.nii.gz): every voxel back exactly and the
// placement (origin, direction, spacing) to 1e-4 mm, for a plain series placed where the
// plugin's NIfTI reader puts the crop (so DICOM and NIfTI line up), an oblique anisotropic one,
// integral and fractional rescales, shuffled file names and Instance Numbers, JPEG 2000
// lossless, JPEG lossless and RLE copies, two series in one folder; uneven steps and a gantry
// tilt give a warning; a missing slice, a truncated or damaged file, a mixed series, two slices at
// one position and an unsupported transfer syntax give an error and an empty output.
#include "DICOMSeriesWriter.h"
#include "DSTestHelpers.h"
#include "vtkDSDICOMSeriesReader.h"
#include "vtkDSNIFTIImageReader.h"

#include "gdcmReader.h"
#include "gdcmTrace.h"
#include "gdcmWriter.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>

namespace fs = std::filesystem;
using dstest::DicomSeriesSpec;

namespace
{
const char* const Colin = "/usr/share/mricron/templates/ch2.nii.gz";
const int CropStart[3] = { 58, 80, 80 }; // voxel of ch2 where the 64 x 64 x 20 crop starts
const int CropSize[3] = { 64, 64, 20 };

struct Messages
{
  int Errors = 0, Warnings = 0;
  std::string Text;
};

void Record(vtkObject*, unsigned long event, void* client, void* call)
{
  auto* m = static_cast<Messages*>(client);
  (event == vtkCommand::ErrorEvent ? m->Errors : m->Warnings) += 1;
  m->Text += std::string(call ? static_cast<const char*>(call) : "") + "\n";
}

struct Result
{
  vtkSmartPointer<vtkDSDICOMSeriesReader> Reader;
  vtkImageData* Image = nullptr;
  std::shared_ptr<Messages> Log = std::make_shared<Messages>(); // the observer writes here
};

Result ReadSeries(const std::string& fileName, const std::string& description = "")
{
  Result r;
  r.Reader = vtkSmartPointer<vtkDSDICOMSeriesReader>::New();
  vtkNew<vtkCallbackCommand> record;
  record->SetCallback(Record);
  record->SetClientData(r.Log.get());
  r.Reader->AddObserver(vtkCommand::ErrorEvent, record);
  r.Reader->AddObserver(vtkCommand::WarningEvent, record);
  r.Reader->SetFileName(fileName.c_str());
  r.Reader->SetSeriesDescription(description.c_str());
  r.Reader->Update();
  r.Image = r.Reader->GetOutput();
  return r;
}

/// The Colin27 crop, placed where the plugin's NIfTI reader puts those voxels.
vtkSmartPointer<vtkImageData> ColinCrop()
{
  vtkNew<vtkDSNIFTIImageReader> reader;
  reader->SetFileName(Colin);
  reader->Update();
  vtkImageData* head = reader->GetOutput();
  auto crop = vtkSmartPointer<vtkImageData>::New();
  crop->SetDimensions(CropSize);
  crop->SetSpacing(head->GetSpacing());
  crop->SetDirectionMatrix(head->GetDirectionMatrix());
  double origin[3];
  head->TransformIndexToPhysicalPoint(CropStart, origin);
  crop->SetOrigin(origin);
  crop->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  for (int k = 0; k < CropSize[2]; ++k)
    for (int j = 0; j < CropSize[1]; ++j)
      for (int i = 0; i < CropSize[0]; ++i)
      {
        *static_cast<unsigned char*>(crop->GetScalarPointer(i, j, k)) =
          *static_cast<unsigned char*>(
            head->GetScalarPointer(CropStart[0] + i, CropStart[1] + j, CropStart[2] + k));
      }
  return crop;
}

/// The crop's values as 16-bit stored values (for the rescale cases).
vtkSmartPointer<vtkImageData> Wide(vtkImageData* crop)
{
  auto wide = vtkSmartPointer<vtkImageData>::New();
  wide->SetDimensions(crop->GetDimensions());
  wide->AllocateScalars(VTK_UNSIGNED_SHORT, 1);
  for (vtkIdType i = 0; i < crop->GetNumberOfPoints(); ++i)
  {
    wide->GetPointData()->GetScalars()->SetTuple1(
      i, crop->GetPointData()->GetScalars()->GetTuple1(i) * 3 + 100);
  }
  return wide;
}

/// An oblique, anisotropic placement: turned about two axes, 0.9 x 0.8 mm pixels, 1.5 mm slices.
DicomSeriesSpec ObliqueSpec(const std::string& folder)
{
  DicomSeriesSpec s;
  s.Folder = folder;
  const double a = 30.0 * M_PI / 180, b = 20.0 * M_PI / 180;
  const double row[3] = { std::cos(a), std::sin(a), 0 };
  const double column[3] = { -std::sin(a) * std::cos(b), std::cos(a) * std::cos(b), std::sin(b) };
  for (int i = 0; i < 3; ++i)
  {
    s.Row[i] = row[i];
    s.Column[i] = column[i];
  }
  const double position[3] = { -101.25, 37.5, -12.345678901 };
  const double spacing[3] = { 0.9, 0.8, 1.5 };
  std::copy(position, position + 3, s.Position);
  std::copy(spacing, spacing + 3, s.Spacing);
  return s;
}

/// Origin, direction and spacing of the output against what the spec wrote, in RAS.
void CheckPlacement(vtkImageData* image, const DicomSeriesSpec& s, const std::string& what)
{
  const double flip[3] = { -1, -1, 1 };
  double normal[3];
  dstest::DicomNormal(s, normal);
  const double* axes[3] = { s.Row, s.Column, normal };
  double worst = 0;
  for (int i = 0; i < 3; ++i)
  {
    worst = std::max(worst, std::abs(image->GetOrigin()[i] - flip[i] * s.Position[i]));
    worst = std::max(worst, std::abs(image->GetSpacing()[i] - s.Spacing[i]));
    for (int j = 0; j < 3; ++j)
    {
      worst = std::max(
        worst, std::abs(image->GetDirectionMatrix()->GetElement(i, j) - flip[i] * axes[j][i]));
    }
  }
  DS_CHECK_LE(worst, 1e-4, what + ": largest placement error (mm, or direction cosine)");
}

/// Voxels exact: out = slope * stored + intercept, in the expected type.
void CheckValues(vtkImageData* image, vtkImageData* stored, double slope, double intercept,
  int type, const std::string& what)
{
  vtkDataArray* out = image->GetPointData()->GetScalars();
  DS_CHECK(out && out->GetNumberOfTuples() == stored->GetNumberOfPoints(),
    what + ": the output has every voxel");
  if (!out || out->GetNumberOfTuples() != stored->GetNumberOfPoints())
  {
    return;
  }
  DS_CHECK(out->GetDataType() == type,
    what + ": scalar type " + out->GetDataTypeAsString() + ", expected " +
      vtkImageScalarTypeNameMacro(type));
  vtkIdType wrong = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfTuples(); ++i)
  {
    const double expected = slope * stored->GetPointData()->GetScalars()->GetTuple1(i) + intercept;
    wrong += out->GetTuple1(i) != expected ? 1 : 0;
  }
  DS_CHECK(wrong == 0, what + ": " + std::to_string(wrong) + " voxels differ");
}

void CheckEmptyWithError(const Result& r, const std::string& expected, const std::string& what)
{
  std::cout << what << ": " << r.Log->Text;
  DS_CHECK(r.Log->Errors > 0, what + ": an error is reported");
  DS_CHECK(r.Log->Text.find(expected) != std::string::npos,
    what + ": the message names \"" + expected + "\"");
  DS_CHECK(r.Image->GetNumberOfPoints() == 0 && !r.Image->GetPointData()->GetScalars(),
    what + ": the output is empty");
}

std::string Fresh(const std::string& name)
{
  const char* root = std::getenv("DS_TEST_OUTPUT");
  const std::string folder = std::string(root ? root : ".") + "/dicom/" + name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

void Write(vtkImageData* volume, DicomSeriesSpec& s)
{
  const std::string error = dstest::WriteDicomSeries(volume, s);
  DS_CHECK(error.empty(), "writing " + s.Folder + ": " + error);
}

/// Rewrites a file's meta header to claim another transfer syntax (the data set unchanged).
void ClaimSyntax(const std::string& file, const std::string& uid)
{
  gdcm::Reader reader;
  reader.SetFileName(file.c_str());
  DS_CHECK(reader.Read(), "re-reading " + file);
  gdcm::File& f = reader.GetFile(); // a gdcm::Object: shared by reference, never copied
  dstest::PutText(f.GetHeader(), 0x0002, 0x0010, gdcm::VR::UI, uid);
  gdcm::Writer writer;
  writer.SetFile(f);
  writer.CheckFileMetaInformationOff();
  writer.SetFileName(file.c_str());
  DS_CHECK(writer.Write(), "rewriting " + file);
}

void Truncate(const std::string& file, double fraction)
{
  const auto size = fs::file_size(file);
  fs::resize_file(file, static_cast<uintmax_t>(size * fraction));
}

// ---------------------------------------------------------------------------------------------
void TestPlain(vtkImageData* crop)
{
  DicomSeriesSpec s = dstest::DicomSpecFromWorld(crop, Fresh("plain"));
  s.Description = "Colin27 crop";
  Write(crop, s);
  std::ofstream(s.Folder + "/README.txt") << "not a DICOM file: skipped\n";
  Result r = ReadSeries(s.Folder);
  DS_CHECK(r.Log->Errors == 0 && r.Log->Warnings == 0, "plain: no message: " + r.Log->Text);
  CheckValues(r.Image, crop, 1, 0, VTK_UNSIGNED_CHAR, "plain");
  CheckPlacement(r.Image, s, "plain");
  // The same voxels where the NIfTI reader put them (DICOM and NIfTI line up).
  double worst = 0;
  for (int i = 0; i < 3; ++i)
  {
    worst = std::max(worst, std::abs(r.Image->GetOrigin()[i] - crop->GetOrigin()[i]));
    for (int j = 0; j < 3; ++j)
    {
      worst = std::max(worst,
        std::abs(r.Image->GetDirectionMatrix()->GetElement(i, j) -
          crop->GetDirectionMatrix()->GetElement(i, j)));
    }
  }
  DS_CHECK_LE(worst, 1e-4, "plain: distance to the NIfTI reader's placement of the same voxels");
  // ch2's sform is MNI: the crop's first voxel at (-32, -45, 9), i.e. LPS (32, 45, 9) in DICOM.
  DS_CHECK_LE(
    std::abs(s.Position[0] - 32) + std::abs(s.Position[1] - 45) + std::abs(s.Position[2] - 9), 1e-9,
    "plain: Image Position (Patient) written, against LPS (32, 45, 9)");

  // Any one file of the series reads the whole series.
  Result one = ReadSeries(dstest::DicomSliceFile(s, 7));
  CheckValues(one.Image, crop, 1, 0, VTK_UNSIGNED_CHAR, "plain, opened by one file");
  DS_CHECK(std::string(one.Reader->GetTransferSyntax()).find("Explicit VR Little Endian") !=
      std::string::npos,
    std::string("plain: transfer syntax ") + one.Reader->GetTransferSyntax());
}

void TestOblique(vtkImageData* crop)
{
  DicomSeriesSpec s = ObliqueSpec(Fresh("oblique"));
  Write(crop, s);
  Result r = ReadSeries(s.Folder);
  DS_CHECK(r.Log->Errors == 0 && r.Log->Warnings == 0, "oblique: no message: " + r.Log->Text);
  CheckValues(r.Image, crop, 1, 0, VTK_UNSIGNED_CHAR, "oblique");
  CheckPlacement(r.Image, s, "oblique");
}

void TestRescale(vtkImageData* crop)
{
  vtkSmartPointer<vtkImageData> stored = Wide(crop);
  DicomSeriesSpec s = ObliqueSpec(Fresh("rescale-integral"));
  s.Slope = 2;
  s.Intercept = -1024; // CT: HU = 2 s - 1024 over 16 unsigned bits fits no 16-bit type
  Write(stored, s);
  Result r = ReadSeries(s.Folder);
  CheckValues(r.Image, stored, 2, -1024, VTK_INT, "rescale 2 s - 1024 (16-bit stored)");
  CheckPlacement(r.Image, s, "rescale 2 s - 1024");

  s = ObliqueSpec(Fresh("rescale-ct"));
  s.Intercept = -1024; // the usual CT rescale: s - 1024 fits a signed short
  Write(crop, s);
  r = ReadSeries(s.Folder);
  CheckValues(r.Image, crop, 1, -1024, VTK_SHORT, "rescale s - 1024 (8-bit stored)");

  s = ObliqueSpec(Fresh("rescale-fraction"));
  s.Slope = 0.25;
  s.Intercept = 0.5;
  Write(stored, s);
  r = ReadSeries(s.Folder);
  CheckValues(r.Image, stored, 0.25, 0.5, VTK_FLOAT, "rescale 0.25 s + 0.5");
}

void TestShuffled(vtkImageData* crop)
{
  DicomSeriesSpec s = ObliqueSpec(Fresh("shuffled"));
  for (int k = 0; k < CropSize[2]; ++k)
  {
    s.FileIndex.push_back((k * 7 + 3) % CropSize[2]);       // names out of slice order
    s.InstanceNumber.push_back((k * 11 + 5) % CropSize[2]); // and the numbers too
  }
  Write(crop, s);
  Result r = ReadSeries(s.Folder);
  CheckValues(r.Image, crop, 1, 0, VTK_UNSIGNED_CHAR, "shuffled file order");
  CheckPlacement(r.Image, s, "shuffled file order");
}

void TestCompressed(vtkImageData* crop)
{
  const struct
  {
    gdcm::TransferSyntax::TSType Syntax;
    const char* Folder;
    const char* Name;
  } cases[] = { { gdcm::TransferSyntax::JPEG2000Lossless, "jpeg2000", "JPEG 2000" },
    { gdcm::TransferSyntax::JPEGLosslessProcess14_1, "jpeg-lossless", "JPEG Lossless" },
    { gdcm::TransferSyntax::RLELossless, "rle", "RLE Lossless" } };
  for (const auto& c : cases)
  {
    DicomSeriesSpec s = ObliqueSpec(Fresh(c.Folder));
    s.Syntax = c.Syntax;
    Write(crop, s);
    Result r = ReadSeries(s.Folder);
    DS_CHECK(r.Log->Errors == 0, std::string(c.Name) + ": no error: " + r.Log->Text);
    CheckValues(r.Image, crop, 1, 0, VTK_UNSIGNED_CHAR, c.Name);
    CheckPlacement(r.Image, s, c.Name);
    DS_CHECK(std::string(r.Reader->GetTransferSyntax()).find(c.Name) != std::string::npos,
      std::string(c.Name) + ": the reader names the syntax: " + r.Reader->GetTransferSyntax());
  }
}

void TestTwoSeries(vtkImageData* crop)
{
  const std::string folder = Fresh("two-series");
  DicomSeriesSpec big = ObliqueSpec(folder);
  big.Description = "axial";
  Write(crop, big);
  DicomSeriesSpec small = dstest::DicomSpecFromWorld(crop, folder);
  small.Description = "scout";
  small.FileIndex = { 100, 101, 102, 103, 104 };
  vtkNew<vtkImageData> five;
  five->SetDimensions(CropSize[0], CropSize[1], 5);
  five->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  five->GetPointData()->GetScalars()->Fill(7);
  Write(five, small);

  Result r = ReadSeries(folder);
  DS_CHECK(r.Reader->GetNumberOfSeries() == 2, "two series found");
  CheckValues(r.Image, crop, 1, 0, VTK_UNSIGNED_CHAR, "two series: the largest by default");
  r = ReadSeries(folder, "scout");
  CheckValues(r.Image, five, 1, 0, VTK_UNSIGNED_CHAR, "two series: chosen by description");
  r = ReadSeries(dstest::DicomSliceFile(small, 2));
  CheckValues(r.Image, five, 1, 0, VTK_UNSIGNED_CHAR, "two series: opened by one of its files");
  CheckEmptyWithError(ReadSeries(folder, "sagittal"), "\"scout\"", "an unknown description");
}

void TestUnevenAndTilted(vtkImageData* crop)
{
  DicomSeriesSpec s = ObliqueSpec(Fresh("uneven"));
  for (int k = 0; k < CropSize[2]; ++k)
  {
    s.SliceOffsets.push_back(k * 1.5 + (k >= 10 ? 0.3 : 0.0)); // one step of 1.8 mm
  }
  Write(crop, s);
  Result r = ReadSeries(s.Folder);
  std::cout << "uneven: " << r.Log->Text;
  DS_CHECK(r.Log->Errors == 0 && r.Log->Warnings == 1, "uneven steps: one warning, no error");
  DS_CHECK(
    r.Log->Text.find("uneven slice steps") != std::string::npos, "uneven: the warning says so");
  CheckValues(r.Image, crop, 1, 0, VTK_UNSIGNED_CHAR, "uneven steps: the image still read");
  DS_CHECK_LE(std::abs(r.Image->GetSpacing()[2] - (19 * 1.5 + 0.3) / 19), 1e-9,
    "uneven: the slice spacing is the mean step (mm)");

  s = ObliqueSpec(Fresh("tilted"));
  for (int i = 0; i < 3; ++i)
  {
    s.Drift[i] = 0.2 * s.Column[i]; // a gantry tilt: 0.2 mm along the columns per 1.5 mm slice
  }
  Write(crop, s);
  r = ReadSeries(s.Folder);
  std::cout << "tilted: " << r.Log->Text;
  DS_CHECK(r.Log->Errors == 0 && r.Log->Warnings == 1, "gantry tilt: one warning, no error");
  DS_CHECK(r.Log->Text.find("gantry tilt") != std::string::npos, "tilt: the warning says so");
  CheckValues(r.Image, crop, 1, 0, VTK_UNSIGNED_CHAR, "gantry tilt: the image still read");
}

void TestBadSeries(vtkImageData* crop)
{
  DicomSeriesSpec s = ObliqueSpec(Fresh("missing-slice"));
  s.SkipSlices = { 12 };
  Write(crop, s);
  CheckEmptyWithError(ReadSeries(s.Folder),
    "missing slice: between " + dstest::DicomSliceFile(s, 11) + " (at", "a missing slice");

  s = ObliqueSpec(Fresh("truncated"));
  Write(crop, s);
  Truncate(dstest::DicomSliceFile(s, 9), 0.6);
  CheckEmptyWithError(ReadSeries(s.Folder), dstest::DicomSliceFile(s, 9) + " is truncated",
    "a file cut in its pixel data");

  s = ObliqueSpec(Fresh("damaged"));
  Write(crop, s);
  Truncate(dstest::DicomSliceFile(s, 4), 0.1);
  CheckEmptyWithError(ReadSeries(s.Folder), dstest::DicomSliceFile(s, 4) + " is truncated",
    "a file cut in its header");

  // Cut inside the preamble: nothing says DICOM any more, the gap names the unreadable file.
  s = ObliqueSpec(Fresh("cut-preamble"));
  Write(crop, s);
  Truncate(dstest::DicomSliceFile(s, 4), 0.02);
  CheckEmptyWithError(ReadSeries(s.Folder), "not DICOM: " + dstest::DicomSliceFile(s, 4),
    "a file cut in its preamble");

  // One series UID, two image sizes.
  s = ObliqueSpec(Fresh("mixed"));
  Write(crop, s);
  DicomSeriesSpec other = s;
  other.FileIndex = { 50 };
  vtkNew<vtkImageData> narrow;
  narrow->SetDimensions(32, CropSize[1], 1);
  narrow->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  narrow->GetPointData()->GetScalars()->Fill(1);
  Write(narrow, other);
  CheckEmptyWithError(ReadSeries(s.Folder), "32 x 64 pixels", "a mixed series");

  s = ObliqueSpec(Fresh("same-position"));
  Write(crop, s);
  fs::copy_file(dstest::DicomSliceFile(s, 3), s.Folder + "/copy.dcm");
  CheckEmptyWithError(ReadSeries(s.Folder), "same position", "a slice twice");

  s = ObliqueSpec(Fresh("mpeg2"));
  Write(crop, s);
  for (int k = 0; k < CropSize[2]; ++k)
  {
    ClaimSyntax(dstest::DicomSliceFile(s, k), "1.2.840.10008.1.2.4.100");
  }
  CheckEmptyWithError(ReadSeries(s.Folder), "MPEG2", "an unsupported transfer syntax");

  CheckEmptyWithError(ReadSeries(Fresh("empty-folder")), "no DICOM image", "an empty folder");
  CheckEmptyWithError(ReadSeries("/nonexistent/dicom"), "does not exist", "no such folder");

  // A reader that read a good series, given a bad one, empties its output.
  DicomSeriesSpec good = ObliqueSpec(Fresh("good-then-bad"));
  Write(crop, good);
  Result r = ReadSeries(good.Folder);
  r.Reader->SetFileName(s.Folder.c_str());
  r.Reader->Update();
  DS_CHECK(r.Reader->GetOutput()->GetNumberOfPoints() == 0 && r.Log->Errors == 1,
    "good then bad: empty output, one error");
}
} // namespace

int main()
{
  if (!fs::exists(Colin))
  {
    std::cerr << Colin << " is missing (Debian package mricron-data)" << std::endl;
    return EXIT_FAILURE;
  }
  gdcm::Trace::WarningOff(); // the writer's notes on defaults it fills in
  vtkSmartPointer<vtkImageData> crop = ColinCrop();
  TestPlain(crop);
  TestOblique(crop);
  TestRescale(crop);
  TestShuffled(crop);
  TestCompressed(crop);
  TestTwoSeries(crop);
  TestUnevenAndTilted(crop);
  TestBadSeries(crop);
  return dstest::Result("TestDICOMSeriesReader");
}
