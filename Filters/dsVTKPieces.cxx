#include "dsVTKPieces.h"

#include "vtkCommunicator.h"
#include "vtkExtentTranslator.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"

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
} // namespace dsurf
