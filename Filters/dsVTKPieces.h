// SPDX-License-Identifier: BSD-3-Clause
// The MPI side of a distributed solve (docs/METHOD.md §9.8): the processes' reductions through
// a vtkMultiProcessController, and the piece of the image the pipeline delivered to this
// process. It uses VTK types, so it lives beside the VTK classes, not in the core.
#ifndef dsVTKPieces_h
#define dsVTKPieces_h

#include "dsPieceField.h"

#include <string>
#include <vector>

class vtkDataArray;
class vtkFieldData;
class vtkImageData;
class vtkInformation;
class vtkMultiProcessController;

namespace dsurf
{
struct ImageVolume;
struct MultilevelParameters;

/// Sum and Max as AllReduce calls of `controller` (which must outlive the reductions).
PieceReductions ControllerReductions(vtkMultiProcessController* controller);

/// Piece `piece` of `pieces` of the image whose whole extent is `wholeExtent`: Held is the
/// extent of the delivered image (`held` its values, read in place in their own type, with its
/// geometry), Owned the piece's extent without ghost levels as the pipeline splits an image
/// (vtkExtentTranslator, block mode), both in the whole extent's indices.
ImagePiece ImagePieceOf(
  const ImageView& held, const int extent[6], const int wholeExtent[6], int piece, int pieces);

/// The geometry of the whole extent, from that of the delivered extent.
ImageGeometry WholeGeometry(
  const ImageGeometry& held, const int extent[6], const int wholeExtent[6]);

/// Whether the image can go in pieces with these parameters: the potential in its default form
/// (EdgeWeight > 0, ImageWeight 0, the global maximum normalisation), the only one
/// ComputePieceForce computes; every other parameter is distributed.
bool PotentialAllowsPieces(const MultilevelParameters& parameters);

/// Asks the pipeline (`imageInfo`, which has the whole extent) for this process's piece of the
/// image with the ghost layers the levels' sigma need. The start is not known yet: the ghosts
/// allow for any sigma_0 up to its largest, extent / 6, and for its probe
/// (MultilevelSolver::DistributedGhostVoxels): a bounded number.
void RequestImagePiece(vtkMultiProcessController* controller,
  const MultilevelParameters& parameters, vtkInformation* imageInfo);

/// Whether the image requested in pieces came whole to process 0 and empty to the others (a
/// reader that cannot split its file: NIfTI, MetaImage): then process 0 solves alone, as with
/// the whole image requested. Collective: every process answers alike.
bool ImageOnProcessZeroOnly(
  vtkMultiProcessController* controller, vtkImageData* image, const int wholeExtent[6]);

/// This process's piece of the image (`array` read in place into `volume`, which must outlive
/// the piece) after the local checks, agreed by one reduction before any other collective call
/// so that no process is left waiting. False on every process (`problem` says why, naming this
/// process's own problem when it has one) when any process's piece is empty or invalid.
bool ReadImagePiece(const PieceReductions& reduce, int rank, int ranks, vtkImageData* image,
  vtkDataArray* array, const int wholeExtent[6], ImageVolume& volume, ImagePiece& piece,
  std::string& problem);

/// The voxels each process held (its piece and ghost layers), summed over the processes:
/// collective.
std::vector<double> HeldVoxels(
  const PieceReductions& reduce, const ImagePiece& piece, int rank, int ranks);

/// Field data PieceVoxels (the voxels each process held) and ImageVoxels (the whole image's).
void AddPieceFieldData(
  const std::vector<double>& held, const ImagePiece& piece, vtkFieldData* fieldData);
} // namespace dsurf

#endif
