// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkDSNIFTIImageReader, the plugin's reader of the NIfTI files users open.
//
// The first byte of an input chooses how the rest becomes a file (VTK's reader takes a file
// name): 0 the bytes as they are (.nii), 1 the bytes gzip-compressed (.nii.gz: the header
// checks and the stream reading of a compressed file), 2 the bytes as a .nii.gz themselves (a
// damaged or cut gzip stream). The reader's cap is 64 MiB, far below the -rss_limit_mb of
// scripts/fuzz.sh, so an allocation the checks let through beyond it shows as a finding.
// The reader's promises: no crash; either an error and an empty output, or no error and an
// image of finite, positive spacing, finite origin and direction, one scalar tuple per point,
// and no more bytes than the cap. (VTK's own reader is not instrumented: a crash in it shows, a
// silent over-read inside it does not.) Seeds: corpus/NIfTIReader, from MakeNIfTICorpus.py.
#include "FuzzVTK.h"
#include "vtkDSNIFTIImageReader.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtk_zlib.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace
{
constexpr vtkIdType Cap = vtkIdType(64) << 20;

/// A private directory for the input files, made once per process.
const std::string& Directory()
{
  static const std::string directory = []
  {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/FuzzNIfTIReader-XXXXXX";
    FUZZ_CHECK(mkdtemp(&pattern[0]) != nullptr, "a temporary directory");
    return pattern;
  }();
  return directory;
}

/// Writes `size` bytes at `data` to `path`, gzip-compressed when `gzip`; false when it cannot.
bool WriteFile(const std::string& path, const uint8_t* data, size_t size, bool gzip)
{
  if (gzip)
  {
    gzFile out = gzopen(path.c_str(), "wb1");
    const bool written = out &&
      (size == 0 || gzwrite(out, data, static_cast<unsigned>(size)) == static_cast<int>(size));
    return out && gzclose(out) == Z_OK && written;
  }
  FILE* out = std::fopen(path.c_str(), "wb");
  const bool written = out && std::fwrite(data, 1, size, out) == size;
  return out && std::fclose(out) == 0 && written;
}

bool AllFinite(const double* values, int count)
{
  for (int i = 0; i < count; ++i)
  {
    if (!std::isfinite(values[i]))
    {
      return false;
    }
  }
  return true;
}

void CheckImage(vtkImageData* image)
{
  const vtkIdType points = image->GetNumberOfPoints();
  FUZZ_CHECK(points > 0, "an image read without an error has points");
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  FUZZ_CHECK(scalars != nullptr, "an image read has scalars");
  FUZZ_CHECK(scalars->GetNumberOfTuples() == points, "one scalar tuple per point");
  FUZZ_CHECK(scalars->GetDataSize() * scalars->GetDataTypeSize() <= Cap,
    "the image is within MaximumDataSize: " +
      std::to_string(scalars->GetDataSize() * scalars->GetDataTypeSize()) + " bytes");
  double spacing[3];
  image->GetSpacing(spacing);
  FUZZ_CHECK(AllFinite(spacing, 3) && spacing[0] > 0 && spacing[1] > 0 && spacing[2] > 0,
    "finite, positive spacing");
  FUZZ_CHECK(AllFinite(image->GetOrigin(), 3), "a finite origin");
  FUZZ_CHECK(AllFinite(image->GetDirectionMatrix()->GetData(), 9), "a finite direction");
}
} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  // The executive's "returned failure" reports of every refused file would flood the log (the
  // reader's own messages go to the counting observer); FUZZ_VERBOSE shows them.
  if (!std::getenv("FUZZ_VERBOSE"))
  {
    vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  const int mode = data[0] % 3;
  const std::string path = Directory() + (mode == 0 ? "/input.nii" : "/input.nii.gz");
  FUZZ_CHECK(WriteFile(path, data + 1, size - 1, mode == 1), "the input file is written");

  vtkNew<vtkDSNIFTIImageReader> reader;
  reader->SetMaximumDataSize(Cap);
  vtkNew<fuzzvtk::MessageCounter> messages;
  reader->AddObserver(vtkCommand::ErrorEvent, messages);
  reader->AddObserver(vtkCommand::WarningEvent, messages);
  reader->SetFileName(path.c_str());
  reader->Update();
  std::remove(path.c_str());

  vtkImageData* image = reader->GetOutput();
  if (std::getenv("FUZZ_VERBOSE"))
  {
    std::fprintf(stderr, "mode %d: %d error(s), %d warning(s), %lld points\n", mode,
      messages->Errors, messages->Warnings, static_cast<long long>(image->GetNumberOfPoints()));
  }
  if (messages->Errors > 0)
  {
    FUZZ_CHECK(image->GetNumberOfPoints() == 0, "an error leaves an empty output");
    return 0;
  }
  CheckImage(image);
  return 0;
}
