// SPDX-License-Identifier: BSD-3-Clause
#include "vtkImageScaleSpaceGradient.h"

#include "dsScaleSpace.h"
#include "dsVTKImage.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <string>

vtkStandardNewMacro(vtkImageScaleSpaceGradient);

//------------------------------------------------------------------------------
vtkImageScaleSpaceGradient::vtkImageScaleSpaceGradient()
{
  // The potential's defaults are the core's (dsurf::ScaleSpaceParameters, same names).
  const dsurf::ScaleSpaceParameters defaults;
  this->EdgeWeight = defaults.EdgeWeight;
  this->ImageWeight = defaults.ImageWeight;
  this->NormalizePotential = defaults.NormalizePotential;
  this->NumberOfThreads = defaults.NumberOfThreads;
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

vtkImageScaleSpaceGradient::~vtkImageScaleSpaceGradient() = default;

//------------------------------------------------------------------------------
void vtkImageScaleSpaceGradient::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Sigma: " << this->Sigma << "\n";
  os << indent << "SigmaFraction: " << this->SigmaFraction << "\n";
  os << indent << "EdgeWeight: " << this->EdgeWeight << "\n";
  os << indent << "ImageWeight: " << this->ImageWeight << "\n";
  os << indent << "NormalizePotential: " << this->NormalizePotential << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "EffectiveSigma: " << this->EffectiveSigma << "\n";
}

//------------------------------------------------------------------------------
// The Gaussian reaches across the whole volume at large sigma: always ask for all of it.
int vtkImageScaleSpaceGradient::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  int whole[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), whole, 6);
  return 1;
}

//------------------------------------------------------------------------------
int vtkImageScaleSpaceGradient::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (!output)
  {
    return 0;
  }
  output->Initialize();
  dsurf::ImageVolume volume;
  std::string error;
  if (!dsurf::GetImageVolume(input, this->GetInputArrayToProcess(0, inputVector),
        dsurf::ForceFieldBytesPerVoxel, volume, error))
  {
    vtkErrorMacro(<< error << ".");
    return 1;
  }
  if (!volume.Note.empty())
  {
    vtkDebugMacro(<< volume.Note << ".");
  }
  const dsurf::ImageGeometry& geometry = volume.Image.Geometry;

  const std::string nonFinite =
    dsurf::FirstNonFinite({ { "Sigma", this->Sigma }, { "SigmaFraction", this->SigmaFraction },
      { "EdgeWeight", this->EdgeWeight }, { "ImageWeight", this->ImageWeight } });
  if (!nonFinite.empty())
  {
    vtkErrorMacro(<< nonFinite << " is not a finite number: set it to a value in its range.");
    return 1;
  }
  double sigma = this->Sigma;
  if (!(sigma > 0.0))
  {
    sigma = this->SigmaFraction * geometry.MeanExtent();
  }

  this->UpdateProgress(0.1);

  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkFloatArray> potential;
  potential->SetName("Potential");
  potential->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> force;
  force->SetName("Force");
  force->SetNumberOfComponents(3);
  force->SetNumberOfTuples(n);

  dsurf::ScaleSpaceParameters parameters;
  parameters.Sigma = sigma;
  parameters.EdgeWeight = this->EdgeWeight;
  parameters.ImageWeight = this->ImageWeight;
  parameters.NormalizePotential = this->NormalizePotential;
  parameters.NumberOfThreads = this->NumberOfThreads;
  if (!dsurf::ComputeScaleSpaceForceInto(
        volume.Image, parameters, potential->GetPointer(0), force->GetPointer(0), &error))
  {
    vtkErrorMacro("Scale-space gradient failed: " << error);
    return 1;
  }
  this->EffectiveSigma = sigma;

  output->CopyStructure(input);
  output->GetPointData()->PassData(input->GetPointData());
  output->GetCellData()->PassData(input->GetCellData());
  output->GetFieldData()->PassData(input->GetFieldData());
  output->GetPointData()->AddArray(potential);
  output->GetPointData()->AddArray(force);
  vtkNew<vtkDoubleArray> sigmaArray;
  sigmaArray->SetName("Sigma");
  sigmaArray->InsertNextValue(sigma);
  output->GetFieldData()->AddArray(sigmaArray);
  this->UpdateProgress(1.0);
  return 1;
}
