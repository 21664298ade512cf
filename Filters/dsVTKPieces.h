// The MPI side of a distributed solve (docs/METHOD.md §9.8): the processes' reductions through
// a vtkMultiProcessController, and the piece of the image the pipeline delivered to this
// process. It uses VTK types, so it lives beside the VTK classes, not in the core.
#ifndef dsVTKPieces_h
#define dsVTKPieces_h

#include "dsPieceField.h"

class vtkMultiProcessController;

namespace dsurf
{
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
} // namespace dsurf

#endif
