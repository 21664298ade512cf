#include "vtkImageScaleSpaceGradient.h"

#include "dsScaleSpace.h"

#include "vtkArrayDispatch.h"
#include "vtkCellData.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkImageScaleSpaceGradient);

namespace
{
// Any scalar type to float, one value per voxel.
struct ToFloat
{
  template <typename ArrayT>
  void operator()(ArrayT* array, std::vector<float>& out) const
  {
    const auto values = vtk::DataArrayValueRange<1>(array);
    out.resize(values.size());
    std::transform(values.cbegin(), values.cend(), out.begin(),
      [](typename decltype(values)::ValueType v) { return static_cast<float>(v); });
  }
};
} // namespace

//------------------------------------------------------------------------------
vtkImageScaleSpaceGradient::vtkImageScaleSpaceGradient()
{
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
  if (!input || input->GetNumberOfPoints() <= 0)
  {
    vtkErrorMacro("The input image is empty.");
    return 1;
  }
  dsurf::ImageGeometry geometry;
  input->GetDimensions(geometry.Dimensions);
  if (geometry.Dimensions[0] < 2 || geometry.Dimensions[1] < 2 || geometry.Dimensions[2] < 2)
  {
    vtkErrorMacro("A 3-D image is needed (at least 2 voxels along every axis); got "
      << geometry.Dimensions[0] << "x" << geometry.Dimensions[1] << "x"
      << geometry.Dimensions[2] << ".");
    return 1;
  }
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
  if (!scalars)
  {
    vtkErrorMacro("No point scalars to process: choose a point array (Scalars).");
    return 1;
  }
  if (scalars->GetNumberOfComponents() != 1 ||
    scalars->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    vtkErrorMacro("The array '" << (scalars->GetName() ? scalars->GetName() : "(unnamed)")
                                << "' must be a point array with one component.");
    return 1;
  }

  input->GetSpacing(geometry.Spacing);
  const int* extent = input->GetExtent();
  // Index (0,0,0) of the core is the first voxel of the extent.
  input->TransformIndexToPhysicalPoint(extent[0], extent[2], extent[4], geometry.Origin);
  std::copy(input->GetDirectionMatrix()->GetData(), input->GetDirectionMatrix()->GetData() + 9,
    geometry.Direction);

  double sigma = this->Sigma;
  if (!(sigma > 0.0))
  {
    sigma = this->SigmaFraction * geometry.MeanExtent();
  }

  // Float input of the usual layout is used in place; anything else is converted.
  std::vector<float> converted;
  const float* values = nullptr;
  vtkFloatArray* asFloat = vtkFloatArray::FastDownCast(scalars);
  if (asFloat)
  {
    values = asFloat->GetPointer(0);
  }
  else
  {
    if (!vtkArrayDispatch::Dispatch::Execute(scalars, ToFloat{}, converted))
    {
      ToFloat{}(scalars, converted);
    }
    values = converted.data();
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
  std::string error;
  if (!dsurf::ComputeScaleSpaceForceInto(
        values, geometry, parameters, potential->GetPointer(0), force->GetPointer(0), &error))
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
