// SPDX-License-Identifier: BSD-3-Clause
#include "vtkDSDICOMSeriesReader.h"

#include "dsDicomPixels.h"
#include "dsDicomSeries.h"
#include "dsMemory.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <filesystem>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkDSDICOMSeriesReader);

struct vtkDSDICOMSeriesReader::State
{
  std::vector<dsurf::dicom::Series> Series;
  dsurf::dicom::Volume Volume;
  int ScalarType = VTK_SHORT;
  std::string Error; ///< why the last RequestInformation found no volume; "" when it did
  std::string TransferSyntax, Warnings;
};

//------------------------------------------------------------------------------
vtkDSDICOMSeriesReader::vtkDSDICOMSeriesReader()
  : Internal(new State)
{
  this->SetNumberOfInputPorts(0);
}

vtkDSDICOMSeriesReader::~vtkDSDICOMSeriesReader()
{
  this->SetFileName(nullptr);
  this->SetSeriesDescription(nullptr);
}

//------------------------------------------------------------------------------
void vtkDSDICOMSeriesReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "SeriesDescription: " << (this->SeriesDescription ? this->SeriesDescription : "")
     << "\n";
  os << indent << "NumberOfSeries: " << this->Internal->Series.size() << "\n";
  os << indent << "TransferSyntax: " << this->Internal->TransferSyntax << "\n";
}

//------------------------------------------------------------------------------
int vtkDSDICOMSeriesReader::CanReadFile(const char* name)
{
  if (!name)
  {
    return 0;
  }
  std::error_code ec;
  std::string error;
  dsurf::dicom::SliceHeader header;
  if (!std::filesystem::is_directory(name, ec))
  {
    return dsurf::dicom::ReadHeader(name, header, error) == dsurf::dicom::HeaderStatus::Ok;
  }
  // A folder: one DICOM file among its first entries is enough (folders can be large).
  int looked = 0;
  // increment(ec), not ++, which throws when the folder changes while it is listed.
  std::filesystem::directory_iterator it(name, ec), end;
  for (; !ec && it != end; it.increment(ec))
  {
    std::error_code fileEc;
    if (it->is_regular_file(fileEc) &&
      dsurf::dicom::ReadHeader(it->path().string(), header, error) ==
        dsurf::dicom::HeaderStatus::Ok)
    {
      return 1;
    }
    if (++looked == 20)
    {
      break;
    }
  }
  return 0;
}

int vtkDSDICOMSeriesReader::GetNumberOfSeries()
{
  return static_cast<int>(this->Internal->Series.size());
}

const char* vtkDSDICOMSeriesReader::GetSeriesDescriptionOf(int series)
{
  if (series < 0 || series >= this->GetNumberOfSeries())
  {
    return nullptr;
  }
  return this->Internal->Series[series].Description.c_str();
}

const char* vtkDSDICOMSeriesReader::GetTransferSyntax()
{
  return this->Internal->TransferSyntax.c_str();
}

const char* vtkDSDICOMSeriesReader::GetPlacementWarnings()
{
  return this->Internal->Warnings.c_str();
}

//------------------------------------------------------------------------------
bool vtkDSDICOMSeriesReader::FindVolume()
{
  State& s = *this->Internal;
  s = State();
  if (!this->FileName || !*this->FileName)
  {
    s.Error = "no FileName: give a folder of DICOM files or one file of the series";
    return false;
  }
  std::error_code ec;
  const std::filesystem::path path(this->FileName);
  const bool isFolder = std::filesystem::is_directory(path, ec);
  if (!isFolder && !std::filesystem::is_regular_file(path, ec))
  {
    s.Error = std::string(this->FileName) + " does not exist";
    return false;
  }
  std::string folder = isFolder ? path.string() : path.parent_path().string();
  if (folder.empty())
  {
    folder = ".";
  }
  std::vector<std::string> skipped;
  if (!dsurf::dicom::ScanFolder(folder, s.Series, skipped, s.Error))
  {
    return false;
  }
  const int chosen = dsurf::dicom::ChooseSeries(s.Series, isFolder ? "" : path.string(),
    this->SeriesDescription ? this->SeriesDescription : "", s.Error);
  if (chosen < 0 || !dsurf::dicom::StackSeries(s.Series[chosen], s.Volume, s.Error))
  {
    // A file damaged beyond recognition is skipped as not DICOM: name such files, they may be
    // the missing slice.
    for (size_t i = 0; i < skipped.size() && i < 5; ++i)
    {
      s.Error += (i ? ", " : " (files skipped as not DICOM: ") + skipped[i];
    }
    s.Error += skipped.empty() ? "" : (skipped.size() > 5 ? ", ...)" : ")");
    return false;
  }
  s.ScalarType = dsurf::dicom::OutputScalarType(s.Volume.Slices);
  const dsurf::dicom::Volume& v = s.Volume;
  const double voxels = double(v.Dimensions[0]) * v.Dimensions[1] * v.Dimensions[2];
  s.Error = dsurf::MemoryShortfall(voxels * vtkDataArray::GetDataTypeSize(s.ScalarType),
    "the DICOM series' " + std::to_string(v.Dimensions[0]) + " x " +
      std::to_string(v.Dimensions[1]) + " x " + std::to_string(v.Dimensions[2]) + " image");
  if (!s.Error.empty())
  {
    return false;
  }
  s.TransferSyntax = s.Volume.Slices.front().TransferSyntaxName;
  for (const std::string& warning : s.Volume.Warnings)
  {
    s.Warnings += warning + "\n";
  }
  return true;
}

//------------------------------------------------------------------------------
// Bad input still returns 1 with an empty extent: the output is then emptied by RequestData
// instead of keeping the previous file's image.
int vtkDSDICOMSeriesReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!this->FindVolume())
  {
    vtkErrorMacro(<< this->Internal->Error << ".");
    vtkImageData::GetData(outInfo)->Initialize(); // in case RequestData is not called
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    return 1;
  }
  const dsurf::dicom::Volume& v = this->Internal->Volume;
  for (const std::string& warning : v.Warnings)
  {
    vtkWarningMacro(<< this->FileName << ": " << warning << ".");
  }
  const int whole[6] = { 0, v.Dimensions[0] - 1, 0, v.Dimensions[1] - 1, 0, v.Dimensions[2] - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkDataObject::SPACING(), v.Spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), v.Origin, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), v.Direction, 9);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, this->Internal->ScalarType, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkDSDICOMSeriesReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* image = vtkImageData::GetData(outInfo);
  image->Initialize();
  State& s = *this->Internal;
  if (!s.Error.empty())
  {
    return 1; // reported by RequestInformation
  }
  const dsurf::dicom::Volume& v = s.Volume;
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(v.Dimensions);
  volume->SetSpacing(v.Spacing);
  volume->SetOrigin(v.Origin);
  volume->SetDirectionMatrix(v.Direction);
  volume->AllocateScalars(s.ScalarType, 1);
  vtkDataArray* values = volume->GetPointData()->GetScalars();
  values->SetName("DICOMImage");
  const vtkIdType perSlice = vtkIdType(v.Dimensions[0]) * v.Dimensions[1];
  for (int k = 0; k < v.Dimensions[2]; ++k)
  {
    std::string error;
    if (!dsurf::dicom::ReadSlice(
          v.Slices[k], s.ScalarType, values->GetVoidPointer(k * perSlice), error))
    {
      vtkErrorMacro(<< error << ".");
      return 1;
    }
    this->UpdateProgress((k + 1.0) / v.Dimensions[2]);
  }
  image->ShallowCopy(volume);
  return 1;
}
