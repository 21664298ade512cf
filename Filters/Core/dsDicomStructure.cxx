// SPDX-License-Identifier: BSD-3-Clause
#include "dsDicomStructure.h"

#include <cstdint>
#include <fstream>
#include <iterator>
#include <vector>

namespace dsurf
{
namespace dicom
{
namespace
{
constexpr uint32_t Undefined = 0xffffffffu;
constexpr int MaxDepth = 32; // nested sequences; deeper is taken as damage (and bounds recursion)

struct Walker
{
  const std::vector<unsigned char>& Bytes;
  bool Explicit = true, BigEndian = false;
  std::string Error;
  long long PixelDataBytes = -2; ///< of the top-level (7FE0,0010): -1 undefined length

  uint16_t U16(size_t p) const
  {
    return BigEndian ? uint16_t(Bytes[p] << 8 | Bytes[p + 1])
                     : uint16_t(Bytes[p + 1] << 8 | Bytes[p]);
  }
  uint32_t U32(size_t p) const
  {
    return BigEndian ? uint32_t(U16(p)) << 16 | U16(p + 2) : uint32_t(U16(p + 2)) << 16 | U16(p);
  }
  bool Fail(const std::string& why, size_t at)
  {
    Error = why + " at byte " + std::to_string(at);
    return false;
  }

  /// Whether an explicit VR is the one the standard gives the elements GDCM's image reader
  /// reads through gdcm::Attribute, which asserts (aborting the process) on another one: a
  /// fuzzed Samples per Pixel (0028,0002) of another VR did. Other elements pass.
  static bool ExpectedVR(uint16_t group, uint16_t element, const std::string& vr)
  {
    struct Expected
    {
      uint16_t Group, Element;
      const char* VR;
    };
    static const Expected table[] = { { 0x0018, 0x0050, "DS" }, { 0x0018, 0x0088, "DS" },
      { 0x0020, 0x000e, "UI" }, { 0x0020, 0x0013, "IS" }, { 0x0020, 0x0032, "DS" },
      { 0x0020, 0x0037, "DS" }, { 0x0028, 0x0002, "US" }, { 0x0028, 0x0004, "CS" },
      { 0x0028, 0x0006, "US" }, { 0x0028, 0x0008, "IS" }, { 0x0028, 0x0010, "US" },
      { 0x0028, 0x0011, "US" }, { 0x0028, 0x0030, "DS" }, { 0x0028, 0x0100, "US" },
      { 0x0028, 0x0101, "US" }, { 0x0028, 0x0102, "US" }, { 0x0028, 0x0103, "US" },
      { 0x0028, 0x1050, "DS" }, { 0x0028, 0x1051, "DS" }, { 0x0028, 0x1052, "DS" },
      { 0x0028, 0x1053, "DS" }, { 0x0028, 0x1054, "LO" } };
    for (const Expected& e : table)
    {
      if (e.Group == group && e.Element == element)
      {
        return vr == e.VR;
      }
    }
    return true;
  }

  /// The element header at p: tag, value length, header size; false when it does not fit.
  bool Header(
    size_t p, uint16_t& group, uint16_t& element, uint32_t& length, size_t& size, std::string& vr)
  {
    if (p + 8 > Bytes.size())
    {
      return Fail("the file ends inside an element header", p);
    }
    group = U16(p);
    element = U16(p + 2);
    vr.clear();
    if (!Explicit || group == 0xfffe) // item tags have no VR in any syntax
    {
      length = U32(p + 4);
      size = 8;
      return true;
    }
    vr.assign(reinterpret_cast<const char*>(&Bytes[p + 4]), 2);
    // An unknown VR: GDCM then guesses (and may read the file another way than this walk).
    static const std::string known = "AE AS AT CS DA DS DT FD FL IS LO LT OB OD OF OL OV OW PN SH "
                                     "SL SQ SS ST SV TM UC UI UL UN UR US UT UV";
    if (vr.find(' ') != std::string::npos || known.find(vr) == std::string::npos ||
      known.find(vr) % 3 != 0)
    {
      return Fail("an unknown value representation", p);
    }
    static const char* const longForm[] = { "OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC",
      "UN", "UR", "UT", "UV" };
    bool isLong = false;
    for (const char* v : longForm)
    {
      isLong = isLong || vr == v;
    }
    if (!isLong)
    {
      length = U16(p + 6);
      size = 8;
      return true;
    }
    if (p + 12 > Bytes.size())
    {
      return Fail("the file ends inside an element header", p);
    }
    length = U32(p + 8);
    size = 12;
    return true;
  }

  /// Elements from p to the end of the file, or (inItem) to an item delimiter.
  bool Elements(size_t& p, int depth, bool inItem)
  {
    if (depth > MaxDepth)
    {
      return Fail("sequences nested too deep", p);
    }
    while (p < Bytes.size())
    {
      uint16_t group, element;
      uint32_t length;
      size_t size;
      std::string vr;
      if (!Header(p, group, element, length, size, vr))
      {
        return false;
      }
      if (group == 0xfffe)
      {
        if (inItem && element == 0xe00d)
        {
          p += 8;
          return length == 0 || Fail("an item delimiter with a length", p - 8);
        }
        return Fail("a misplaced item or delimiter tag", p);
      }
      if (depth == 0 && !vr.empty() && !ExpectedVR(group, element, vr))
      {
        return Fail("an element of the image's description with another value representation "
                    "than the standard's (" +
            vr + ")",
          p);
      }
      p += size;
      if (depth == 0 && group == 0x7fe0 && element == 0x0010)
      {
        PixelDataBytes = length == Undefined ? -1 : static_cast<long long>(length);
      }
      if (length == Undefined)
      {
        // GDCM asserts on any other undefined length: a sequence, an unknown (UN, whose items
        // are implicit VR: PS3.5 §6.2.2) or encapsulated (OB, OW) Pixel Data.
        const bool pixels = group == 0x7fe0 && element == 0x0010;
        if (!vr.empty() &&
          !(pixels ? (vr == "OB" || vr == "OW" || vr == "UN") : (vr == "SQ" || vr == "UN")))
        {
          return Fail("an undefined length on a " + vr + " element", p - size);
        }
        const bool wasExplicit = Explicit;
        Explicit = Explicit && vr != "UN";
        const bool ok = Items(p, depth + 1);
        Explicit = wasExplicit;
        if (!ok)
        {
          return false;
        }
      }
      else if (length > Bytes.size() - p)
      {
        return Fail(
          "the file ends inside an element of " + std::to_string(length) + " bytes", p - size);
      }
      else
      {
        p += length;
      }
    }
    return !inItem || Fail("the file ends inside an item", p);
  }

  /// The items of an undefined-length sequence or of encapsulated pixel data, to its delimiter.
  bool Items(size_t& p, int depth)
  {
    while (true)
    {
      if (p + 8 > Bytes.size())
      {
        return Fail("the file ends inside a sequence", p);
      }
      const uint16_t group = U16(p), element = U16(p + 2);
      const uint32_t length = U32(p + 4);
      if (group != 0xfffe || (element != 0xe000 && element != 0xe0dd))
      {
        return Fail("a sequence holds something other than items", p);
      }
      p += 8;
      if (element == 0xe0dd)
      {
        // Delimiters have length 0 (PS3.5 §7.5); GDCM would allocate any other as a fragment.
        return length == 0 || Fail("a sequence delimiter with a length", p - 8);
      }
      if (length == Undefined)
      {
        if (!Elements(p, depth, true))
        {
          return false;
        }
      }
      else if (length > Bytes.size() - p)
      {
        return Fail("the file ends inside an item of " + std::to_string(length) + " bytes", p - 8);
      }
      else
      {
        p += length;
      }
    }
  }
};

std::string Trimmed(const std::vector<unsigned char>& bytes, size_t p, size_t n)
{
  std::string s(reinterpret_cast<const char*>(&bytes[p]), n);
  while (!s.empty() && (s.back() == '\0' || s.back() == ' '))
  {
    s.pop_back();
  }
  return s;
}
} // namespace

Structure CheckStructure(const std::string& file, FileFacts& facts, std::string& error)
{
  facts = FileFacts();
  std::string& transferSyntax = facts.TransferSyntax;
  std::ifstream in(file, std::ios::binary);
  const std::vector<unsigned char> bytes(
    (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  facts.FileBytes = static_cast<long long>(bytes.size());
  if (bytes.size() < 132 || std::string(bytes.begin() + 128, bytes.begin() + 132) != "DICM")
  {
    error = file + " is not a DICOM file (no \"DICM\" after the 128-byte preamble)";
    return Structure::NotDicom;
  }
  // The meta header: group 0002, always explicit VR little endian.
  Walker walk{ bytes };
  size_t p = 132;
  while (p + 8 <= bytes.size() && walk.U16(p) == 0x0002)
  {
    uint16_t group, element;
    uint32_t length;
    size_t size;
    std::string vr;
    if (!walk.Header(p, group, element, length, size, vr) || length == Undefined ||
      length > bytes.size() - p - size)
    {
      error = file + " is damaged in its meta header: " +
        (walk.Error.empty() ? "an element runs past the end" : walk.Error);
      return Structure::Damaged;
    }
    if (element == 0x0010)
    {
      transferSyntax = Trimmed(bytes, p + size, length);
    }
    p += size + length;
  }
  if (transferSyntax == "1.2.840.10008.1.2.1.99")
  {
    error = file + " has a deflated data set (Deflated Explicit VR Little Endian), which this " +
      "reader does not support";
    return Structure::Unwalkable;
  }
  // Every standard syntax but two encodes explicit VR little endian; GDCM guesses for others.
  if (transferSyntax.rfind("1.2.840.10008.1.2", 0) != 0)
  {
    error = file + " has the unknown transfer syntax \"" + transferSyntax + "\"";
    return Structure::Unwalkable;
  }
  walk.Explicit = transferSyntax != "1.2.840.10008.1.2";
  walk.BigEndian = transferSyntax == "1.2.840.10008.1.2.2";
  if (!walk.Elements(p, 0, false))
  {
    error = file + " is truncated or damaged: " + walk.Error;
    return Structure::Damaged;
  }
  facts.PixelDataBytes = walk.PixelDataBytes;
  return Structure::Complete;
}
} // namespace dicom
} // namespace dsurf
