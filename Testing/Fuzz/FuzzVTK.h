// SPDX-License-Identifier: BSD-3-Clause
// Shared by the fuzzers of the VTK filters: counting error and warning events, a deep
// fingerprint of a vtkPolyData (to assert that inputs stay unchanged, NaNs included), the
// conversion of a filter's triangle output to dsurf::TriangleMesh, and input coordinates.
#ifndef FuzzVTK_h
#define FuzzVTK_h

#include "FuzzCheck.h"

#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkIdList.h"
#include "vtkObject.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <fuzzer/FuzzedDataProvider.h>

#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

namespace fuzzvtk
{
class MessageCounter : public vtkCommand
{
public:
  static MessageCounter* New() { return new MessageCounter; }
  void Execute(vtkObject*, unsigned long event, void*) override
  {
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings) += 1;
  }
  int Errors = 0, Warnings = 0;
};

/// Every byte of the points (their bit patterns: NaN == NaN here) and of every cell array.
inline std::vector<unsigned char> Fingerprint(vtkPolyData* pd)
{
  std::vector<unsigned char> bytes;
  auto add = [&bytes](const void* p, size_t n)
  {
    const auto* c = static_cast<const unsigned char*>(p);
    bytes.insert(bytes.end(), c, c + n);
  };
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    double x[3];
    pd->GetPoint(i, x);
    add(x, sizeof(x));
  }
  vtkNew<vtkIdList> ids;
  for (vtkCellArray* cells : { pd->GetVerts(), pd->GetLines(), pd->GetPolys(), pd->GetStrips() })
  {
    const vtkIdType n = cells ? cells->GetNumberOfCells() : -1;
    add(&n, sizeof(n));
    for (vtkIdType c = 0; cells && c < n; ++c)
    {
      cells->GetCellAtId(c, ids);
      const vtkIdType k = ids->GetNumberOfIds();
      add(&k, sizeof(k));
      add(ids->GetPointer(0), sizeof(vtkIdType) * k);
    }
  }
  return bytes;
}

/// With FUZZ_VERBOSE set, prints the points of a data set (to read a saved crash input).
inline void PrintPoints(const char* what, vtkPointSet* data)
{
  if (!std::getenv("FUZZ_VERBOSE"))
  {
    return;
  }
  std::fprintf(
    stderr, "%s: %lld points\n", what, static_cast<long long>(data->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double x[3];
    data->GetPoint(i, x);
    std::fprintf(
      stderr, "  %lld: %.17g %.17g %.17g\n", static_cast<long long>(i), x[0], x[1], x[2]);
  }
}

/// With FUZZ_VERBOSE set, prints the cells of a vtkPolyData by kind.
inline void PrintCells(const char* what, vtkPolyData* pd)
{
  if (!std::getenv("FUZZ_VERBOSE"))
  {
    return;
  }
  const char* kinds[4] = { "vertex", "line", "polygon", "strip" };
  vtkCellArray* arrays[4] = { pd->GetVerts(), pd->GetLines(), pd->GetPolys(), pd->GetStrips() };
  vtkNew<vtkIdList> ids;
  for (int k = 0; k < 4; ++k)
  {
    for (vtkIdType c = 0; arrays[k] && c < arrays[k]->GetNumberOfCells(); ++c)
    {
      arrays[k]->GetCellAtId(c, ids);
      std::fprintf(stderr, "%s %s:", what, kinds[k]);
      for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      {
        std::fprintf(stderr, " %lld", static_cast<long long>(ids->GetId(i)));
      }
      std::fprintf(stderr, "\n");
    }
  }
}

/// The triangles and points of a filter's surface output as a mesh (its topology not built yet);
/// false when a polygon is not a triangle or other cells are present.
inline bool ToMesh(vtkPolyData* pd, dsurf::TriangleMesh& mesh)
{
  mesh = dsurf::TriangleMesh();
  mesh.Points.resize(pd->GetNumberOfPoints());
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    pd->GetPoint(i, mesh.Points[i].data());
  }
  vtkNew<vtkIdList> ids;
  vtkCellArray* polys = pd->GetPolys();
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    polys->GetCellAtId(c, ids);
    if (ids->GetNumberOfIds() != 3)
    {
      return false;
    }
    mesh.Triangles.push_back({ static_cast<int>(ids->GetId(0)), static_cast<int>(ids->GetId(1)),
      static_cast<int>(ids->GetId(2)) });
  }
  return pd->GetNumberOfVerts() == 0 && pd->GetNumberOfLines() == 0 && pd->GetNumberOfStrips() == 0;
}

/// One input coordinate: mostly on a coarse lattice of `step` in [0, cells * step] (coincident,
/// collinear and coplanar points come often), sometimes any double at all (NaN, inf, huge).
inline double Coordinate(FuzzedDataProvider& in, double step, int cells)
{
  switch (in.ConsumeIntegralInRange(0, 15))
  {
    case 0:
      return in.ConsumeFloatingPoint<double>();
    case 1:
      return std::numeric_limits<double>::quiet_NaN();
    case 2:
      return std::numeric_limits<double>::infinity();
    case 3:
      return step * cells * in.ConsumeProbability<double>();
    default:
      return step * in.ConsumeIntegralInRange(0, cells);
  }
}
} // namespace fuzzvtk

#endif
