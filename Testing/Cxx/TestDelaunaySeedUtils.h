// Checks shared by the TestDelaunaySeed* tests: is a triangle surface closed, consistently
// and outward oriented, what is its Euler characteristic and volume.
#ifndef TestDelaunaySeedUtils_h
#define TestDelaunaySeedUtils_h

#include "DSTestHelpers.h"

#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkIdList.h"
#include "vtkMassProperties.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <iostream>
#include <map>
#include <set>
#include <utility>

namespace dsseedtest
{
struct SurfaceFacts
{
  vtkIdType Triangles = 0;
  vtkIdType NonTriangles = 0;
  vtkIdType UsedPoints = 0;
  vtkIdType Edges = 0;
  vtkIdType EdgesNotTwice = 0;          // undirected edges not used by exactly 2 triangles
  vtkIdType DirectedEdgesRepeated = 0;  // directed edges used twice: inconsistent orientation
  vtkIdType VerticesNotOneFan = 0;      // vertices whose triangles do not form a single fan
  long Euler = 0;
  double SignedVolume = 0.0;            // divergence theorem, > 0 for outward normals
  double MassVolume = 0.0;              // vtkMassProperties
};

inline SurfaceFacts Measure(vtkPolyData* surface)
{
  SurfaceFacts f;
  std::map<std::pair<vtkIdType, vtkIdType>, int> directed;
  std::set<vtkIdType> used;
  std::map<vtkIdType, std::vector<std::pair<vtkIdType, vtkIdType>>> fans; // vertex -> (next, prev)
  vtkNew<vtkIdList> ids;
  auto polys = surface->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(ids);)
  {
    if (ids->GetNumberOfIds() != 3)
    {
      ++f.NonTriangles;
      continue;
    }
    ++f.Triangles;
    double p[3][3];
    for (int j = 0; j < 3; ++j)
    {
      used.insert(ids->GetId(j));
      ++directed[{ ids->GetId(j), ids->GetId((j + 1) % 3) }];
      fans[ids->GetId(j)].push_back({ ids->GetId((j + 1) % 3), ids->GetId((j + 2) % 3) });
      surface->GetPoint(ids->GetId(j), p[j]);
    }
    f.SignedVolume += (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) -
                        p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
                        p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0])) /
      6.0;
  }
  std::map<std::pair<vtkIdType, vtkIdType>, int> undirected;
  for (const auto& e : directed)
  {
    f.DirectedEdgesRepeated += e.second > 1 ? 1 : 0;
    undirected[{ std::min(e.first.first, e.first.second), std::max(e.first.first, e.first.second) }] +=
      e.second;
  }
  for (const auto& e : undirected)
  {
    f.EdgesNotTwice += e.second != 2 ? 1 : 0;
  }
  // A manifold vertex: following next->prev links from one triangle visits all of them.
  for (const auto& v : fans)
  {
    std::map<vtkIdType, vtkIdType> nextOf;
    for (const auto& np : v.second)
    {
      nextOf[np.second] = np.first; // around the vertex: prev -> next
    }
    vtkIdType start = v.second.front().second, cur = start;
    std::size_t steps = 0;
    do
    {
      auto it = nextOf.find(cur);
      if (it == nextOf.end())
      {
        break;
      }
      cur = it->second;
      ++steps;
    } while (cur != start && steps <= v.second.size());
    f.VerticesNotOneFan += (cur != start || steps != v.second.size()) ? 1 : 0;
  }
  f.UsedPoints = static_cast<vtkIdType>(used.size());
  f.Edges = static_cast<vtkIdType>(undirected.size());
  f.Euler = static_cast<long>(f.UsedPoints) - static_cast<long>(f.Edges) + static_cast<long>(f.Triangles);
  if (f.Triangles > 0)
  {
    vtkNew<vtkMassProperties> mass;
    mass->SetInputData(surface);
    mass->Update();
    f.MassVolume = mass->GetVolume();
  }
  std::cout << "  surface: " << f.Triangles << " triangles, " << f.UsedPoints << " points ("
            << surface->GetNumberOfPoints() << " stored), " << f.Edges << " edges, Euler " << f.Euler
            << ", signed volume " << f.SignedVolume << ", vtkMassProperties volume " << f.MassVolume
            << std::endl;
  return f;
}

/// The checks every valid seed surface must pass: closed, manifold, consistently and outward
/// oriented, no unused points, expected Euler characteristic (pass f.Euler to skip that one).
inline void CheckClosedManifold(const SurfaceFacts& f, vtkIdType storedPoints, long expectedEuler)
{
  DS_CHECK(f.Triangles > 0, "surface has triangles");
  DS_CHECK(f.NonTriangles == 0, "only triangles");
  DS_CHECK(f.EdgesNotTwice == 0, "closed: every edge used by exactly two triangles");
  DS_CHECK(f.DirectedEdgesRepeated == 0, "consistent orientation: no directed edge used twice");
  DS_CHECK(f.VerticesNotOneFan == 0, "manifold vertices: one fan each");
  DS_CHECK(f.UsedPoints == storedPoints, "output holds only used points");
  DS_CHECK(f.SignedVolume > 0, "outward orientation: signed volume > 0");
  DS_CHECK(f.Euler == expectedEuler, "Euler characteristic " + std::to_string(f.Euler) + " expected " +
      std::to_string(expectedEuler));
}

/// Counts errors and warnings an algorithm emits (and keeps them off the terminal).
class MessageCounter : public vtkCommand
{
public:
  static MessageCounter* New() { return new MessageCounter; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    const char* text = static_cast<const char*>(data);
    std::cout << "  [" << (event == vtkCommand::ErrorEvent ? "error" : "warning") << "] "
              << (text ? text : "") << std::endl;
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings)++;
  }
  int Errors = 0;
  int Warnings = 0;
};
} // namespace dsseedtest

#endif
