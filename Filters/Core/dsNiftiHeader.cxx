// SPDX-License-Identifier: BSD-3-Clause
#include "dsNiftiHeader.h"

#include "vtk_zlib.h" // zlib as VTK links it: the gzip stream is read as VTK's reader reads it

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>

namespace dsurf
{
namespace
{
/// Little helper reading fixed-width fields of the header at a byte offset, swapping when the
/// file's byte order is not the machine's (memcpy: the offsets are not aligned for every type).
class FieldReader
{
public:
  FieldReader(const unsigned char* bytes, bool swapped)
    : Bytes(bytes)
    , Swapped(swapped)
  {
  }
  template <typename T>
  T Get(std::size_t offset) const
  {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, this->Bytes + offset, sizeof(T));
    if (this->Swapped)
    {
      std::reverse(raw, raw + sizeof(T));
    }
    T value;
    std::memcpy(&value, raw, sizeof(T));
    return value;
  }

private:
  const unsigned char* Bytes;
  bool Swapped;
};

int32_t Swap32(int32_t value)
{
  return FieldReader(reinterpret_cast<const unsigned char*>(&value), true).Get<int32_t>(0);
}

/// VTK's CheckNIFTIVersion: the NIfTI-2 magic "n+2\0\r\n\032\n" sits where NIfTI-1 keeps
/// data_type (byte 4); the NIfTI-1 magic "n+1\0" / "ni1\0" at byte 344; neither: Analyze 7.5.
/// A NIfTI-2 magic without its "\r\n\032\n" tail was damaged by a newline conversion (negative).
int MagicVersion(const unsigned char* bytes)
{
  const unsigned char* v2 = bytes + 4;
  if (v2[0] == 'n' && (v2[1] == '+' || v2[1] == 'i') && v2[2] >= '2' && v2[2] <= '9' &&
    v2[3] == '\0')
  {
    const int version = v2[2] - '0';
    const bool intact = v2[4] == '\r' && v2[5] == '\n' && v2[6] == '\032' && v2[7] == '\n';
    return intact ? version : -version;
  }
  const unsigned char* v1 = bytes + 344;
  if (v1[0] == 'n' && (v1[1] == '+' || v1[1] == 'i') && v1[2] == '1' && v1[3] == '\0')
  {
    return 1;
  }
  return 0;
}

/// The byte order from sizeof_hdr (348 or 540 as written, or swapped); "" or the refusal.
std::string ByteOrder(const unsigned char* bytes, int headerSize, bool& swapped)
{
  int32_t sizeofHdr;
  std::memcpy(&sizeofHdr, bytes, 4);
  swapped = Swap32(sizeofHdr) == headerSize;
  if (sizeofHdr == headerSize || swapped)
  {
    return "";
  }
  std::ostringstream message;
  message << "not a NIfTI file: sizeof_hdr is " << sizeofHdr << " (" << Swap32(sizeofHdr)
          << " byte-swapped), not " << headerSize;
  return message.str();
}

void ParseVersion1(const FieldReader& in, NiftiHeader& header)
{
  // nifti1.h: dim at 40 (int16), datatype 70, bitpix 72, pixdim 76 (float), vox_offset 108,
  // qform_code 252, sform_code 254, quatern_b..qoffset_z 256..276, srow_x/y/z 280/296/312.
  for (int i = 0; i < 8; ++i)
  {
    header.Dim[i] = in.Get<int16_t>(40 + 2 * i);
    header.PixDim[i] = in.Get<float>(76 + 4 * i);
  }
  header.DataType = in.Get<int16_t>(70);
  header.BitPix = in.Get<int16_t>(72);
  header.VoxOffset = in.Get<float>(108);
  header.QFormCode = in.Get<int16_t>(252);
  header.SFormCode = in.Get<int16_t>(254);
  for (int i = 0; i < 3; ++i)
  {
    header.Quatern[i] = in.Get<float>(256 + 4 * i);
    header.QOffset[i] = in.Get<float>(268 + 4 * i);
    for (int j = 0; j < 4; ++j)
    {
      header.SRow[i][j] = in.Get<float>(280 + 16 * i + 4 * j);
    }
  }
}

void ParseVersion2(const FieldReader& in, NiftiHeader& header)
{
  // nifti2.h: datatype 12, bitpix 14, dim 16 (int64), pixdim 104 (double), vox_offset 168
  // (int64), qform_code 344, sform_code 348 (int32), quatern_b..qoffset_z 352..392,
  // srow_x/y/z 400/432/464.
  header.DataType = in.Get<int16_t>(12);
  header.BitPix = in.Get<int16_t>(14);
  for (int i = 0; i < 8; ++i)
  {
    header.Dim[i] = in.Get<int64_t>(16 + 8 * i);
    header.PixDim[i] = in.Get<double>(104 + 8 * i);
  }
  header.VoxOffset = static_cast<double>(in.Get<int64_t>(168));
  header.QFormCode = in.Get<int32_t>(344);
  header.SFormCode = in.Get<int32_t>(348);
  for (int i = 0; i < 3; ++i)
  {
    header.Quatern[i] = in.Get<double>(352 + 8 * i);
    header.QOffset[i] = in.Get<double>(376 + 8 * i);
    for (int j = 0; j < 4; ++j)
    {
      header.SRow[i][j] = in.Get<double>(400 + 32 * i + 8 * j);
    }
  }
}

/// a * b, or the largest uint64 when that overflows (the result is then only compared).
uint64_t SaturatingProduct(uint64_t a, uint64_t b)
{
  if (b != 0 && a > std::numeric_limits<uint64_t>::max() / b)
  {
    return std::numeric_limits<uint64_t>::max();
  }
  return a * b;
}

std::string DatatypeError(const NiftiHeader& header)
{
  const int bytes = NiftiBytesPerVoxel(header.DataType);
  std::ostringstream message;
  if (bytes == 0)
  {
    message << "datatype " << header.DataType
            << " is not a NIfTI data type VTK reads (2, 4, 8, 16, 32, 64, 128, 256, 512, 768, "
               "1024, 1280, 1792, 2304)";
  }
  else if (header.BitPix != 8 * bytes)
  {
    message << "bitpix is " << header.BitPix << " but datatype " << header.DataType << " has "
            << 8 * bytes << " bits per voxel";
  }
  return message.str();
}

std::string DimError(const NiftiHeader& header)
{
  std::ostringstream message;
  if (header.Dim[0] < 1 || header.Dim[0] > 7)
  {
    message << "dim[0] (the number of dimensions) is " << header.Dim[0] << ", not in 1..7";
    return message.str();
  }
  for (int i = 1; i <= header.Dim[0]; ++i)
  {
    message << "dim[" << i << "] is " << header.Dim[i];
    if (header.Dim[i] <= 0)
    {
      return message.str() + ": dimensions must be positive";
    }
    if (header.Dim[i] > std::numeric_limits<int32_t>::max())
    {
      return message.str() + ", beyond VTK's int indices";
    }
    message.str("");
  }
  return "";
}

/// The bytes of every voxel the dims describe, saturating at 2^64 - 1.
uint64_t DataSize(const NiftiHeader& header)
{
  uint64_t size = static_cast<uint64_t>(NiftiBytesPerVoxel(header.DataType));
  for (int i = 1; i <= header.Dim[0]; ++i)
  {
    size = SaturatingProduct(size, static_cast<uint64_t>(header.Dim[i]));
  }
  return size;
}

std::string SizeError(const NiftiHeader& header, uint64_t dataSize, uint64_t maximumDataSize)
{
  if (dataSize <= maximumDataSize)
  {
    return "";
  }
  std::ostringstream message;
  message << "the data size (dim";
  for (int i = 1; i <= header.Dim[0]; ++i)
  {
    message << (i > 1 ? " x " : " ") << header.Dim[i];
  }
  message << " voxels of " << NiftiBytesPerVoxel(header.DataType) << " bytes = ";
  if (dataSize == std::numeric_limits<uint64_t>::max())
  {
    message << "more than 2^64 bytes";
  }
  else
  {
    message << dataSize << " bytes";
  }
  message << ") exceeds MaximumDataSize (" << maximumDataSize << " bytes)";
  return message.str();
}

/// A non-finite value among `count` values named `name`[j] (or `name` alone when count is 1).
std::string NonFinite(const char* name, const double* values, int count)
{
  for (int j = 0; j < count; ++j)
  {
    if (!std::isfinite(values[j]))
    {
      std::ostringstream message;
      message << name;
      if (count > 1)
      {
        message << "[" << j << "]";
      }
      message << " is " << values[j] << " (not finite)";
      return message.str();
    }
  }
  return "";
}

std::string GeometryError(const NiftiHeader& header)
{
  std::ostringstream message;
  if (!std::isfinite(header.VoxOffset) || header.VoxOffset < 0)
  {
    message << "vox_offset is " << header.VoxOffset << ": not a byte offset (finite, >= 0)";
    return message.str();
  }
  // pixdim[0] is qfac; pixdim[1..3] become the spacing even for fewer dimensions.
  const int pixdims = static_cast<int>(std::max<int64_t>(3, header.Dim[0])) + 1;
  std::string error = NonFinite("pixdim", header.PixDim, pixdims);
  if (header.Version > 0 && header.QFormCode > 0)
  {
    static const char* quatern[3] = { "quatern_b", "quatern_c", "quatern_d" };
    static const char* qoffset[3] = { "qoffset_x", "qoffset_y", "qoffset_z" };
    for (int i = 0; i < 3 && error.empty(); ++i)
    {
      error = NonFinite(quatern[i], &header.Quatern[i], 1);
      error = error.empty() ? NonFinite(qoffset[i], &header.QOffset[i], 1) : error;
    }
  }
  if (header.Version > 0 && header.SFormCode > 0)
  {
    static const char* srow[3] = { "srow_x", "srow_y", "srow_z" };
    for (int i = 0; i < 3 && error.empty(); ++i)
    {
      error = NonFinite(srow[i], header.SRow[i], 4);
    }
  }
  return error;
}

/// pixdim 0 or negative on a spatial axis: spacing 1 there (VTK's reader already takes 1 for
/// 0, and would take a negative spacing as it is); a warning when the axis is used.
void UnitSpacing(const NiftiHeader& header, NiftiVerdict& verdict)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    const double pixdim = header.PixDim[axis + 1];
    if (pixdim > 0)
    {
      continue;
    }
    verdict.UnitSpacing[axis] = true;
    if (axis + 1 <= header.Dim[0])
    {
      std::ostringstream message;
      message << "pixdim[" << axis + 1 << "] is " << pixdim << ": spacing 1 is used on axis "
              << "xyz"[axis];
      verdict.Warnings.push_back(message.str());
    }
  }
}

/// The length of a file's contents as zlib reads them (as VTK's reader will): its size when it
/// is not compressed, else the decompressed bytes, read until `needed` (no further) or the end.
struct ContentLength
{
  uint64_t Bytes = 0;
  std::string Failure;  // the file cannot be read at all
  std::string ZlibNote; // zlib's complaint where a damaged or cut stream ended
};

ContentLength MeasureContent(const std::string& file, uint64_t needed)
{
  ContentLength content;
  gzFile stream = gzopen(file.c_str(), "rb");
  if (!stream)
  {
    content.Failure = "cannot open " + file;
    return content;
  }
  if (gzdirect(stream))
  {
    gzclose(stream);
    std::error_code failed;
    content.Bytes = std::filesystem::file_size(file, failed);
    content.Failure = failed ? "cannot tell the size of " + file + ": " + failed.message() : "";
    return content;
  }
  std::vector<unsigned char> buffer(1 << 18);
  while (content.Bytes < needed)
  {
    const uint64_t want = std::min<uint64_t>(buffer.size(), needed - content.Bytes);
    const int got = gzread(stream, buffer.data(), static_cast<unsigned>(want));
    if (got <= 0)
    {
      int code = Z_OK;
      const char* text = gzerror(stream, &code);
      content.ZlibNote = got < 0 && text ? std::string(" (zlib: ") + text + ")" : "";
      break;
    }
    content.Bytes += static_cast<uint64_t>(got);
  }
  gzclose(stream);
  return content;
}

std::string LengthError(const NiftiHeader& header, uint64_t dataSize, const std::string& dataFile)
{
  std::ostringstream message;
  // VTK seeks to vox_offset as an integer (its HeaderSize); past 2^62 no file reaches it.
  if (header.VoxOffset >= 0x1p62)
  {
    message << "vox_offset is " << header.VoxOffset << ": beyond the end of " << dataFile;
    return message.str();
  }
  const uint64_t offset = static_cast<uint64_t>(header.VoxOffset);
  const uint64_t needed = dataSize > std::numeric_limits<uint64_t>::max() - offset
    ? std::numeric_limits<uint64_t>::max()
    : offset + dataSize;
  const ContentLength content = MeasureContent(dataFile, needed);
  if (!content.Failure.empty() || content.Bytes >= needed)
  {
    return content.Failure;
  }
  if (offset >= content.Bytes)
  {
    message << "vox_offset is " << header.VoxOffset << ": beyond the end of " << dataFile << " ("
            << content.Bytes << " bytes)";
  }
  else
  {
    message << dataFile << " is truncated: the data need " << dataSize << " bytes from vox_offset "
            << offset << ", the file holds " << content.Bytes - offset;
  }
  return message.str() + content.ZlibNote;
}

/// Up to NiftiHeaderBytes of the file's start, decompressed when gzipped.
std::string ReadHeaderBytes(const std::string& file, std::vector<unsigned char>& bytes)
{
  bytes.assign(NiftiHeaderBytes, 0);
  gzFile stream = gzopen(file.c_str(), "rb");
  if (!stream)
  {
    return "cannot open " + file;
  }
  const int got = gzread(stream, bytes.data(), static_cast<unsigned>(bytes.size()));
  gzclose(stream);
  bytes.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
  return "";
}
} // namespace

int NiftiBytesPerVoxel(int datatype)
{
  switch (datatype)
  {
    case 2:   // UINT8
    case 256: // INT8
      return 1;
    case 4:   // INT16
    case 512: // UINT16
      return 2;
    case 8:    // INT32
    case 768:  // UINT32
    case 16:   // FLOAT32
    case 2304: // RGBA32
      return 4;
    case 1024: // INT64
    case 1280: // UINT64
    case 64:   // FLOAT64
    case 32:   // COMPLEX64
      return 8;
    case 1792: // COMPLEX128
      return 16;
    case 128: // RGB24
      return 3;
    default: // BINARY, FLOAT128, COMPLEX256 and anything else: VTK's reader has no type for them
      return 0;
  }
}

std::string ParseNiftiHeader(const unsigned char* bytes, std::size_t size, NiftiHeader& header)
{
  header = NiftiHeader();
  if (size < 348)
  {
    return "not a NIfTI file: " + std::to_string(size) +
      " bytes, shorter than a NIfTI-1 header (348)";
  }
  const int version = MagicVersion(bytes);
  if (version < 0)
  {
    return "the NIfTI-2 magic is damaged (a text-mode newline conversion?)";
  }
  if (version > 2)
  {
    return "the magic says NIfTI-" + std::to_string(version) + ": only NIfTI-1 and -2 are known";
  }
  header.Version = version;
  header.HeaderSize = version == 2 ? 540 : 348;
  if (size < static_cast<std::size_t>(header.HeaderSize))
  {
    return "not a NIfTI file: " + std::to_string(size) + " bytes, shorter than a NIfTI-2 header";
  }
  const std::string order = ByteOrder(bytes, header.HeaderSize, header.Swapped);
  if (!order.empty())
  {
    return order;
  }
  const FieldReader in(bytes, header.Swapped);
  if (version == 2)
  {
    ParseVersion2(in, header);
  }
  else
  {
    ParseVersion1(in, header);
  }
  return "";
}

NiftiVerdict CheckNiftiHeader(const NiftiHeader& header, uint64_t maximumDataSize)
{
  NiftiVerdict verdict;
  verdict.Error = DatatypeError(header);
  if (verdict.Error.empty())
  {
    verdict.Error = DimError(header);
  }
  if (verdict.Error.empty())
  {
    verdict.DataSize = DataSize(header);
    verdict.Error = SizeError(header, verdict.DataSize, maximumDataSize);
  }
  if (verdict.Error.empty())
  {
    verdict.Error = GeometryError(header);
  }
  if (verdict.Error.empty())
  {
    UnitSpacing(header, verdict);
  }
  return verdict;
}

NiftiVerdict CheckNiftiFile(
  const std::string& headerFile, const std::string& dataFile, uint64_t maximumDataSize)
{
  NiftiVerdict verdict;
  std::vector<unsigned char> bytes;
  NiftiHeader header;
  verdict.Error = ReadHeaderBytes(headerFile, bytes);
  if (verdict.Error.empty())
  {
    const std::string error = ParseNiftiHeader(bytes.data(), bytes.size(), header);
    verdict.Error = error.empty() ? "" : headerFile + ": " + error;
  }
  if (!verdict.Error.empty())
  {
    return verdict;
  }
  verdict = CheckNiftiHeader(header, maximumDataSize);
  if (!verdict.Error.empty())
  {
    verdict.Error = headerFile + ": " + verdict.Error;
    return verdict;
  }
  verdict.Error = LengthError(header, verdict.DataSize, dataFile);
  return verdict;
}
} // namespace dsurf
