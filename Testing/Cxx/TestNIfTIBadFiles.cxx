// SPDX-License-Identifier: BSD-3-Clause
// Corrupt NIfTI files through vtkDSNIFTIImageReader (the plugin's reader): each must give an
// error naming the spoiled field and an empty output, never a crash (before the checks, datatype
// 1234 killed ParaView, dims 30000^3 aborted it, a truncated file was solved on in part). The files
// are made from a small synthetic volume written by VTK's own writer, one header field spoiled
// at its nifti1.h offset; gzipped variants too. pixdim 0 or negative must give a warning and
// spacing 1. Valid files in the other byte order and as NIfTI-2 must read as the original.
// An error while VTK reads (the file cut between the header pass and the data pass) must
// leave the output empty as well.
#include "DSTestHelpers.h"

#include "dsNiftiHeader.h"
#include "vtkDSNIFTIImageReader.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkImageCast.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkNIFTIImageWriter.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"
#include "vtk_zlib.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace
{
using Bytes = std::vector<unsigned char>;

class MessageLog : public vtkCommand
{
public:
  static MessageLog* New() { return new MessageLog; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings)
      .push_back(data ? static_cast<const char*>(data) : "");
  }
  std::vector<std::string> Errors, Warnings;
};

std::string OutputDir()
{
  const char* dir = std::getenv("DS_TEST_OUTPUT");
  return dir ? dir : ".";
}

/// The synthetic valid volume: 12 x 10 x 8 int16 (1 920 bytes of data), spacing 0.8 0.9 1.1, a
/// qform (qform_code 1) and an sform (sform_code 2), written by VTK's writer.
Bytes ValidFile(int version)
{
  vtkNew<vtkRTAnalyticSource> source;
  source->SetWholeExtent(0, 11, 0, 9, 0, 7);
  vtkNew<vtkImageCast> cast;
  cast->SetInputConnection(source->GetOutputPort());
  cast->SetOutputScalarTypeToShort();
  cast->Update();
  vtkNew<vtkImageData> image;
  image->DeepCopy(cast->GetOutput());
  image->SetSpacing(0.8, 0.9, 1.1);
  vtkNew<vtkMatrix4x4> placement;
  placement->SetElement(0, 3, -20.0);
  placement->SetElement(1, 3, 5.0);
  const std::string path = OutputDir() + "/nifti_valid_v" + std::to_string(version) + ".nii";
  vtkNew<vtkNIFTIImageWriter> writer;
  writer->SetInputData(image);
  writer->SetQFormMatrix(placement);
  writer->SetSFormMatrix(placement);
  writer->SetNIFTIVersion(version);
  writer->SetFileName(path.c_str());
  writer->Write();
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

template <typename T>
void Put(Bytes& bytes, std::size_t offset, T value)
{
  std::memcpy(bytes.data() + offset, &value, sizeof(T));
}

std::string Write(const std::string& name, const Bytes& bytes, bool gzip)
{
  const std::string path = OutputDir() + "/" + name + (gzip ? ".nii.gz" : ".nii");
  if (gzip)
  {
    gzFile out = gzopen(path.c_str(), "wb");
    gzwrite(out, bytes.data(), static_cast<unsigned>(bytes.size()));
    gzclose(out);
  }
  else
  {
    std::ofstream(path, std::ios::binary)
      .write(
        reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  return path;
}

struct Outcome
{
  MessageLog* Log;
  vtkIdType Points;
  double Spacing[3];
  Bytes Scalars;
};

Outcome Read(vtkDSNIFTIImageReader* reader, MessageLog* log, const std::string& path)
{
  log->Errors.clear();
  log->Warnings.clear();
  reader->SetFileName(path.c_str());
  reader->Update();
  Outcome outcome{ log, reader->GetOutput()->GetNumberOfPoints(), { 0, 0, 0 }, {} };
  reader->GetOutput()->GetSpacing(outcome.Spacing);
  vtkDataArray* scalars = reader->GetOutput()->GetPointData()->GetScalars();
  if (scalars)
  {
    const auto* first = static_cast<const unsigned char*>(scalars->GetVoidPointer(0));
    outcome.Scalars.assign(first, first + scalars->GetDataSize() * scalars->GetDataTypeSize());
  }
  return outcome;
}

bool Contains(const std::vector<std::string>& messages, const std::string& part)
{
  return std::any_of(messages.begin(), messages.end(),
    [&part](const std::string& m) { return m.find(part) != std::string::npos; });
}

/// A spoiled file: an error containing `field`, and an empty output.
void ExpectRefused(const std::string& name, const Bytes& bytes, bool gzip, const std::string& field)
{
  vtkNew<vtkDSNIFTIImageReader> reader;
  vtkNew<MessageLog> log;
  reader->AddObserver(vtkCommand::ErrorEvent, log);
  reader->AddObserver(vtkCommand::WarningEvent, log);
  const Outcome out = Read(reader, log, Write(name, bytes, gzip));
  std::cout << name << (gzip ? " (gzip)" : "") << ": " << out.Points << " points; "
            << (log->Errors.empty() ? "no error" : log->Errors.back()) << std::endl;
  DS_CHECK(Contains(log->Errors, field), name + ": an error naming '" + field + "'");
  DS_CHECK(out.Points == 0, name + ": the output is empty");
}

/// Byte-swaps the nifti1.h fields VTK's reader swaps, and the int16 data: the same file as a
/// machine of the other byte order writes it.
Bytes OtherByteOrder(Bytes bytes)
{
  auto swap = [&bytes](std::size_t offset, std::size_t width, std::size_t count)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      std::reverse(bytes.begin() + offset + k * width, bytes.begin() + offset + (k + 1) * width);
    }
  };
  swap(0, 4, 1);                          // sizeof_hdr
  swap(32, 4, 1);                         // extents
  swap(36, 2, 1);                         // session_error
  swap(40, 2, 8);                         // dim
  swap(56, 4, 3);                         // intent_p1..3
  swap(68, 2, 4);                         // intent_code, datatype, bitpix, slice_start
  swap(76, 4, 11);                        // pixdim, vox_offset, scl_slope, scl_inter
  swap(120, 2, 1);                        // slice_end
  swap(124, 4, 6);                        // cal_max, cal_min, slice_duration, toffset, glmax, glmin
  swap(252, 2, 2);                        // qform_code, sform_code
  swap(256, 4, 18);                       // quatern_b..qoffset_z, srow_x, srow_y, srow_z
  swap(352, 2, (bytes.size() - 352) / 2); // the int16 voxels
  return bytes;
}

void CheckSpoiledHeaders(const Bytes& valid)
{
  Bytes b = valid;
  Put<int16_t>(b, 70, 1234); // datatype
  ExpectRefused("nifti_datatype_1234", b, false, "datatype 1234");

  b = valid;
  Put<int16_t>(b, 72, 8); // bitpix 8 for int16
  ExpectRefused("nifti_bitpix_8", b, false, "bitpix");

  b = valid;
  Put<int16_t>(b, 40, 9); // dim[0]
  ExpectRefused("nifti_dim0_9", b, false, "dim[0]");

  b = valid;
  Put<int16_t>(b, 44, -10); // dim[2]
  ExpectRefused("nifti_negative_dim", b, false, "dim[2] is -10");

  b = valid;
  Put<float>(b, 80, std::numeric_limits<float>::quiet_NaN()); // pixdim[1]
  ExpectRefused("nifti_nan_pixdim", b, false, "pixdim[1]");

  b = valid;
  Put<float>(b, 300, std::numeric_limits<float>::quiet_NaN()); // srow_y[1]
  ExpectRefused("nifti_nan_sform", b, false, "srow_y[1]");

  b = valid;
  Put<float>(b, 256, std::numeric_limits<float>::infinity()); // quatern_b
  ExpectRefused("nifti_inf_quatern", b, false, "quatern_b");

  b = valid;
  Put<float>(b, 108, 1.0e6f); // vox_offset
  ExpectRefused("nifti_vox_offset_beyond", b, false, "vox_offset");

  b = valid;
  Put<float>(b, 108, -352.0f);
  ExpectRefused("nifti_vox_offset_negative", b, false, "vox_offset");

  const std::string text = "This is a text file that someone named .nii by mistake.\n";
  Bytes notNifti;
  while (notNifti.size() < 1000)
  {
    notNifti.insert(notNifti.end(), text.begin(), text.end());
  }
  ExpectRefused("nifti_not_a_nifti_file", notNifti, false, "not a NIfTI file");
  ExpectRefused(
    "nifti_short_file", Bytes(valid.begin(), valid.begin() + 200), false, "not a NIfTI file");
}

/// The size cases, plain and gzipped: data cut short, and dims that describe far more data than
/// the file (and any memory) holds.
void CheckSizes(const Bytes& valid)
{
  for (bool gzip : { false, true })
  {
    const Bytes truncated(valid.begin(), valid.end() - 1000);
    ExpectRefused("nifti_truncated", truncated, gzip, "truncated");

    Bytes huge(valid.begin(), valid.begin() + 352 + 1000); // 1 000 bytes of data
    for (std::size_t axis = 1; axis <= 3; ++axis)
    {
      Put<int16_t>(huge, 40 + 2 * axis, 30000);
    }
    ExpectRefused("nifti_huge_dims", huge, gzip, "MaximumDataSize");

    Bytes beyond = valid;
    Put<float>(beyond, 108, 1.0e6f);
    ExpectRefused("nifti_vox_offset_beyond", beyond, gzip, "vox_offset");
  }

  // dims within the cap but beyond the data: found by reading the gzip stream, not its trailer.
  Bytes longer = valid;
  Put<int16_t>(longer, 46, 9); // dim[3] 8 -> 9
  ExpectRefused("nifti_dims_beyond_data", longer, true, "truncated");

  // A damaged gzip stream: its compressed bytes overwritten after the header.
  const std::string gz = Write("nifti_damaged_stream", valid, true);
  std::ifstream in(gz, std::ios::binary);
  Bytes raw(std::istreambuf_iterator<char>(in), {});
  std::fill(raw.begin() + raw.size() / 2, raw.end() - 8, 0xA5);
  std::ofstream(gz, std::ios::binary)
    .write(reinterpret_cast<const char*>(raw.data()), static_cast<std::streamsize>(raw.size()));
  vtkNew<vtkDSNIFTIImageReader> reader;
  vtkNew<MessageLog> log;
  reader->AddObserver(vtkCommand::ErrorEvent, log);
  const Outcome out = Read(reader, log, gz);
  std::cout << "damaged gzip stream: " << out.Points << " points; "
            << (log->Errors.empty() ? "no error" : log->Errors.back()) << std::endl;
  DS_CHECK(!log->Errors.empty() && out.Points == 0, "a damaged gzip stream: error, empty output");

  // The cap is the reader's property: the valid file refused below its size.
  vtkNew<vtkDSNIFTIImageReader> capped;
  capped->SetMaximumDataSize(1000);
  capped->AddObserver(vtkCommand::ErrorEvent, log);
  const Outcome small = Read(capped, log, Write("nifti_capped", valid, false));
  DS_CHECK(Contains(log->Errors, "MaximumDataSize (1000 bytes)") && small.Points == 0,
    "MaximumDataSize 1000 refuses 1 920 bytes of data");
}

/// pixdim 0 and negative: read, with a warning naming the field and spacing 1 on that axis.
void CheckUnitSpacing(const Bytes& valid, const Outcome& reference)
{
  for (float bad : { 0.0f, -2.0f })
  {
    Bytes b = valid;
    Put<float>(b, 84, bad); // pixdim[2]
    vtkNew<vtkDSNIFTIImageReader> reader;
    vtkNew<MessageLog> log;
    reader->AddObserver(vtkCommand::ErrorEvent, log);
    reader->AddObserver(vtkCommand::WarningEvent, log);
    const Outcome out =
      Read(reader, log, Write(bad == 0 ? "nifti_pixdim_zero" : "nifti_pixdim_negative", b, false));
    std::cout << "pixdim[2] " << bad << ": " << out.Points << " points, spacing " << out.Spacing[0]
              << " " << out.Spacing[1] << " " << out.Spacing[2] << "; "
              << (log->Warnings.empty() ? "no warning" : log->Warnings.front()) << std::endl;
    DS_CHECK(log->Errors.empty(), "pixdim 0 or negative is no error");
    DS_CHECK(Contains(log->Warnings, "pixdim[2]") && Contains(log->Warnings, "spacing 1"),
      "a warning naming pixdim[2] and saying spacing 1");
    DS_CHECK(out.Spacing[1] == 1.0 && std::abs(out.Spacing[0] - 0.8) < 1e-6 &&
        std::abs(out.Spacing[2] - 1.1) < 1e-6,
      "spacing 1 on y only");
    DS_CHECK(out.Scalars == reference.Scalars, "the voxels read as from the intact file");
  }
}

/// A reader error after the header pass leaves an empty output: the file cut between
/// UpdateInformation and Update (VTK's "NIFTI file is truncated"), and a good file replaced by
/// a bad one on the same reader (the previous image must not stay).
void CheckDownstreamStops(const Bytes& valid)
{
  vtkNew<vtkDSNIFTIImageReader> reader;
  vtkNew<MessageLog> log;
  reader->AddObserver(vtkCommand::ErrorEvent, log);
  const std::string path = Write("nifti_cut_while_read", valid, false);
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  Write("nifti_cut_while_read", Bytes(valid.begin(), valid.end() - 1000), false);
  reader->Update();
  std::cout << "cut between the passes: " << reader->GetOutput()->GetNumberOfPoints() << " points; "
            << (log->Errors.empty() ? "no error" : log->Errors.back()) << std::endl;
  DS_CHECK(Contains(log->Errors, "truncated"), "VTK's reader reports the truncation");
  DS_CHECK(reader->GetOutput()->GetNumberOfPoints() == 0, "nothing of the part read is kept");

  vtkNew<vtkDSNIFTIImageReader> reused;
  reused->AddObserver(vtkCommand::ErrorEvent, log);
  const Outcome good = Read(reused, log, Write("nifti_reused_good", valid, false));
  Bytes bad = valid;
  Put<int16_t>(bad, 70, 1234);
  const Outcome after = Read(reused, log, Write("nifti_reused_bad", bad, false));
  DS_CHECK(good.Points == 960 && after.Points == 0,
    "a bad file after a good one: the good image does not stay");
}

/// The same volume big-endian and as NIfTI-2: the same voxels and spacing; spoiled NIfTI-2 and
/// big-endian headers refused.
void CheckOtherLayouts(const Bytes& valid, const Outcome& reference)
{
  vtkNew<vtkDSNIFTIImageReader> reader;
  vtkNew<MessageLog> log;
  reader->AddObserver(vtkCommand::ErrorEvent, log);
  reader->AddObserver(vtkCommand::WarningEvent, log);
  const Bytes big = OtherByteOrder(valid);
  const Outcome swapped = Read(reader, log, Write("nifti_big_endian", big, true));
  DS_CHECK(log->Errors.empty() && swapped.Scalars == reference.Scalars &&
      swapped.Spacing[2] == reference.Spacing[2],
    "a big-endian file reads as the little-endian one");
  Bytes bigBad = big;
  Put<int16_t>(bigBad, 44, static_cast<int16_t>(0xF6FF)); // dim[2] = -10 big-endian
  ExpectRefused("nifti_big_endian_negative_dim", bigBad, false, "dim[2] is -10");

  const Bytes v2 = ValidFile(2);
  dsurf::NiftiHeader header;
  DS_CHECK(dsurf::ParseNiftiHeader(v2.data(), v2.size(), header).empty() && header.Version == 2 &&
      header.Dim[1] == 12,
    "the NIfTI-2 header is decoded");
  const Outcome two = Read(reader, log, Write("nifti_version2", v2, false));
  DS_CHECK(log->Errors.empty() && two.Scalars == reference.Scalars, "NIfTI-2 reads as NIfTI-1");
  // quatern_c 1e200: b^2 + c^2 + d^2 overflows and VTK's qform matrix is NaN; not a rotation,
  // so the image stays at the origin (the refused matrix must not place it).
  Bytes v2wild = v2;
  Put<int32_t>(v2wild, 348, 0);          // sform_code: the qform alone
  Put<double>(v2wild, 352 + 8, 1.0e200); // quatern_c
  const Outcome wild = Read(reader, log, Write("nifti_version2_wild_quatern", v2wild, false));
  double origin[3];
  reader->GetOutput()->GetOrigin(origin);
  std::cout << "NIfTI-2, quatern_c 1e200: " << wild.Points << " points, origin " << origin[0] << " "
            << origin[1] << " " << origin[2] << ", placed by " << reader->GetOrientationSource()
            << std::endl;
  DS_CHECK(wild.Points == 960 && origin[0] == 0 && origin[1] == 0 && origin[2] == 0 &&
      std::string(reader->GetOrientationSource()) == "none",
    "a NaN qform matrix does not place the image");
  Bytes v2bad = v2;
  Put<int64_t>(v2bad, 16 + 8 * 3, 0); // dim[3]
  ExpectRefused("nifti_version2_zero_dim", v2bad, false, "dim[3] is 0");
  Put<int64_t>(v2bad, 16 + 8 * 3, int64_t(1) << 40);
  ExpectRefused("nifti_version2_huge_dim", v2bad, true, "dim[3]");
}
} // namespace

/// The field checks on decoded headers, without files: the size product saturates instead of
/// wrapping, types VTK has no scalar type for are refused, dims above dim[0] do not count.
void CheckCore()
{
  dsurf::NiftiHeader header;
  header.Version = 1;
  header.DataType = 16; // FLOAT32
  header.BitPix = 32;
  header.Dim[0] = 7;
  std::fill(header.Dim + 1, header.Dim + 8, 32767);
  dsurf::NiftiVerdict verdict = dsurf::CheckNiftiHeader(header, uint64_t(1) << 34);
  std::cout << "seven dims of 32767: " << verdict.Error << std::endl;
  DS_CHECK(verdict.Error.find("more than 2^64 bytes") != std::string::npos,
    "32767^7 voxels: the size saturates, it does not wrap to a small number");
  header.Dim[0] = 2;
  header.Dim[3] = -5; // beyond dim[0]: unused
  header.PixDim[1] = header.PixDim[2] = 1.0;
  header.PixDim[3] = 0.0; // unused axis: spacing 1, no warning
  verdict = dsurf::CheckNiftiHeader(header, uint64_t(1) << 34);
  DS_CHECK(verdict.Error.empty() && verdict.Warnings.empty() && verdict.UnitSpacing[2] &&
      verdict.DataSize == 4ull * 32767 * 32767,
    "a 2-D header: dims and pixdim past dim[0] are not checked, its data size 4 x 32767^2");
  for (int unread : { 1, 1536, 2048 }) // BINARY, FLOAT128, COMPLEX256
  {
    DS_CHECK(
      dsurf::NiftiBytesPerVoxel(unread) == 0, "no VTK type for datatype " + std::to_string(unread));
  }
}

int TestNIfTIBadFiles(int, char*[])
{
  CheckCore();
  const Bytes valid = ValidFile(1);
  DS_CHECK(valid.size() == 352 + 1920, "the synthetic file: 352 bytes of header, 1 920 of data");

  vtkNew<vtkDSNIFTIImageReader> reader;
  vtkNew<MessageLog> log;
  reader->AddObserver(vtkCommand::ErrorEvent, log);
  reader->AddObserver(vtkCommand::WarningEvent, log);
  const Outcome reference = Read(reader, log, Write("nifti_intact", valid, false));
  DS_CHECK(log->Errors.empty() && log->Warnings.empty() && reference.Points == 960,
    "the intact file reads without a message");
  const Outcome gzipped = Read(reader, log, Write("nifti_intact", valid, true));
  DS_CHECK(log->Errors.empty() && gzipped.Scalars == reference.Scalars,
    "the intact file gzipped reads the same");

  CheckSpoiledHeaders(valid);
  CheckSizes(valid);
  CheckUnitSpacing(valid, reference);
  CheckDownstreamStops(valid);
  CheckOtherLayouts(valid, reference);
  return dstest::Result("TestNIfTIBadFiles");
}

int main(int argc, char* argv[])
{
  return TestNIfTIBadFiles(argc, argv);
}
