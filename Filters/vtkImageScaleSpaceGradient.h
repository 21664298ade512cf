#ifndef vtkImageScaleSpaceGradient_h
#define vtkImageScaleSpaceGradient_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class DEFORMABLESURFACEFILTERS_EXPORT vtkImageScaleSpaceGradient : public vtkImageAlgorithm
{
public:
  static vtkImageScaleSpaceGradient* New();
  vtkTypeMacro(vtkImageScaleSpaceGradient, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetClampMacro(SigmaFraction, double, 0.0, 1.0);
  vtkGetMacro(SigmaFraction, double);

protected:
  vtkImageScaleSpaceGradient();
  ~vtkImageScaleSpaceGradient() override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  double SigmaFraction = 1.0 / 6.0;

private:
  vtkImageScaleSpaceGradient(const vtkImageScaleSpaceGradient&) = delete;
  void operator=(const vtkImageScaleSpaceGradient&) = delete;
};
#endif
