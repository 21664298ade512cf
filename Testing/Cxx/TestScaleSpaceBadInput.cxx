// SPDX-License-Identifier: BSD-3-Clause
// Bad input to vtkImageScaleSpaceGradient: no scalars, a 2-D image, an empty image,
// a 3-component array. Each must raise a vtkErrorMacro (counted through an
// ErrorEvent observer) and leave an empty output; a good image afterwards works.
#include "DSTestHelpers.h"

#include "ScaleSpaceTestUtils.h"
#include <cmath>

#include "dsScaleSpace.h"
#include "vtkCommand.h"
#include "vtkImageScaleSpaceGradient.h"

#include <iostream>
#include <string>

namespace
{
class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    ++this->Count;
    this->Last = data ? static_cast<const char*>(data) : "";
  }
  int Count = 0;
  std::string Last;
};

void Expect(const char* what, vtkImageData* input)
{
  vtkNew<vtkImageScaleSpaceGradient> filter;
  vtkNew<ErrorCounter> errors;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->SetInputData(input);
  filter->SetSigma(2.0);
  filter->Update();
  std::cout << what << ": " << errors->Count << " error(s), last: " << errors->Last << std::endl;
  DS_CHECK(errors->Count >= 1, std::string(what) + ": an error is reported");
  DS_CHECK(filter->GetOutput()->GetNumberOfPoints() == 0, std::string(what) + ": output is empty");
  DS_CHECK(filter->GetOutput()->GetPointData()->GetNumberOfArrays() == 0,
    std::string(what) + ": output has no arrays");
}
} // namespace

int TestScaleSpaceBadInput(int, char*[])
{
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  auto ramp = [](const double* x) { return x[0] + 2 * x[1]; };

  vtkNew<vtkImageData> noScalars;
  noScalars->SetDimensions(8, 8, 8);
  Expect("no scalars", noScalars);

  const int ext2d[6] = { 0, 15, 0, 15, 0, 0 };
  Expect("2-D image", sstest::MakeImage(ext2d, spacing, origin, identity, ramp));

  vtkNew<vtkImageData> empty;
  Expect("empty image", empty);

  const int ext[6] = { 0, 9, 0, 9, 0, 9 };
  auto vec = sstest::MakeImage(ext, spacing, origin, identity, ramp);
  vtkNew<vtkFloatArray> v3;
  v3->SetName("v");
  v3->SetNumberOfComponents(3);
  v3->SetNumberOfTuples(vec->GetNumberOfPoints());
  v3->Fill(1.0);
  vec->GetPointData()->SetScalars(v3);
  Expect("3-component scalars", vec);

  // One NaN voxel would spread along every recursive-filter line: rejected.
  auto withNaN = sstest::MakeImage(ext, spacing, origin, identity, ramp);
  withNaN->GetPointData()->GetScalars()->SetTuple1(123, std::nan(""));
  Expect("a NaN voxel", withNaN);

  // A shear (or scale) in the direction matrix: world coordinates would be wrong.
  const double shear[9] = { 1, 0.5, 0, 0, 1, 0, 0, 0, 1 };
  Expect("sheared direction matrix", sstest::MakeImage(ext, spacing, origin, shear, ramp));

  // The core rejects the same, and non-finite sigma, without touching the output.
  {
    dsurf::ImageGeometry g;
    g.Dimensions[0] = g.Dimensions[1] = 4;
    g.Dimensions[2] = 1;
    std::vector<float> data(16, 1.0f);
    dsurf::ScaleSpaceParameters p;
    dsurf::ForceField field;
    std::string error;
    DS_CHECK(!dsurf::ComputeScaleSpaceForce(data.data(), g, p, field, &error) && field.Empty(),
      "core: 2-D rejected");
    std::cout << "core 2-D: " << error << std::endl;
    g.Dimensions[2] = 4;
    data.assign(64, 1.0f);
    p.Sigma = std::nan("");
    DS_CHECK(!dsurf::ComputeScaleSpaceForce(data.data(), g, p, field, &error) && field.Empty(),
      "core: NaN sigma rejected");
    std::cout << "core NaN sigma: " << error << std::endl;
    p.Sigma = 1.0;
    g.Spacing[1] = 0.0;
    DS_CHECK(!dsurf::ComputeScaleSpaceForce(data.data(), g, p, field, &error) && field.Empty(),
      "core: zero spacing rejected");
    std::cout << "core zero spacing: " << error << std::endl;
  }

  // After bad input the same filter recovers on a good image; input untouched.
  vtkNew<vtkImageScaleSpaceGradient> filter;
  vtkNew<ErrorCounter> errors;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->SetInputData(noScalars);
  filter->Update();
  auto good = sstest::MakeImage(ext, spacing, origin, identity, ramp);
  filter->SetInputData(good);
  filter->Update();
  DS_CHECK(filter->GetOutput()->GetNumberOfPoints() == 1000, "good image after bad: full output");
  DS_CHECK(filter->GetOutput()->GetPointData()->GetArray("Force") != nullptr, "Force present");
  DS_CHECK(good->GetPointData()->GetNumberOfArrays() == 1, "input not modified");
  return dstest::Result("TestScaleSpaceBadInput");
}

int main(int argc, char* argv[])
{
  return TestScaleSpaceBadInput(argc, argv);
}
