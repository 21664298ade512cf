// SPDX-License-Identifier: BSD-3-Clause
// A volume too large for the memory left is refused before anything is allocated: a clear
// error naming the need and what is available, an empty output, and no growth of the process
// (never an out-of-memory kill part-way; docs/METHOD.md §9.6). The Scale-Space Gradient and the
// region preview are refused before they start (their output is the whole image); a solve
// when the force field of its first level, its bricks and tiles around the start with the local
// edge normalisation, would not fit, by a margin (a field counted below what is available would
// be made, and the solve would run for minutes). The volumes are
// real vtkImageData whose 8-bit voxels live in a lazily mapped zero region: large enough to need
// 1.7 to 5 times the machine's available memory, yet they cost nothing until written. Distributed
// (processes emulated by threads, EmulatedRanks.h), a field that fits on one process but not on
// another fails both before either allocates it: the one names its need and what is available, the
// other the size another process lacks, and neither waits for the other (a hang would hit the ctest
// timeout).
#include "CapsulePhantom.h"
#include "DSTestHelpers.h"
#include "PieceSlabs.h"

#include "dsMemory.h"
#include "dsMultilevel.h"
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
#include <cstdlib>
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

/// `voxels` bytes of zeros, mapped lazily (only the pages written cost memory); null on failure.
unsigned char* MapZeros(std::size_t voxels)
{
  void* zeros = mmap(
    nullptr, voxels, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  return zeros == MAP_FAILED ? nullptr : static_cast<unsigned char*>(zeros);
}

/// An n^3 image of 8-bit values read in place from `values` (point array "CT").
void MakeImage(vtkImageData* image, unsigned char* values, int n)
{
  image->SetDimensions(n, n, n);
  vtkNew<vtkUnsignedCharArray> array;
  array->SetName("CT");
  array->SetArray(values, static_cast<vtkIdType>(n) * n * n, 1);
  image->GetPointData()->SetScalars(array);
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
/// Two emulated processes, each holding its slab along z of an n x n x 2H image of 8-bit zeros
/// (lazily mapped: each slab a view of it, no copy), with a cube in the middle of rank 0's slab
/// as the start at Sigma 8 voxels (given: no probe) and RegionWeight 0 (no range): the first
/// field covers the cube and 6 sigma (49 voxels) around it on the image's own grid, within rank
/// 0's slab. The cube's side makes that part (27 bytes a voxel in bricks) about twice what is
/// available; rank 1's slab holds none of it. A cube, not a flat box: its start mesh is small
/// (a flat box 3 000 voxels wide split to edges of 4 sigma held 120 000 triangles, which a
/// sanitizer's quarantine kept resident).
void OneProcessShort(double available)
{
  const int side = static_cast<int>(std::ceil(std::cbrt(2.0 * available / 27.0))) - 98;
  const int n = side + 100, H = side + 140;
  dsurf::ImageGeometry g;
  g.Dimensions[0] = g.Dimensions[1] = n;
  g.Dimensions[2] = 2 * H;
  const std::size_t voxels = static_cast<std::size_t>(g.NumberOfVoxels());
  unsigned char* zeros = MapZeros(voxels);
  DS_CHECK(zeros != nullptr, "the lazily mapped distributed volume");
  if (!zeros)
  {
    return;
  }
  zeros[static_cast<std::size_t>(n) * n * (H / 2) + 1] = 1;
  std::cout << "distributed: " << n << " x " << n << " x " << 2 * H << " voxels of 8 bits"
            << std::endl;
  dsurf::MultilevelParameters p;
  p.Sigma = 8.0;
  p.RegionWeight = 0.0;
  p.Solver.NumberOfThreads = 1;
  const dsurf::TriangleMesh start = dstest::CapsuleBox(
    { (n - 1) / 2.0, (n - 1) / 2.0, H / 2.0 }, { side / 2.0, side / 2.0, side / 2.0 });
  dstest::EmulatedRanks emulated(2);
  std::vector<std::string> errors(2);
  std::vector<int> ok(2, 1);
  const double before = ResidentBytes();
  emulated.Run(
    [&](int r)
    {
      const dsurf::ImagePiece piece = dstest::SlabView(g, static_cast<const unsigned char*>(zeros),
        r, 2, [&](int a) { return dsurf::MultilevelSolver::DistributedGhostVoxels(p, g, a); });
      dsurf::MultilevelSolver solver;
      solver.SetParameters(p);
      solver.SetDistribution(piece, dstest::ReductionsOf(emulated, r));
      dsurf::ImageView whole = piece.Image;
      whole.Geometry = g;
      dsurf::TriangleMesh mesh = start;
      ok[r] = solver.Run(whole, mesh, &errors[r]);
    });
  std::cout << "rank 0: " << errors[0] << std::endl << "rank 1: " << errors[1] << std::endl;
  DS_CHECK(!ok[0] && !ok[1], "distributed: both processes refuse");
  DS_CHECK(errors[0].find("GiB of memory are available") != std::string::npos,
    "distributed: the short process names its need and what is available");
  DS_CHECK(errors[1].find("another process's part of the force field") != std::string::npos &&
      errors[1].find("GiB") != std::string::npos,
    "distributed: the other names the size another process lacks");
  const auto need = [](const std::string& e)
  {
    const std::size_t at = e.find("needs about ");
    return at == std::string::npos ? std::string() : e.substr(at, e.find("GiB", at) - at);
  };
  DS_CHECK(!need(errors[0]).empty() && need(errors[0]) == need(errors[1]),
    "distributed: both name the same need (" + need(errors[0]) + "GiB)");
  DS_CHECK_LE(ResidentBytes() - before, 64.0 * 1024 * 1024,
    "distributed: growth of the process while refusing (bytes)");
  munmap(zeros, voxels);
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
  // uint8 input, read in place, available / 3 voxels: the Scale-Space Gradient's field is 16
  // bytes a voxel, about 5x what is available. A sphere reaching 0.45 of the image from its
  // centre, at sigma 8 voxels (given: no probe), has its first field on the image's own grid,
  // counted as made around the sphere: the locally normalised P in tiles and the bricks near it
  // (TestFieldBricks checks that count), about 1.7x what is available.
  const int n = static_cast<int>(std::ceil(std::cbrt(available / 3.0)));
  const std::size_t voxels = static_cast<std::size_t>(n) * n * n;
  unsigned char* zeros = MapZeros(voxels);
  DS_CHECK(zeros != nullptr, "the lazily mapped volume");
  if (!zeros)
  {
    return dstest::Result("TestTooLargeVolume");
  }
  std::cout << n << "^3 voxels of 8 bits, " << available / 1073741824.0 << " GiB available"
            << std::endl;
  zeros[1] = 1; // not constant (the filter refuses a constant image), one page written
  vtkNew<vtkImageData> image;
  MakeImage(image, zeros, n);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(n / 2.0, n / 2.0, n / 2.0);
  sphere->SetRadius(0.45 * n);
  {
    vtkNew<vtkDeformableSurfaceFilter> filter;
    vtkNew<ErrorText> errors;
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
    filter->SetInputData(0, image);
    filter->SetInitialSurfaceConnection(sphere->GetOutputPort());
    filter->SetSigma(8.0);
    filter->SetRegionWeight(0.0);
    filter->SetEdgeNormalization(vtkDeformableSurfaceFilter::LOCAL);
    const double before = ResidentBytes();
    filter->Update();
    CheckRefused(*errors, before, "Deformable Surface");
    DS_CHECK(errors->Text.find("force field") != std::string::npos, "the first field is named");
    const std::size_t at = errors->Text.find("needs about ");
    const double need = at == std::string::npos ? 0.0 : std::atof(errors->Text.c_str() + at + 12);
    DS_CHECK_LE(1.3 * available / 1073741824.0 / need, 1.0,
      "1.3x the memory available over the first field's need (the test's margin)");
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

  // The preview is counted at 20 bytes a voxel of the whole image: available / 10 voxels, 2x.
  const int m = static_cast<int>(std::ceil(std::cbrt(available / 10.0)));
  const std::size_t previewVoxels = static_cast<std::size_t>(m) * m * m;
  unsigned char* previewZeros = MapZeros(previewVoxels);
  DS_CHECK(previewZeros != nullptr, "the lazily mapped preview volume");
  if (previewZeros)
  {
    previewZeros[1] = 1;
    vtkNew<vtkImageData> large;
    MakeImage(large, previewZeros, m);
    vtkNew<vtkDeformableSurfaceFilter> filter;
    vtkNew<ErrorText> errors;
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
    filter->SetInputData(0, large);
    filter->SetInitialSurfaceConnection(sphere->GetOutputPort());
    filter->SetPreviewRegion(true);
    const double before = ResidentBytes();
    filter->Update();
    CheckRefused(*errors, before, "Region preview");
    DS_CHECK(filter->GetOutput()->GetNumberOfPoints() == 0, "an empty preview");
    munmap(previewZeros, previewVoxels);
  }
  OneProcessShort(available);
  return dstest::Result("TestTooLargeVolume");
}

int main(int argc, char* argv[])
{
  return TestTooLargeVolume(argc, argv);
}
