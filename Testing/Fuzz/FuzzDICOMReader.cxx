// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkDSDICOMSeriesReader on a folder of mutated DICOM files.
//
// The input is a small series packed as records: a 4-byte little-endian length, then that many
// bytes of one file; the records become files slice0.dcm, slice1.dcm, ... of a scratch folder
// (at most 8; a length past the end takes what is left). The committed seeds
// (corpus/DICOMReader) are real series written with GDCM by Testing/Cxx/DICOMFromNIfTI, 8 x 8
// pixels, 3 slices, native, rescaled and JPEG 2000, so mutations hit headers, lengths, sequences,
// decimal strings and compressed streams. The folder is read, then its first file. The reader's
// promises: no crash or hang (GDCM aborts on damaged files unless dsDicomStructure stops them
// first); either an error and an empty output, or an image whose values fill its extent, with a
// finite origin, positive finite spacing and an orthonormal direction matrix.
#include "FuzzVTK.h"
#include "vtkDSDICOMSeriesReader.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace
{
const std::string& Scratch()
{
  static const std::string folder = []
  {
    char name[] = "/tmp/FuzzDICOMReader-XXXXXX";
    const char* made = mkdtemp(name);
    FUZZ_CHECK(made != nullptr, "cannot make a scratch folder");
    return std::string(made);
  }();
  return folder;
}

/// Unpacks the records into files of the emptied scratch folder; returns how many.
int Unpack(const uint8_t* data, size_t size)
{
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(Scratch(), ec))
  {
    std::filesystem::remove(entry.path(), ec);
  }
  int files = 0;
  size_t p = 0;
  while (p + 4 <= size && files < 8)
  {
    const size_t length = std::min<size_t>(size - p - 4,
      uint32_t(data[p]) | uint32_t(data[p + 1]) << 8 | uint32_t(data[p + 2]) << 16 |
        uint32_t(data[p + 3]) << 24);
    std::ofstream(Scratch() + "/slice" + std::to_string(files++) + ".dcm", std::ios::binary)
      .write(reinterpret_cast<const char*>(data + p + 4), static_cast<std::streamsize>(length));
    p += 4 + length;
  }
  return files;
}

void CheckRead(const std::string& name)
{
  vtkNew<vtkDSDICOMSeriesReader> reader;
  vtkNew<fuzzvtk::MessageCounter> messages;
  reader->AddObserver(vtkCommand::ErrorEvent, messages);
  reader->AddObserver(vtkCommand::WarningEvent, messages);
  reader->SetFileName(name.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (messages->Errors > 0)
  {
    FUZZ_CHECK(image->GetNumberOfPoints() == 0 && !image->GetPointData()->GetScalars(),
      "an error, yet a non-empty output");
    return;
  }
  vtkDataArray* values = image->GetPointData()->GetScalars();
  FUZZ_CHECK(values && values->GetNumberOfTuples() == image->GetNumberOfPoints() &&
      image->GetNumberOfPoints() > 0,
    "no error, yet the values do not fill the extent");
  vtkMatrix3x3* d = image->GetDirectionMatrix();
  for (int i = 0; i < 3; ++i)
  {
    FUZZ_CHECK(std::isfinite(image->GetOrigin()[i]), "a non-finite origin");
    FUZZ_CHECK(std::isfinite(image->GetSpacing()[i]) && image->GetSpacing()[i] > 0,
      "a spacing that is not positive and finite");
    for (int j = 0; j < 3; ++j)
    {
      const double dot = d->GetElement(0, i) * d->GetElement(0, j) +
        d->GetElement(1, i) * d->GetElement(1, j) + d->GetElement(2, i) * d->GetElement(2, j);
      FUZZ_CHECK(std::abs(dot - (i == j ? 1 : 0)) < 1e-2, "a direction matrix not orthonormal");
    }
  }
}
} // namespace

// GDCM 3.0's codecs leak on damaged compressed data: the JPEG 2000 codec does not destroy its
// OpenJPEG decoder (opj_create_decompress) when a codestream fails to decode, the JPEG-LS codec
// its buffers (gdcm::JPEGLSCodec::GetHeaderInfo, Decode), the JPEG codec strings. Leaks in the
// third-party library the reader cannot avoid; LeakSanitizer reads this hook. Leaks of the
// reader's own code (no GDCM codec on their allocation's stack) are still findings.
extern "C" const char* __lsan_default_suppressions()
{
  return "leak:gdcm::*Codec::\nleak:opj_create_decompress\nleak:libopenjp2.so\n";
}

// Whole allocation stacks: libc's strdup (which the JPEG codec calls) has no frame pointers, so
// the fast unwinder stops there and the suppressions above could not see the codec.
extern "C" const char* __asan_default_options()
{
  return "fast_unwind_on_malloc=0";
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (Unpack(data, size) == 0)
  {
    return 0;
  }
  CheckRead(Scratch());
  CheckRead(Scratch() + "/slice0.dcm");
  return 0;
}
