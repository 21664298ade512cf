#include "vtkDSNIFTIImageReader.h"

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix4x4.h"
#include "vtkNIFTIImageHeader.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

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
      if (std::abs(dot - (a == b ? 1.0 : 0.0)) > 1e-4)
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
  // then the qform; a matrix is used only when it is a rotation.
  this->OrientationSource = "none";
  vtkNIFTIImageHeader* header = this->GetNIFTIHeader();
  vtkMatrix4x4* sform = header && header->GetSFormCode() > 0 ? this->GetSFormMatrix() : nullptr;
  vtkMatrix4x4* qform = header && header->GetQFormCode() > 0 ? this->GetQFormMatrix() : nullptr;
  if (sform)
  {
    Split(sform, rotation, translation);
    if (IsRotation(rotation))
    {
      this->OrientationSource = "sform";
      return true;
    }
    vtkWarningMacro("The sform of " << (this->GetFileName() ? this->GetFileName() : "the file")
                                    << " scales or shears; the qform is used if there is one.");
  }
  if (qform)
  {
    Split(qform, rotation, translation);
    if (IsRotation(rotation))
    {
      this->OrientationSource = "qform";
      return true;
    }
  }
  return false;
}

int vtkDSNIFTIImageReader::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    return 0;
  }
  // Always set: a file without a usable orientation must not keep the previous file's.
  double r[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 }, t[3] = { 0, 0, 0 };
  this->FileOrientation(r, t);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
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
  if (!this->Superclass::RequestData(request, inputVector, outputVector))
  {
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
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
}
