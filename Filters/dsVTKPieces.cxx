// SPDX-License-Identifier: BSD-3-Clause
#include "dsVTKPieces.h"

#include "dsFieldGrid.h"
#include "dsMultilevel.h"
#include "dsScaleSpace.h"
#include "dsVTKImage.h"

#include "vtkCommunicator.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <vector>

namespace dsurf
{
PieceReductions ControllerReductions(vtkMultiProcessController* controller)
{
  PieceReductions reduce;
  reduce.Sum = [controller](std::vector<double>& values)
  {
    std::vector<double> sum(values.size());
    controller->AllReduce(
      values.data(), sum.data(), static_cast<vtkIdType>(values.size()), vtkCommunicator::SUM_OP);
    values.swap(sum);
  };
  reduce.Max = [controller](double value)
  {
    double result = value;
    controller->AllReduce(&value, &result, 1, vtkCommunicator::MAX_OP);
    return result;
  };
  return reduce;
}

ImageGeometry WholeGeometry(
  const ImageGeometry& held, const int extent[6], const int wholeExtent[6])
{
  ImageGeometry whole = held;
  double first[3];
  for (int a = 0; a < 3; ++a)
  {
    whole.Dimensions[a] = wholeExtent[2 * a + 1] - wholeExtent[2 * a] + 1;
    first[a] = wholeExtent[2 * a] - extent[2 * a];
  }
  held.IndexToWorld(first, whole.Origin);
  return whole;
}

ImagePiece ImagePieceOf(
  const ImageView& held, const int extent[6], const int wholeExtent[6], int piece, int pieces)
{
  ImagePiece p;
  p.Whole = WholeGeometry(held.Geometry, extent, wholeExtent);
  int owned[6];
  vtkNew<vtkExtentTranslator> translator;
  translator->PieceToExtentThreadSafe(
    piece, pieces, 0, const_cast<int*>(wholeExtent), owned, vtkExtentTranslator::BLOCK_MODE, 0);
  for (int a = 0; a < 3; ++a)
  {
    p.Held.Begin[a] = extent[2 * a] - wholeExtent[2 * a];
    p.Held.End[a] = extent[2 * a + 1] - wholeExtent[2 * a] + 1;
    p.Owned.Begin[a] = owned[2 * a] - wholeExtent[2 * a];
    p.Owned.End[a] = std::max(p.Owned.Begin[a], owned[2 * a + 1] - wholeExtent[2 * a] + 1);
  }
  p.Image = held;
  p.Image.Geometry = p.HeldGeometry(); // placed by the whole image's, as the core places it
  return p;
}

bool PotentialAllowsPieces(const MultilevelParameters& parameters)
{
  return parameters.EdgeWeight > 0 && parameters.ImageWeight == 0 &&
    parameters.EdgeNormalization == EdgeNormalization::GlobalMaximum;
}

void RequestImagePiece(vtkMultiProcessController* controller,
  const MultilevelParameters& parameters, vtkInformation* imageInfo)
{
  const int* whole = imageInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  ImageGeometry geometry;
  for (int a = 0; a < 3; ++a)
  {
    geometry.Dimensions[a] = whole[2 * a + 1] - whole[2 * a] + 1;
    geometry.Spacing[a] =
      imageInfo->Has(vtkDataObject::SPACING()) ? imageInfo->Get(vtkDataObject::SPACING())[a] : 1.0;
  }
  int ghost = 0;
  for (int a = 0; a < 3; ++a)
  {
    ghost = std::max(ghost, MultilevelSolver::DistributedGhostVoxels(parameters, geometry, a));
  }
  imageInfo->Set(
    vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), controller->GetLocalProcessId());
  imageInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(),
    controller->GetNumberOfProcesses());
  imageInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), ghost);
}

bool ImageOnProcessZeroOnly(
  vtkMultiProcessController* controller, vtkImageData* image, const int wholeExtent[6])
{
  const bool empty = !image || image->GetNumberOfPoints() <= 0;
  bool mine = empty;
  if (controller->GetLocalProcessId() == 0)
  {
    mine = !empty && std::equal(wholeExtent, wholeExtent + 6, image->GetExtent());
  }
  return ControllerReductions(controller).Max(mine ? 0.0 : 1.0) == 0.0;
}

bool ReadImagePiece(const PieceReductions& reduce, int rank, int ranks, vtkImageData* image,
  vtkDataArray* array, const int wholeExtent[6], ImageVolume& volume, ImagePiece& piece,
  std::string& problem)
{
  if (!image || image->GetNumberOfPoints() <= 0)
  {
    problem = "this process's piece of the image is empty";
  }
  else
  {
    // Only the piece's values (a float copy if one is needed): a solve's fields are checked as
    // they are made (docs/METHOD.md §9.6).
    GetImageVolume(image, array, 0.0, volume, problem);
  }
  if (reduce.Max(problem.empty() ? 0.0 : 1.0) > 0.0)
  {
    if (problem.empty())
    {
      problem = "another process's piece of the image is empty or invalid";
    }
    return false;
  }
  piece = ImagePieceOf(volume.Image, image->GetExtent(), wholeExtent, rank, ranks);
  return true;
}

std::vector<double> HeldVoxels(
  const PieceReductions& reduce, const ImagePiece& piece, int rank, int ranks)
{
  std::vector<double> held(ranks, 0.0);
  held[rank] = static_cast<double>(piece.Held.NumberOfVoxels());
  reduce.Sum(held);
  return held;
}

void AddPieceFieldData(
  const std::vector<double>& held, const ImagePiece& piece, vtkFieldData* fieldData)
{
  vtkNew<vtkDoubleArray> voxels;
  voxels->SetName("PieceVoxels");
  for (double h : held)
  {
    voxels->InsertNextValue(h);
  }
  fieldData->AddArray(voxels);
  vtkNew<vtkDoubleArray> whole;
  whole->SetName("ImageVoxels");
  whole->InsertNextValue(static_cast<double>(piece.Whole.NumberOfVoxels()));
  fieldData->AddArray(whole);
}
} // namespace dsurf
