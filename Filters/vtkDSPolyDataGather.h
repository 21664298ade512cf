// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkDSPolyDataGather
 * @brief   Collects the pieces of a distributed vtkPolyData on process 0.
 *
 * The filters of this module solve on one process (the Delaunay complex and the deformable
 * surface are global objects), so under MPI (pvbatch, pvserver) they first bring every
 * process's piece of their point or surface input to process 0. GatherOnProcessZero() does
 * that for both: every process sends its piece, and process 0 appends the non-empty ones in
 * process order (vtkAppendPolyData: the points of process p follow those of processes < p;
 * point and cell arrays present in every non-empty piece are kept).
 *
 * It is collective: every process of the controller must call it, also those with an empty
 * piece, or process 0 waits forever. Ghost cells or points are not removed here (what counts
 * as a duplicate depends on the caller); duplicate points along piece seams come back as
 * separate points.
 *
 * Only static methods; there is nothing to instantiate.
 */
#ifndef vtkDSPolyDataGather_h
#define vtkDSPolyDataGather_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "vtkObject.h"

class vtkMultiProcessController;
class vtkPolyData;

class DEFORMABLESURFACEFILTERS_EXPORT vtkDSPolyDataGather : public vtkObject
{
public:
  static vtkDSPolyDataGather* New();
  vtkTypeMacro(vtkDSPolyDataGather, vtkObject);

  /**
   * Appends every process's `local` into `gathered` on process 0 and returns true there;
   * returns false, leaving `gathered` untouched, on the other processes. With no controller
   * or a single process, `gathered` becomes a shallow copy of `local` and the result is true.
   * `local` is not modified.
   */
  static bool GatherOnProcessZero(
    vtkMultiProcessController* controller, vtkPolyData* local, vtkPolyData* gathered);

  /**
   * True when `controller` spans more than one process, i.e. when a filter must gather.
   */
  static bool IsDistributed(vtkMultiProcessController* controller);

protected:
  vtkDSPolyDataGather() = default;
  ~vtkDSPolyDataGather() override = default;

private:
  vtkDSPolyDataGather(const vtkDSPolyDataGather&) = delete;
  void operator=(const vtkDSPolyDataGather&) = delete;
};

#endif
