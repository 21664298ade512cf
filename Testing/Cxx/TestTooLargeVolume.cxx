// SPDX-License-Identifier: BSD-3-Clause
// A volume too large for the memory left is refused before anything is allocated: a clear
// error naming the need and what is available, an empty output, and no growth of the process
// (never an out-of-memory kill part-way). The volume is a real vtkImageData whose 8-bit voxels
// live in a lazily mapped zero region: large enough to need 2.5x the machine's available
// memory, yet it costs nothing until it is written.
#include "DSTestHelpers.h"

#include "dsMemory.h"
#include "vtkDeformableSurfaceFilter.h"
#include "vtkImageScaleSpaceGradient.h"

#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <fstream>
#include <sys/mman.h>

namespace
{
class ErrorText : public vtkCommand
{
public:
  static ErrorText* New() { return new ErrorText; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    this->Text += data ? static_cast<const char*>(data) : "";
    ++this->Count;
  }
  std::string Text;
  int Count = 0;
};

/// The resident set of this process in bytes (VmRSS of /proc/self/status).
double ResidentBytes()
{
  std::ifstream status("/proc/self/status");
  std::string key;
  double kib = 0;
  while (status >> key)
  {
    if (key == "VmRSS:")
    {
      status >> kib;
      break;
    }
  }
  return kib * 1024.0;
}

void CheckRefused(const ErrorText& errors, double rssBefore, const std::string& who)
{
  std::cout << who << ": " << errors.Text << std::endl;
  DS_CHECK(errors.Count == 1, who + ": one error");
  DS_CHECK(errors.Text.find("GiB of memory are available") != std::string::npos,
    who + ": the message says what is available");
  DS_CHECK(errors.Text.find("Extract Subset") != std::string::npos, who + ": and what to do");
  DS_CHECK_LE(ResidentBytes() - rssBefore, 64.0 * 1024 * 1024,
    who + ": growth of the process while refusing (bytes)");
}
} // namespace

int TestTooLargeVolume(int, char*[])
{
  // The message itself, with the memory given.
  DS_CHECK(dsurf::MemoryShortfall(1e9, "x", 2e9).empty(), "what fits is not refused");
  DS_CHECK(dsurf::MemoryShortfall(1e9, "x", 0.0).empty(), "unknown memory refuses nothing");
  DS_CHECK(
    dsurf::MemoryShortfall(4e9, "This image", 2e9).find("This image needs about 3.73 GiB") == 0,
    "the need in GiB: " + dsurf::MemoryShortfall(4e9, "This image", 2e9));

  const double available = dsurf::AvailableMemoryBytes();
  if (!(available > 0))
  {
    std::cout << "available memory unknown on this system: nothing to refuse" << std::endl;
    return dstest::Result("TestTooLargeVolume");
  }
  // uint8 input, read in place: the force field of a whole-image level is 16 bytes a voxel,
  // so available / 8 voxels need 2x what is available.
  const int n = static_cast<int>(std::ceil(std::cbrt(available / 8.0)));
  const std::size_t voxels = static_cast<std::size_t>(n) * n * n;
  void* zeros = mmap(
    nullptr, voxels, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  DS_CHECK(zeros != MAP_FAILED, "the lazily mapped volume");
  if (zeros == MAP_FAILED)
  {
    return dstest::Result("TestTooLargeVolume");
  }
  std::cout << n << "^3 voxels of 8 bits, " << available / 1073741824.0 << " GiB available"
            << std::endl;
  vtkNew<vtkImageData> image;
  image->SetDimensions(n, n, n);
  vtkNew<vtkUnsignedCharArray> values;
  values->SetName("CT");
  values->SetArray(static_cast<unsigned char*>(zeros), static_cast<vtkIdType>(voxels), 1);
  image->GetPointData()->SetScalars(values);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(n / 2.0, n / 2.0, n / 2.0);
  sphere->SetRadius(n / 4.0);

  {
    vtkNew<vtkDeformableSurfaceFilter> filter;
    vtkNew<ErrorText> errors;
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
    filter->SetInputData(0, image);
    filter->SetInitialSurfaceConnection(sphere->GetOutputPort());
    const double before = ResidentBytes();
    filter->Update();
    CheckRefused(*errors, before, "Deformable Surface");
    DS_CHECK(filter->GetOutput()->GetNumberOfPoints() == 0, "an empty surface");
  }
  {
    vtkNew<vtkImageScaleSpaceGradient> gradient;
    vtkNew<ErrorText> errors;
    gradient->AddObserver(vtkCommand::ErrorEvent, errors);
    gradient->SetInputData(image);
    const double before = ResidentBytes();
    gradient->Update();
    CheckRefused(*errors, before, "Scale-Space Gradient");
    DS_CHECK(gradient->GetOutput()->GetNumberOfPoints() == 0, "an empty image");
  }
  munmap(zeros, voxels);
  return dstest::Result("TestTooLargeVolume");
}

int main(int argc, char* argv[])
{
  return TestTooLargeVolume(argc, argv);
}
