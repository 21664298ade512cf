// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkDSSeedPoints
 * @brief   The seed points a user placed: a point list held as a property, as vtkPolyData.
 *
 * The paper's workflow starts by clicking boundary points on slices (Lürig, Kobbelt & Ertl
 * 2000, section 7 and Fig. 10). This source holds those points as two flat lists, so that they
 * are a property of a ParaView proxy (state files, undo/redo, pvpython `SeedPoints(Points=...)`,
 * the GUI's point table) rather than a chain of selections and extracts:
 * - PointCoordinates: x y z of each point, one after the other (3 values per point);
 * - ObjectIds: one integer per point, the object the point seeds. Empty means every point seeds
 *   object 0.
 *
 * Output: vtkPolyData with one point and one vertex cell per seed point, in the given order
 * (so point i is the i-th triplet: Delaunay Seed Surface's SeedPointId indexes this list), the
 * points in double precision, and the int point array `ObjectId`. Under MPI only piece 0 holds
 * the points (the other pieces are empty), so a filter gathering the pieces sees each point once.
 *
 * Bad input gives an error and an empty output: a coordinate count that is not a multiple of 3,
 * a coordinate that is not finite (NaN, inf), or an ObjectIds count that is neither 0 nor the
 * number of points.
 */
#ifndef vtkDSSeedPoints_h
#define vtkDSSeedPoints_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <vector> // for the point and object lists

class DEFORMABLESURFACEFILTERS_EXPORT vtkDSSeedPoints : public vtkPolyDataAlgorithm
{
public:
  static vtkDSSeedPoints* New();
  vtkTypeMacro(vtkDSSeedPoints, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The coordinates, x y z per point (ParaView's `Points` property: SetNumberOfPointCoordinates
   * then SetPointCoordinate for each index). A count that is not a multiple of 3 is kept as
   * given and reported by RequestData.
   */
  void SetNumberOfPointCoordinates(int count);
  int GetNumberOfPointCoordinates() const;
  void SetPointCoordinate(int index, double value);
  double GetPointCoordinate(int index) const;
  ///@}

  ///@{
  /// The object each point seeds (ParaView's `ObjectIds` property); none: all object 0.
  void SetNumberOfObjectIds(int count);
  int GetNumberOfObjectIds() const;
  void SetObjectId(int index, int objectId);
  int GetObjectId(int index) const;
  ///@}

  /// Appends one point (x y z) seeding `objectId`; gives every earlier point object 0 if the
  /// ObjectIds list was empty. For C++ and Python users building a list point by point.
  void AddPoint(double x, double y, double z, int objectId = 0);
  /// Empties both lists.
  void RemoveAllPoints();

protected:
  vtkDSSeedPoints();
  ~vtkDSSeedPoints() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::vector<double> PointCoordinates;
  std::vector<int> ObjectIds;

private:
  vtkDSSeedPoints(const vtkDSSeedPoints&) = delete;
  void operator=(const vtkDSSeedPoints&) = delete;

  bool CheckLists() const;
};

#endif
