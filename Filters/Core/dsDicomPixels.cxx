// SPDX-License-Identifier: BSD-3-Clause
#include "dsDicomPixels.h"

#include "gdcmImage.h"
#include "gdcmImageReader.h"

#include "vtkSetGet.h" // vtkTemplateMacro
#include "vtkType.h"

#if defined(__unix__) || defined(__APPLE__)
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>
#define DS_DECODE_APART 1
#endif

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace dsurf
{
namespace dicom
{
namespace
{
/// Decodes compressed pixel data into `buffer` in a child process where the system allows it.
/// The decoders GDCM calls are not safe on damaged data: OpenJPEG (its JPEG 2000 codec) freed a
/// wild pointer in opj_destroy_codec on a codestream with two bytes of code-block data swapped
/// (FuzzDICOMReader, Testing/Fuzz/corpus/DICOMReader/regression-jpeg2000-wild-free), and a
/// damaged file must give an error, not end ParaView. The child decodes into a shared mapping and
/// exits; one that fails or dies reads as damaged data. Where fork() is missing (or fails) the
/// data is decoded here.
bool DecodeApart(const gdcm::Image& image, std::vector<char>& buffer)
{
#ifdef DS_DECODE_APART
  const size_t length = std::max<size_t>(buffer.size(), 1);
  void* shared = mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (shared != MAP_FAILED)
  {
    const pid_t child = fork();
    if (child == 0)
    {
      _exit(image.GetBuffer(static_cast<char*>(shared)) ? 0 : 1); // no exit handlers, no leaks
    }
    if (child > 0)
    {
      int status = 0;
      pid_t waited = -1;
      do
      {
        waited = waitpid(child, &status, 0);
      } while (waited < 0 && errno == EINTR);
      const bool ok = waited == child && WIFEXITED(status) && WEXITSTATUS(status) == 0;
      if (ok)
      {
        std::memcpy(buffer.data(), shared, buffer.size());
      }
      munmap(shared, length);
      return ok;
    }
    munmap(shared, length);
  }
#endif
  return image.GetBuffer(buffer.data());
}

bool Whole(double v)
{
  return std::floor(v) == v;
}

/// The range of values the slice's format can store.
void StoredRange(const SliceHeader& s, double& lo, double& hi)
{
  const double levels = std::ldexp(1.0, static_cast<int>(s.BitsStored));
  lo = s.PixelRepresentation ? -levels / 2 : 0;
  hi = s.PixelRepresentation ? levels / 2 - 1 : levels - 1;
}

int SmallestInteger(double lo, double hi)
{
  struct Candidate
  {
    int Type;
    double Lo, Hi;
  };
  static const Candidate candidates[] = { { VTK_UNSIGNED_CHAR, 0, 255 },
    { VTK_SIGNED_CHAR, -128, 127 }, { VTK_UNSIGNED_SHORT, 0, 65535 }, { VTK_SHORT, -32768, 32767 },
    { VTK_UNSIGNED_INT, 0, 4294967295.0 }, { VTK_INT, -2147483648.0, 2147483647.0 } };
  for (const Candidate& c : candidates)
  {
    if (lo >= c.Lo && hi <= c.Hi)
    {
      return c.Type;
    }
  }
  return VTK_DOUBLE; // exact for integers up to 2^53
}

/// The stored value of pixel i: Bits Allocated wide, only its low Bits Stored bits meaningful
/// (the rest may hold overlays or padding), sign-extended when signed.
int64_t Stored(
  const char* buffer, size_t i, unsigned int bitsAllocated, unsigned int bitsStored, bool isSigned)
{
  uint32_t raw = 0;
  switch (bitsAllocated)
  {
    case 8:
      raw = static_cast<uint8_t>(buffer[i]);
      break;
    case 16:
    {
      uint16_t v;
      std::memcpy(&v, buffer + 2 * i, 2);
      raw = v;
      break;
    }
    default:
      std::memcpy(&raw, buffer + 4 * i, 4);
  }
  const uint64_t mask = (uint64_t(1) << bitsStored) - 1;
  int64_t value = static_cast<int64_t>(raw & mask);
  if (isSigned && (value >> (bitsStored - 1)) & 1)
  {
    value -= int64_t(1) << bitsStored;
  }
  return value;
}

template <typename T>
void Rescale(const char* buffer, size_t count, const SliceHeader& s, T* out)
{
  for (size_t i = 0; i < count; ++i)
  {
    const double stored = static_cast<double>(
      Stored(buffer, i, s.BitsAllocated, s.BitsStored, s.PixelRepresentation != 0));
    out[i] = static_cast<T>(s.Slope * stored + s.Intercept);
  }
}
} // namespace

int OutputScalarType(const std::vector<SliceHeader>& slices)
{
  double lo = 0, hi = 0;
  bool whole = true, wide = false;
  for (size_t k = 0; k < slices.size(); ++k)
  {
    const SliceHeader& s = slices[k];
    double a, b;
    StoredRange(s, a, b);
    a = s.Slope * a + s.Intercept;
    b = s.Slope * b + s.Intercept;
    lo = k ? std::min({ lo, a, b }) : std::min(a, b);
    hi = k ? std::max({ hi, a, b }) : std::max(a, b);
    whole = whole && Whole(s.Slope) && Whole(s.Intercept);
    wide = wide || s.BitsStored > 16;
  }
  if (!whole)
  {
    return wide ? VTK_DOUBLE : VTK_FLOAT;
  }
  return SmallestInteger(lo, hi);
}

bool ReadSlice(const SliceHeader& slice, int scalarType, void* out, std::string& error)
{
  const size_t count = size_t(slice.Columns) * slice.Rows;
  const size_t bytes = count * (slice.BitsAllocated / 8);
  gdcm::ImageReader reader;
  reader.SetFileName(slice.File.c_str());
  if (!reader.Read())
  {
    error = "cannot read the pixel data of " + slice.File + " (truncated or damaged)";
    return false;
  }
  const gdcm::Image& image = reader.GetImage();
  const gdcm::PixelFormat& format = image.GetPixelFormat();
  if (image.GetDimension(0) != slice.Columns || image.GetDimension(1) != slice.Rows ||
    format.GetBitsAllocated() != slice.BitsAllocated || format.GetSamplesPerPixel() != 1)
  {
    error = "the pixel data of " + slice.File + " does not match its header";
    return false;
  }
  const gdcm::ByteValue* native = image.GetDataElement().GetByteValue();
  if (image.GetBufferLength() < bytes || (native && native->GetLength() < bytes))
  {
    error = "the pixel data of " + slice.File + " is shorter than its " +
      std::to_string(slice.Columns) + " x " + std::to_string(slice.Rows) +
      " pixels (truncated file)";
    return false;
  }
  std::vector<char> buffer(image.GetBufferLength());
  if (!(native ? image.GetBuffer(buffer.data()) : DecodeApart(image, buffer)))
  {
    error = "cannot decode the pixel data of " + slice.File + " (" + slice.TransferSyntaxName +
      "): truncated or damaged";
    return false;
  }
  switch (scalarType)
  {
    vtkTemplateMacro(Rescale(buffer.data(), count, slice, static_cast<VTK_TT*>(out)));
    default:
      error = "unsupported output type " + std::to_string(scalarType);
      return false;
  }
  return true;
}
} // namespace dicom
} // namespace dsurf
