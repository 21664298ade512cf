// SPDX-License-Identifier: BSD-3-Clause
#include "vtkDSPolyDataGather.h"

#include "vtkAppendPolyData.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <vector>

vtkStandardNewMacro(vtkDSPolyDataGather);

bool vtkDSPolyDataGather::IsDistributed(vtkMultiProcessController* controller)
{
  return controller && controller->GetNumberOfProcesses() > 1;
}

bool vtkDSPolyDataGather::GatherOnProcessZero(
  vtkMultiProcessController* controller, vtkPolyData* local, vtkPolyData* gathered)
{
  if (!gathered)
  {
    return false;
  }
  if (!IsDistributed(controller))
  {
    if (local)
    {
      gathered->ShallowCopy(local);
    }
    else
    {
      gathered->Initialize();
    }
    return true;
  }

  // Marshalling goes through a copy, so `local` keeps its arrays and cells as they were.
  vtkNew<vtkPolyData> piece;
  if (local)
  {
    piece->ShallowCopy(local);
  }
  std::vector<vtkSmartPointer<vtkDataObject>> pieces;
  controller->Gather(piece, pieces, 0);
  if (controller->GetLocalProcessId() != 0)
  {
    return false;
  }

  // An empty piece may come back as nullptr or as a data object without points; either way
  // it adds nothing, and leaving it out keeps vtkAppendPolyData from dropping arrays that
  // only the empty piece lacks.
  vtkNew<vtkAppendPolyData> append;
  for (const auto& received : pieces)
  {
    vtkPolyData* poly = vtkPolyData::SafeDownCast(received);
    if (poly && poly->GetNumberOfPoints() > 0)
    {
      append->AddInputData(poly);
    }
  }
  gathered->Initialize();
  if (append->GetNumberOfInputConnections(0) > 0)
  {
    append->Update();
    gathered->ShallowCopy(append->GetOutput());
  }
  return true;
}
