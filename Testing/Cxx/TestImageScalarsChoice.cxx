// SPDX-License-Identifier: BSD-3-Clause
// Which image array the filters use (vtkDeformableSurfaceFilter, vtkImageScaleSpaceGradient):
// the selected one; when the selection is empty or names a missing array (pvpython: the
// reader had not run when the filter was made), the active point scalars, else the only point
// array; an error naming the choices when neither exists, and an error naming the array and
// the choices when the selected one has several components. The output is then empty.
#include "DSSurfaceInvariants.h"

#include "vtkCommand.h"
#include "vtkDeformableSurfaceFilter.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageScaleSpaceGradient.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <cmath>
#include <string>

namespace
{
class ErrorText : public vtkCommand
{
public:
  static ErrorText* New() { return new ErrorText; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    ++this->Count;
    this->Text += data ? static_cast<const char*>(data) : "";
  }
  int Count = 0;
  std::string Text;
};

/// A soft ball of radius 8 in a 32^3 image, as a named float array (not made active).
vtkSmartPointer<vtkFloatArray> Ball(const char* name, int components = 1)
{
  const int n = 32;
  auto values = vtkSmartPointer<vtkFloatArray>::New();
  values->SetName(name);
  values->SetNumberOfComponents(components);
  values->SetNumberOfTuples(n * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double r =
          std::sqrt((i - 16.0) * (i - 16.0) + (j - 16.0) * (j - 16.0) + (k - 16.0) * (k - 16.0));
        for (int c = 0; c < components; ++c)
        {
          values->SetComponent(i + n * (j + n * k), c, 1.0 / (1.0 + std::exp(2.0 * (r - 8.0))));
        }
      }
  return values;
}

vtkSmartPointer<vtkImageData> Image()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(32, 32, 32);
  return image;
}

struct Outcome
{
  vtkIdType SurfacePoints = 0, GradientPoints = 0;
  int Errors = 0;
  std::string Text;
};

/// Both filters on `image`, with the array `selected` (nullptr: the filters' default, the
/// active scalars; "" as ParaView sets it while the domain is empty).
Outcome Run(vtkImageData* image, const char* selected)
{
  vtkNew<ErrorText> errors;
  vtkNew<vtkSphereSource> start;
  start->SetCenter(16, 16, 16);
  start->SetRadius(11);
  vtkNew<vtkDeformableSurfaceFilter> ds;
  ds->AddObserver(vtkCommand::ErrorEvent, errors);
  ds->SetInputData(0, image);
  ds->SetInitialSurfaceConnection(start->GetOutputPort());
  ds->SetSigma(1.5);
  ds->SetMaxLevels(0);
  ds->SetMaxSweepsPerLevel(50);
  vtkNew<vtkImageScaleSpaceGradient> gradient;
  gradient->AddObserver(vtkCommand::ErrorEvent, errors);
  gradient->SetInputData(image);
  gradient->SetSigma(1.5);
  if (selected)
  {
    ds->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, selected);
    gradient->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, selected);
  }
  dstest::UpdateWithInputsUnchanged(ds, "Deformable Surface");
  dstest::UpdateWithInputsUnchanged(gradient, "scale-space gradient");
  if (ds->GetOutput()->GetNumberOfPoints() > 0) // the error cases assert their empty output
  {
    dstest::CheckSurfaceInvariants(start->GetOutput(), ds->GetOutput(), "Deformable Surface");
  }
  Outcome o;
  o.SurfacePoints = ds->GetOutput()->GetNumberOfPoints();
  o.GradientPoints = gradient->GetOutput()->GetPointData()->GetArray("Force") ? 1 : 0;
  o.Errors = errors->Count;
  o.Text = errors->Text;
  return o;
}
} // namespace

int TestImageScalarsChoice(int, char*[])
{
  // Selected name empty or missing, the array is the active scalars: it is used.
  {
    auto image = Image();
    image->GetPointData()->SetScalars(Ball("density"));
    for (const char* selected : { "", "no such array" })
    {
      const Outcome o = Run(image, selected);
      std::cout << "selected '" << selected << "', active scalars: " << o.SurfacePoints
                << " points, " << o.Errors << " errors" << std::endl;
      DS_CHECK(o.Errors == 0 && o.SurfacePoints > 0 && o.GradientPoints > 0,
        std::string("selection '") + selected + "' falls back to the active scalars");
    }
  }
  // No active scalars, one point array: it is used.
  {
    auto image = Image();
    image->GetPointData()->AddArray(Ball("only"));
    const Outcome o = Run(image, "");
    DS_CHECK(
      o.Errors == 0 && o.SurfacePoints > 0 && o.GradientPoints > 0, "the only point array is used");
  }
  // No active scalars, two point arrays, nothing selected: an error naming both, empty outputs.
  {
    auto image = Image();
    image->GetPointData()->AddArray(Ball("first"));
    image->GetPointData()->AddArray(Ball("second"));
    std::cout << "(two error messages naming the choices are expected next)" << std::endl;
    const Outcome o = Run(image, "");
    DS_CHECK(o.Errors == 2 && o.SurfacePoints == 0 && o.GradientPoints == 0,
      "two arrays, none chosen: errors");
    DS_CHECK(o.Text.find("'first', 'second'") != std::string::npos,
      "the error names the choices: " + o.Text);
    // Choosing one of them works.
    const Outcome chosen = Run(image, "second");
    DS_CHECK(chosen.Errors == 0 && chosen.SurfacePoints > 0, "two arrays, one chosen: no error");
  }
  // The selected array has three components: an error naming it and the one-component choices.
  {
    auto image = Image();
    image->GetPointData()->AddArray(Ball("vectors", 3));
    image->GetPointData()->AddArray(Ball("density"));
    std::cout << "(two error messages about 'vectors' are expected next)" << std::endl;
    const Outcome o = Run(image, "vectors");
    DS_CHECK(
      o.Errors == 2 && o.SurfacePoints == 0 && o.GradientPoints == 0, "three components: errors");
    DS_CHECK(o.Text.find("'vectors' has 3 components") != std::string::npos,
      "the error names the array: " + o.Text);
    DS_CHECK(
      o.Text.find("'density'") != std::string::npos, "the error names the choices: " + o.Text);
  }
  return dstest::Result("TestImageScalarsChoice");
}

int main(int argc, char* argv[])
{
  return TestImageScalarsChoice(argc, argv);
}
