// Links DeformableSurface::Filters from an installed package and runs the
// scale-space gradient on a small binary sphere; prints the force range.
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkImageScaleSpaceGradient.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <cstdio>

int main()
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(32, 32, 32);
  image->AllocateScalars(VTK_FLOAT, 1);
  float* v = static_cast<float*>(image->GetScalarPointer());
  for (int k = 0; k < 32; ++k)
    for (int j = 0; j < 32; ++j)
      for (int i = 0; i < 32; ++i)
        *v++ = ((i - 16) * (i - 16) + (j - 16) * (j - 16) + (k - 16) * (k - 16) < 100) ? 1.f : 0.f;

  vtkNew<vtkImageScaleSpaceGradient> gradient;
  gradient->SetInputData(image);
  gradient->SetSigmaFraction(0.1);
  gradient->Update();
  vtkDataArray* force = gradient->GetOutput()->GetPointData()->GetArray("Force");
  if (!force)
  {
    std::fprintf(stderr, "no Force array\n");
    return 1;
  }
  double range[2];
  force->GetRange(range, -1);
  std::printf("|Force| in [%g, %g]\n", range[0], range[1]);
  return range[1] > 0 ? 0 : 1;
}
