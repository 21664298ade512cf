// SPDX-License-Identifier: BSD-3-Clause
#include "vtkDSNIFTIImageReader.h"

#include "dsNiftiHeader.h"

#include "vtkDataObject.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix4x4.h"
#include "vtkNIFTIImageHeader.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkDSNIFTIImageReader);

namespace
{
/// R R^T = I and det R = +1, to 1e-4: a rotation.
bool IsRotation(const double r[9])
{
  for (int a = 0; a < 3; ++a)
  {
    for (int b = 0; b < 3; ++b)
    {
      const double dot =
        r[3 * a] * r[3 * b] + r[3 * a + 1] * r[3 * b + 1] + r[3 * a + 2] * r[3 * b + 2];
      if (!(std::abs(dot - (a == b ? 1.0 : 0.0)) <= 1e-4)) // NaN is no rotation either
      {
        return false;
      }
    }
  }
  const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
    r[2] * (r[3] * r[7] - r[4] * r[6]);
  return det > 0;
}

void Split(vtkMatrix4x4* m, double rotation[9], double translation[3])
{
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      rotation[3 * i + j] = m->GetElement(i, j);
    }
    translation[i] = m->GetElement(i, 3);
  }
}
} // namespace

bool vtkDSNIFTIImageReader::FileOrientation(double rotation[9], double translation[3])
{
  // The sform first when the file says it is meant (sform_code > 0): templates and atlases
  // put their standard space there (MNI for Colin27) and often an unrelated qform beside it;
  // then the qform; a matrix is used only when it is a rotation (rotation and translation are
  // left as they are otherwise: a refused matrix must not place the image).
  this->OrientationSource = "none";
  vtkNIFTIImageHeader* header = this->GetNIFTIHeader();
  vtkMatrix4x4* sform = header && header->GetSFormCode() > 0 ? this->GetSFormMatrix() : nullptr;
  vtkMatrix4x4* qform = header && header->GetQFormCode() > 0 ? this->GetQFormMatrix() : nullptr;
  double r[9], t[3];
  auto usable = [&r, &t](vtkMatrix4x4* m)
  {
    if (!m)
    {
      return false;
    }
    Split(m, r, t);
    return IsRotation(r) && std::isfinite(t[0] + t[1] + t[2]);
  };
  if (usable(sform))
  {
    this->OrientationSource = "sform";
  }
  else
  {
    if (sform)
    {
      vtkWarningMacro("The sform of " << (this->GetFileName() ? this->GetFileName() : "the file")
                                      << " scales or shears; the qform is used if there is one.");
    }
    if (!usable(qform))
    {
      return false;
    }
    this->OrientationSource = "qform";
  }
  std::copy(r, r + 9, rotation);
  std::copy(t, t + 3, translation);
  return true;
}

bool vtkDSNIFTIImageReader::FilesToRead(std::string& headerFile, std::string& dataFile)
{
  if (this->FileNames)
  {
    for (vtkIdType i = 0; i < this->FileNames->GetNumberOfValues(); ++i)
    {
      const std::string& name = this->FileNames->GetValue(i);
      (CheckExtension(name.c_str(), ".hdr") ? headerFile : dataFile) = name;
    }
    return this->FileNames->GetNumberOfValues() == 2;
  }
  if (!this->FileName)
  {
    return false;
  }
  // ReplaceExtension returns the name of a file that exists (new[]), or null.
  auto existing = [this](const char* from, const char* to)
  {
    char* found = ReplaceExtension(this->FileName, from, to);
    std::string name = found ? found : "";
    delete[] found;
    return name;
  };
  headerFile = existing(".img", ".hdr");
  dataFile = existing(".hdr", ".img");
  return true;
}

bool vtkDSNIFTIImageReader::CheckFile(bool unitSpacing[3])
{
  std::string headerFile, dataFile;
  if (!this->FilesToRead(headerFile, dataFile))
  {
    return true; // VTK's reader refuses it before reading anything
  }
  dsurf::NiftiVerdict verdict;
  if (headerFile.empty() || dataFile.empty())
  {
    verdict.Error = std::string("cannot find the ") + (headerFile.empty() ? "header" : "data") +
      " file of " + (this->FileName ? this->FileName : "the file names given");
  }
  else
  {
    verdict = dsurf::CheckNiftiFile(
      headerFile, dataFile, static_cast<uint64_t>(std::max<vtkIdType>(0, this->MaximumDataSize)));
  }
  if (!verdict.Error.empty())
  {
    vtkErrorMacro(<< "Not read: " << verdict.Error);
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    return false;
  }
  for (const std::string& warning : verdict.Warnings)
  {
    vtkWarningMacro(<< headerFile << ": " << warning);
  }
  std::copy(verdict.UnitSpacing, verdict.UnitSpacing + 3, unitSpacing);
  return true;
}

void vtkDSNIFTIImageReader::ClearOutput(vtkInformation* outInfo)
{
  if (vtkDataObject* output = outInfo->Get(vtkDataObject::DATA_OBJECT()))
  {
    output->Initialize();
  }
  const int empty[6] = { 0, -1, 0, -1, 0, -1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
}

int vtkDSNIFTIImageReader::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  bool unitSpacing[3] = { false, false, false };
  if (!this->CheckFile(unitSpacing) ||
    !this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    this->OrientationSource = "none";
    ClearOutput(outInfo);
    return 0;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    this->DataSpacing[axis] = unitSpacing[axis] ? 1.0 : this->DataSpacing[axis];
  }
  outInfo->Set(vtkDataObject::SPACING(), this->DataSpacing, 3);
  // Always set: a file without a usable orientation must not keep the previous file's.
  double r[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 }, t[3] = { 0, 0, 0 };
  this->FileOrientation(r, t);
  double origin[3] = { 0, 0, 0 };
  if (outInfo->Has(vtkDataObject::ORIGIN()))
  {
    outInfo->Get(vtkDataObject::ORIGIN(), origin);
  }
  double placed[3];
  for (int i = 0; i < 3; ++i)
  {
    placed[i] = r[3 * i] * origin[0] + r[3 * i + 1] * origin[1] + r[3 * i + 2] * origin[2] + t[i];
  }
  outInfo->Set(vtkDataObject::ORIGIN(), placed, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), r, 9);
  return 1;
}

int vtkDSNIFTIImageReader::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!this->Superclass::RequestData(request, inputVector, outputVector))
  {
    // VTK's reader keeps what it read before the error (a truncated gzip stream): nothing of it
    // may reach a filter.
    ClearOutput(outInfo);
    return 0;
  }
  vtkImageData* image = vtkImageData::GetData(outInfo);
  if (image && outInfo->Has(vtkDataObject::DIRECTION()))
  {
    image->SetOrigin(outInfo->Get(vtkDataObject::ORIGIN()));
    image->SetDirectionMatrix(outInfo->Get(vtkDataObject::DIRECTION()));
  }
  return 1;
}

void vtkDSNIFTIImageReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OrientationSource: " << this->OrientationSource << "\n";
  os << indent << "MaximumDataSize: " << this->MaximumDataSize << "\n";
}
