#include "vtkImageScaleSpaceGradient.h"
#include "vtkObjectFactory.h"
vtkStandardNewMacro(vtkImageScaleSpaceGradient);
vtkImageScaleSpaceGradient::vtkImageScaleSpaceGradient() = default;
vtkImageScaleSpaceGradient::~vtkImageScaleSpaceGradient() = default;
void vtkImageScaleSpaceGradient::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
int vtkImageScaleSpaceGradient::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*)
{
  return 1;
}
