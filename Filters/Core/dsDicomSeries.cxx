// SPDX-License-Identifier: BSD-3-Clause
#include "dsDicomSeries.h"

#include "dsDicomStructure.h"

#include "gdcmDataSet.h"
#include "gdcmReader.h"
#include "gdcmTrace.h"
#include "gdcmUIDs.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace dsurf
{
namespace dicom
{
namespace
{
/// The text of an element, without the trailing spaces and NULs DICOM pads with; "" if absent.
std::string Text(const gdcm::DataSet& ds, const gdcm::Tag& tag)
{
  if (!ds.FindDataElement(tag))
  {
    return "";
  }
  const gdcm::ByteValue* bv = ds.GetDataElement(tag).GetByteValue();
  if (!bv || !bv->GetPointer())
  {
    return "";
  }
  std::string s(bv->GetPointer(), bv->GetLength());
  const size_t end = s.find_last_not_of(std::string(" \0", 2));
  s.erase(end == std::string::npos ? 0 : end + 1);
  const size_t begin = s.find_first_not_of(' ');
  return begin == std::string::npos ? "" : s.substr(begin);
}

/// A Decimal String of exactly `count` finite values ("a\b\c") into `values`; false, and
/// `values` untouched, if absent or malformed.
bool Decimals(const gdcm::DataSet& ds, const gdcm::Tag& tag, int count, double* values)
{
  std::stringstream text(Text(ds, tag));
  std::string item;
  std::vector<double> parsed;
  while (std::getline(text, item, '\\'))
  {
    const char* begin = item.c_str();
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(v))
    {
      return false;
    }
    parsed.push_back(v);
  }
  if (static_cast<int>(parsed.size()) != count)
  {
    return false;
  }
  std::copy(parsed.begin(), parsed.end(), values);
  return true;
}

/// An unsigned short element (Rows, Bits Allocated, ...); `fallback` when absent or malformed.
/// Decoded here: gdcm::Attribute asserts that the tag is its own, for each tag a template.
unsigned int Short(
  const gdcm::DataSet& ds, const gdcm::Tag& tag, bool bigEndian, unsigned int fallback)
{
  if (!ds.FindDataElement(tag))
  {
    return fallback;
  }
  const gdcm::ByteValue* bv = ds.GetDataElement(tag).GetByteValue();
  if (!bv || bv->GetLength() != 2 || !bv->GetPointer())
  {
    return fallback;
  }
  const auto* b = reinterpret_cast<const unsigned char*>(bv->GetPointer());
  return bigEndian ? (b[0] << 8 | b[1]) : (b[1] << 8 | b[0]);
}

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// n = row x column of an orientation (LPS), and whether row and column are orthonormal.
bool SliceNormal(const double o[6], double n[3])
{
  const double* r = o;
  const double* c = o + 3;
  n[0] = r[1] * c[2] - r[2] * c[1];
  n[1] = r[2] * c[0] - r[0] * c[2];
  n[2] = r[0] * c[1] - r[1] * c[0];
  const double len = std::sqrt(Dot(n, n));
  if (std::abs(Dot(r, r) - 1) > 1e-3 || std::abs(Dot(c, c) - 1) > 1e-3 ||
    std::abs(Dot(r, c)) > 1e-3 || !(len > 0))
  {
    return false;
  }
  for (int i = 0; i < 3; ++i)
  {
    n[i] /= len;
  }
  return true;
}

/// The first difference between a slice and the series' first slice that stops them forming
/// one volume ("" when none).
std::string Mismatch(const SliceHeader& a, const SliceHeader& b)
{
  std::ostringstream why;
  if (a.Rows != b.Rows || a.Columns != b.Columns)
  {
    why << b.Columns << " x " << b.Rows << " pixels where " << a.File << " has " << a.Columns
        << " x " << a.Rows;
  }
  else if (a.BitsAllocated != b.BitsAllocated || a.BitsStored != b.BitsStored ||
    a.PixelRepresentation != b.PixelRepresentation || a.SamplesPerPixel != b.SamplesPerPixel)
  {
    why << "another pixel format than " << a.File;
  }
  else if (a.HasOrientation != b.HasOrientation || a.HasPosition != b.HasPosition)
  {
    why << "Image Position/Orientation where " << a.File << " has none, or the reverse";
  }
  else
  {
    for (int i = 0; i < 6 && why.str().empty(); ++i)
    {
      if (std::abs(a.Orientation[i] - b.Orientation[i]) > 1e-4)
      {
        why << "another Image Orientation (Patient) than " << a.File;
      }
    }
    for (int i = 0; i < 2 && why.str().empty(); ++i)
    {
      if (std::abs(a.PixelSpacing[i] - b.PixelSpacing[i]) > 1e-4 * a.PixelSpacing[i])
      {
        why << "another Pixel Spacing than " << a.File;
      }
    }
  }
  return why.str().empty() ? "" : b.File + " has " + why.str();
}

/// The slice's header fields a volume needs, with a reason when one is unusable.
std::string Unusable(const SliceHeader& s)
{
  if (s.Rows == 0 || s.Columns == 0)
  {
    return s.File + " has no Rows/Columns";
  }
  if (s.Frames != 1)
  {
    return s.File + " holds " + std::to_string(s.Frames) +
      " frames: multi-frame files are not supported, only one slice per file";
  }
  if (s.SamplesPerPixel != 1)
  {
    return s.File + " is a colour image (" + std::to_string(s.SamplesPerPixel) +
      " samples per pixel): only grey-value images are supported";
  }
  if ((s.BitsAllocated != 8 && s.BitsAllocated != 16 && s.BitsAllocated != 32) ||
    s.BitsStored == 0 || s.BitsStored > s.BitsAllocated)
  {
    return s.File + " has an unsupported pixel format (Bits Allocated " +
      std::to_string(s.BitsAllocated) + ", Bits Stored " + std::to_string(s.BitsStored) + ")";
  }
  // Sizes bounded by the file before anything is allocated for them: native pixel data must
  // hold Rows x Columns; a compressed slice is taken to decode to at most 4096 times its file
  // (lossless codecs reach a few hundred on blank images).
  const double bytes = double(s.Rows) * s.Columns * (s.BitsAllocated / 8);
  if (s.PixelDataBytes == -2)
  {
    return s.File + " has no Pixel Data";
  }
  if (s.PixelDataBytes >= 0 ? s.PixelDataBytes < bytes : bytes > 4096.0 * s.FileBytes)
  {
    return s.File + " has Pixel Data too short for its " + std::to_string(s.Columns) + " x " +
      std::to_string(s.Rows) + " pixels (damaged)";
  }
  if (!(s.PixelSpacing[0] > 0 && s.PixelSpacing[1] > 0))
  {
    return s.File + " has a Pixel Spacing that is not positive";
  }
  if (!SupportedTransferSyntax(s.TransferSyntaxUID))
  {
    return s.File + " is stored in the transfer syntax " + s.TransferSyntaxName + " (" +
      s.TransferSyntaxUID + "), which this reader cannot decode (supported: native, " +
      "JPEG, JPEG-LS, JPEG 2000, RLE)";
  }
  return "";
}

std::string Millimetres(double v)
{
  std::ostringstream s;
  s.precision(6);
  s << v << " mm";
  return s.str();
}

/// Slice positions along the normal, in order: a missing slice is an error, uneven steps a
/// warning; the step used is the mean one.
bool SliceStep(const std::vector<SliceHeader>& slices, const std::vector<double>& along,
  double& step, std::vector<std::string>& warnings, std::string& error)
{
  const size_t n = along.size();
  double smallest = along[1] - along[0], largest = smallest;
  for (size_t k = 0; k + 1 < n; ++k)
  {
    const double s = along[k + 1] - along[k];
    if (!(s > 1e-4))
    {
      error = slices[k].File + " and " + slices[k + 1].File + " lie at the same position (" +
        Millimetres(along[k]) +
        " along the slice normal): the series holds more than one volume (time points, "
        "echoes?) or a slice twice";
      return false;
    }
    smallest = std::min(smallest, s);
    largest = std::max(largest, s);
  }
  for (size_t k = 0; k + 1 < n; ++k)
  {
    // A step close to a whole multiple of the smallest one: slices are missing there.
    const double ratio = (along[k + 1] - along[k]) / smallest;
    if (ratio > 1.5 && std::abs(ratio - std::round(ratio)) < 0.1)
    {
      const long missing = std::lround(ratio) - 1;
      error = "missing slice: between " + slices[k].File + " (at " + Millimetres(along[k]) +
        ") and " + slices[k + 1].File + " (at " + Millimetres(along[k + 1]) + ") the step is " +
        Millimetres(along[k + 1] - along[k]) + ", " + std::to_string(missing + 1) +
        " times the series' " + Millimetres(smallest) + ": " + std::to_string(missing) +
        " slice(s) missing";
      return false;
    }
  }
  step = (along[n - 1] - along[0]) / static_cast<double>(n - 1);
  if (largest - smallest > 1e-3 * smallest)
  {
    double off = 0; // how far a slice lies from where the even stack puts it
    for (size_t k = 0; k < n; ++k)
    {
      off = std::max(off, std::abs(along[k] - along[0] - static_cast<double>(k) * step));
    }
    warnings.push_back("uneven slice steps (from " + Millimetres(smallest) + " to " +
      Millimetres(largest) + "): the slices are stacked at their mean step of " +
      Millimetres(step) + " (not resampled), so some lie up to " + Millimetres(off) +
      " from where their files place them");
  }
  return true;
}

/// Sideways drift of the positions off the slice normal (a gantry tilt): a warning.
void TiltWarning(const std::vector<SliceHeader>& slices, const double normal[3], double along,
  std::vector<std::string>& warnings)
{
  double d[3];
  for (int i = 0; i < 3; ++i)
  {
    d[i] = slices.back().Position[i] - slices.front().Position[i];
  }
  double lateral[3];
  for (int i = 0; i < 3; ++i)
  {
    lateral[i] = d[i] - along * normal[i];
  }
  const double drift = std::sqrt(Dot(lateral, lateral));
  if (drift > 1e-3 * std::max(1.0, std::abs(along)))
  {
    const double degrees = std::atan2(drift, std::abs(along)) * 180.0 / 3.14159265358979323846;
    std::ostringstream s;
    s.precision(4);
    s << "gantry tilt: the slice positions drift " << degrees
      << " degrees off the slice normal; the slices are stacked along the normal (not "
         "resampled), so the last slice lies "
      << Millimetres(drift) << " from where its file places it";
    warnings.push_back(s.str());
  }
}
/// The fields of the Image Plane and Image Pixel modules (PS3.3 C.7.6.2, C.7.6.3) and the
/// rescale (C.11.1.1.2); h.TransferSyntaxUID must be set (for the byte order).
void ImageFields(const gdcm::DataSet& ds, SliceHeader& h)
{
  h.HasPosition = Decimals(ds, gdcm::Tag(0x0020, 0x0032), 3, h.Position);
  h.HasOrientation = Decimals(ds, gdcm::Tag(0x0020, 0x0037), 6, h.Orientation);
  Decimals(ds, gdcm::Tag(0x0028, 0x0030), 2, h.PixelSpacing);
  const std::string frames = Text(ds, gdcm::Tag(0x0028, 0x0008));
  h.Frames =
    frames.empty() ? 1u : static_cast<unsigned int>(std::strtoul(frames.c_str(), nullptr, 10));
  const bool bigEndian = h.TransferSyntaxUID == "1.2.840.10008.1.2.2"; // Explicit VR Big Endian
  h.Rows = Short(ds, gdcm::Tag(0x0028, 0x0010), bigEndian, 0);
  h.Columns = Short(ds, gdcm::Tag(0x0028, 0x0011), bigEndian, 0);
  h.SamplesPerPixel = Short(ds, gdcm::Tag(0x0028, 0x0002), bigEndian, 1);
  h.BitsAllocated = Short(ds, gdcm::Tag(0x0028, 0x0100), bigEndian, 0);
  h.BitsStored = Short(ds, gdcm::Tag(0x0028, 0x0101), bigEndian, h.BitsAllocated);
  h.PixelRepresentation = Short(ds, gdcm::Tag(0x0028, 0x0103), bigEndian, 0);
  Decimals(ds, gdcm::Tag(0x0028, 0x1053), 1, &h.Slope);
  Decimals(ds, gdcm::Tag(0x0028, 0x1052), 1, &h.Intercept);
  if (h.Slope == 0)
  {
    h.Slope = 1; // a zero slope would erase the image: files that write one mean "none"
  }
}
} // namespace

HeaderStatus ReadHeader(const std::string& file, SliceHeader& h, std::string& error)
{
  // GDCM reports to stderr by default; this reader reports through its caller instead.
  gdcm::Trace::WarningOff();
  gdcm::Trace::ErrorOff();
  gdcm::Trace::DebugOff();
  h = SliceHeader();
  h.File = file;
  // GDCM aborts on some damaged files (its assertions are on in Debian's build): check first.
  FileFacts facts;
  switch (CheckStructure(file, facts, error))
  {
    case Structure::Complete:
      break;
    case Structure::NotDicom:
      return HeaderStatus::NotDicom;
    default:
      return HeaderStatus::Damaged;
  }
  gdcm::Reader reader;
  reader.SetFileName(file.c_str());
  if (!reader.ReadUpToTag(gdcm::Tag(0x7fe0, 0x0010)))
  {
    error = file + " starts as a DICOM file but cannot be parsed (damaged)";
    return HeaderStatus::Damaged;
  }
  const gdcm::File& f = reader.GetFile();
  const gdcm::DataSet& ds = f.GetDataSet();
  h.PixelDataBytes = facts.PixelDataBytes;
  h.FileBytes = facts.FileBytes;
  h.SeriesUID = Text(ds, gdcm::Tag(0x0020, 0x000e));
  if (h.SeriesUID.empty())
  {
    error = file + " is not a DICOM image of a series (no Series Instance UID)";
    return HeaderStatus::NotDicom;
  }
  h.SeriesDescription = Text(ds, gdcm::Tag(0x0008, 0x103e));
  h.TransferSyntaxUID = Text(f.GetHeader(), gdcm::Tag(0x0002, 0x0010));
  if (h.TransferSyntaxUID.empty())
  {
    h.TransferSyntaxUID = gdcm::TransferSyntax::GetTSString(
      gdcm::TransferSyntax::TSType(f.GetHeader().GetDataSetTransferSyntax()));
  }
  gdcm::UIDs uid;
  h.TransferSyntaxName =
    uid.SetFromUID(h.TransferSyntaxUID.c_str()) && uid.GetName() ? uid.GetName() : "unknown";
  ImageFields(ds, h);
  return HeaderStatus::Ok;
}

bool SupportedTransferSyntax(const std::string& uid)
{
  static const char* const decodable[] = {
    "1.2.840.10008.1.2",      // Implicit VR Little Endian
    "1.2.840.10008.1.2.1",    // Explicit VR Little Endian
    "1.2.840.10008.1.2.2",    // Explicit VR Big Endian
    "1.2.840.10008.1.2.4.50", // JPEG Baseline
    "1.2.840.10008.1.2.4.51", // JPEG Extended
    "1.2.840.10008.1.2.4.57", // JPEG Lossless, Process 14
    "1.2.840.10008.1.2.4.70", // JPEG Lossless, first-order prediction
    "1.2.840.10008.1.2.4.80", // JPEG-LS Lossless
    "1.2.840.10008.1.2.4.81", // JPEG-LS Near-Lossless
    "1.2.840.10008.1.2.4.90", // JPEG 2000 Lossless
    "1.2.840.10008.1.2.4.91", // JPEG 2000
    "1.2.840.10008.1.2.5",    // RLE Lossless
  };
  return std::find(std::begin(decodable), std::end(decodable), uid) != std::end(decodable);
}

bool ScanFolder(const std::string& folder, std::vector<Series>& series,
  std::vector<std::string>& skipped, std::string& error)
{
  series.clear();
  skipped.clear();
  std::error_code ec;
  std::vector<std::string> files;
  // increment(ec), not ++: a folder changed or made unreadable while it is listed must give an
  // error, not a std::filesystem_error nothing catches.
  std::filesystem::directory_iterator it(folder, ec), end;
  for (; !ec && it != end; it.increment(ec))
  {
    std::error_code fileEc;
    if (it->is_regular_file(fileEc))
    {
      files.push_back(it->path().string());
    }
  }
  if (ec)
  {
    error = "cannot list the folder " + folder + ": " + ec.message();
    return false;
  }
  std::sort(files.begin(), files.end());
  std::map<std::string, Series> byUID;
  for (const std::string& file : files)
  {
    SliceHeader h;
    const HeaderStatus status = ReadHeader(file, h, error);
    if (status == HeaderStatus::Damaged)
    {
      return false;
    }
    if (status == HeaderStatus::NotDicom)
    {
      skipped.push_back(file);
    }
    else if (!h.SeriesUID.empty())
    {
      Series& s = byUID[h.SeriesUID];
      s.UID = h.SeriesUID;
      s.Description = h.SeriesDescription;
      s.Slices.push_back(h);
    }
  }
  error.clear();
  for (auto& item : byUID)
  {
    series.push_back(std::move(item.second));
  }
  std::stable_sort(series.begin(), series.end(),
    [](const Series& a, const Series& b) { return a.Slices.size() > b.Slices.size(); });
  if (series.empty())
  {
    error = "no DICOM image with a Series Instance UID in " + folder;
    return false;
  }
  return true;
}

int ChooseSeries(const std::vector<Series>& series, const std::string& file,
  const std::string& description, std::string& error)
{
  std::error_code ec;
  for (size_t i = 0; i < series.size() && !file.empty(); ++i)
  {
    for (const SliceHeader& s : series[i].Slices)
    {
      if (std::filesystem::equivalent(s.File, file, ec))
      {
        return static_cast<int>(i);
      }
    }
  }
  if (!file.empty())
  {
    error = file + " is not a DICOM image of a series";
    return -1;
  }
  if (description.empty())
  {
    return series.empty() ? -1 : 0; // largest first
  }
  std::string known;
  for (size_t i = 0; i < series.size(); ++i)
  {
    if (series[i].Description == description)
    {
      return static_cast<int>(i);
    }
    known += (i ? ", \"" : "\"") + series[i].Description + "\"";
  }
  error = "no series is described as \"" + description + "\"; the folder holds " + known;
  return -1;
}

bool StackSeries(const Series& series, Volume& volume, std::string& error)
{
  volume = Volume();
  if (series.Slices.empty())
  {
    error = "the series has no slices";
    return false;
  }
  for (const SliceHeader& s : series.Slices)
  {
    error = Unusable(s);
    if (error.empty())
    {
      error = Mismatch(series.Slices.front(), s);
    }
    if (!error.empty())
    {
      error = "cannot stack series " + series.UID + ": " + error;
      return false;
    }
  }
  const SliceHeader& first = series.Slices.front();
  double normal[3] = { 0, 0, 1 };
  if (series.Slices.size() > 1 && (!first.HasPosition || !first.HasOrientation))
  {
    error = first.File + " has no Image Position/Orientation (Patient): the slices cannot be " +
      "ordered or placed";
    return false;
  }
  if (first.HasOrientation && !SliceNormal(first.Orientation, normal))
  {
    error = first.File + " has an Image Orientation (Patient) that is not two orthogonal unit " +
      "vectors";
    return false;
  }
  volume.Slices = series.Slices;
  std::stable_sort(volume.Slices.begin(), volume.Slices.end(),
    [&normal](const SliceHeader& a, const SliceHeader& b)
    { return Dot(normal, a.Position) < Dot(normal, b.Position); });
  std::vector<double> along;
  for (const SliceHeader& s : volume.Slices)
  {
    along.push_back(Dot(normal, s.Position));
  }
  double step = 1;
  if (along.size() > 1 && !SliceStep(volume.Slices, along, step, volume.Warnings, error))
  {
    return false;
  }
  if (along.size() > 1)
  {
    TiltWarning(volume.Slices, normal, along.back() - along.front(), volume.Warnings);
  }

  volume.Dimensions[0] = static_cast<int>(first.Columns);
  volume.Dimensions[1] = static_cast<int>(first.Rows);
  volume.Dimensions[2] = static_cast<int>(volume.Slices.size());
  volume.Spacing[0] = first.PixelSpacing[1]; // between columns: along a row
  volume.Spacing[1] = first.PixelSpacing[0]; // between rows: along a column
  volume.Spacing[2] = step;
  // LPS to the plugin's world (RAS, as the NIfTI reader): x and y negated.
  const double lpsToRas[3] = { -1, -1, 1 };
  const double* axes[3] = { first.Orientation, first.Orientation + 3, normal };
  for (int i = 0; i < 3; ++i)
  {
    volume.Origin[i] = lpsToRas[i] * volume.Slices.front().Position[i];
    for (int j = 0; j < 3; ++j)
    {
      volume.Direction[3 * i + j] = lpsToRas[i] * axes[j][i];
    }
  }
  return true;
}
} // namespace dicom
} // namespace dsurf
