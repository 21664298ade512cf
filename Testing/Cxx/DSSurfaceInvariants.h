// SPDX-License-Identifier: BSD-3-Clause
// The invariants every surface a filter of this module produces must keep, checked the same
// way by every test that produces one:
//  - finite coordinates, triangles only, no unused points;
//  - a closed start stays closed, 2-manifold (each edge in two triangles, each vertex one fan),
//    consistently oriented, with the start's Euler characteristic and orientation sign;
//  - the "SelfIntersections" field (vtkDeformableSurfaceFilter) is 0 unless the test says why not;
//  - the inputs (image scalars and geometry, start surface points and cells) are bit-identical
//    before and after the run (InputFingerprint, InputGuard).
// Also the message recorder the bad-input tests use to assert the text of errors and warnings.
#ifndef DSSurfaceInvariants_h
#define DSSurfaceInvariants_h

#include "DSTestHelpers.h"
#include "TestSolverMeshes.h"

#include "dsSelfIntersectionCount.h"
#include "dsTriangleMesh.h"

#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkMassProperties.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace dstest
{
struct SurfaceFacts
{
  vtkIdType Triangles = 0;
  vtkIdType NonTriangles = 0; // polygons with other than 3 points, strips
  vtkIdType OtherCells = 0;   // vertices and lines
  vtkIdType UsedPoints = 0;
  vtkIdType NonFinitePoints = 0; // points with a NaN or infinite coordinate
  vtkIdType Edges = 0;
  vtkIdType EdgesNotTwice = 0;         // undirected edges not used by exactly 2 triangles
  vtkIdType DirectedEdgesRepeated = 0; // directed edges used twice: inconsistent orientation
  vtkIdType VerticesNotOneFan = 0;     // vertices whose triangles do not form a single fan
  long Euler = 0;
  double SignedVolume = 0.0; // divergence theorem, > 0 for outward normals
  double MassVolume = 0.0;   // vtkMassProperties
  bool Closed() const { return this->Triangles > 0 && this->EdgesNotTwice == 0; }
};

/// Topology and volume of the triangles of `surface` (other polygons are counted, not used).
inline SurfaceFacts Measure(vtkPolyData* surface)
{
  SurfaceFacts f;
  std::map<std::pair<vtkIdType, vtkIdType>, int> directed;
  std::set<vtkIdType> used;
  std::map<vtkIdType, std::vector<std::pair<vtkIdType, vtkIdType>>> fans; // vertex -> (next, prev)
  vtkNew<vtkIdList> ids;
  f.NonTriangles = surface->GetNumberOfStrips();
  f.OtherCells = surface->GetNumberOfVerts() + surface->GetNumberOfLines();
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double x[3];
    surface->GetPoint(i, x);
    f.NonFinitePoints += std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]) ? 0 : 1;
  }
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
    undirected[{ std::min(e.first.first, e.first.second),
      std::max(e.first.first, e.first.second) }] += e.second;
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
  f.Euler =
    static_cast<long>(f.UsedPoints) - static_cast<long>(f.Edges) + static_cast<long>(f.Triangles);
  if (f.Triangles > 0 && f.NonFinitePoints == 0)
  {
    vtkNew<vtkMassProperties> mass;
    mass->SetInputData(surface);
    mass->Update();
    f.MassVolume = mass->GetVolume();
  }
  std::cout << "  surface: " << f.Triangles << " triangles, " << f.UsedPoints << " points ("
            << surface->GetNumberOfPoints() << " stored), " << f.Edges << " edges, Euler "
            << f.Euler << ", signed volume " << f.SignedVolume << ", vtkMassProperties volume "
            << f.MassVolume << std::endl;
  return f;
}

/// The facts of a start surface as vtkDeformableSurfaceFilter sees it: polygons and strips
/// split into triangles (which keeps the Euler characteristic), vertices and lines ignored,
/// points closer than 1e-6 of the bounding box merged (ParaView's Box has each face apart).
inline SurfaceFacts MeasureStart(vtkPolyData* start)
{
  vtkNew<vtkPolyData> faces;
  faces->SetPoints(start->GetPoints());
  faces->SetPolys(start->GetPolys());
  faces->SetStrips(start->GetStrips());
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(faces);
  vtkNew<vtkCleanPolyData> merged;
  merged->SetInputConnection(triangles->GetOutputPort());
  merged->SetTolerance(1e-6);
  merged->ConvertPolysToLinesOff();
  merged->Update();
  return Measure(merged->GetOutput());
}

/// The checks every valid closed surface must pass: closed, manifold, consistently oriented,
/// finite, no unused points, the expected Euler characteristic (pass f.Euler to skip that one)
/// and outward orientation (signed volume > 0) when `outward`.
inline void CheckClosedManifold(const SurfaceFacts& f, vtkIdType storedPoints, long expectedEuler,
  bool outward = true, const std::string& label = "")
{
  const std::string at = label.empty() ? "" : label + ": ";
  DS_CHECK(f.Triangles > 0, at + "surface has triangles");
  DS_CHECK(f.NonTriangles == 0 && f.OtherCells == 0, at + "only triangles");
  DS_CHECK(f.NonFinitePoints == 0, at + "finite coordinates");
  DS_CHECK(f.EdgesNotTwice == 0, at + "closed: every edge used by exactly two triangles");
  DS_CHECK(
    f.DirectedEdgesRepeated == 0, at + "consistent orientation: no directed edge used twice");
  DS_CHECK(f.VerticesNotOneFan == 0, at + "manifold vertices: one fan each");
  DS_CHECK(f.UsedPoints == storedPoints, at + "output holds only used points");
  if (outward)
  {
    DS_CHECK(f.SignedVolume > 0, at + "outward orientation: signed volume > 0");
  }
  DS_CHECK(f.Euler == expectedEuler,
    at + "Euler characteristic " + std::to_string(f.Euler) + " expected " +
      std::to_string(expectedEuler));
}

/// What a test allows a produced surface to differ from the invariants, each with its reason.
struct SurfaceAllowance
{
  /// Self-intersections the surface may keep (the field's value is printed either way).
  int SelfIntersections = 0;
};

/// The invariants of a surface `output` produced from the start surface `start`: finite,
/// triangles only, every point used; if the start is closed (after triangulating it), the
/// output is closed and manifold, consistently oriented like the start (same sign of the
/// volume) and keeps its Euler characteristic; an open start gives a consistently oriented,
/// edge-manifold output. The "SelfIntersections" field, when present, is within the allowance.
inline SurfaceFacts CheckSurfaceInvariants(vtkPolyData* start, vtkPolyData* output,
  const std::string& label, const SurfaceAllowance& allow = SurfaceAllowance())
{
  std::cout << label << ": invariants" << std::endl;
  const SurfaceFacts s = MeasureStart(start);
  const SurfaceFacts f = Measure(output);
  if (s.Closed())
  {
    CheckClosedManifold(f, output->GetNumberOfPoints(), s.Euler, false, label);
    DS_CHECK((f.SignedVolume > 0) == (s.SignedVolume > 0), label + ": orientation as the start's");
  }
  else
  {
    DS_CHECK(f.Triangles > 0, label + ": surface has triangles");
    DS_CHECK(f.NonTriangles == 0 && f.OtherCells == 0, label + ": only triangles");
    DS_CHECK(f.NonFinitePoints == 0, label + ": finite coordinates");
    DS_CHECK(f.DirectedEdgesRepeated == 0, label + ": consistent orientation");
    DS_CHECK(
      f.UsedPoints == output->GetNumberOfPoints(), label + ": output holds only used points");
  }
  if (vtkDataArray* selfx = output->GetFieldData()->GetArray("SelfIntersections"))
  {
    DS_CHECK_LE(selfx->GetTuple1(0), allow.SelfIntersections, label + ": SelfIntersections field");
  }
  return f;
}

/// The same invariants for the core's meshes (dsurf::MultilevelSolver's start and result),
/// with the self-intersections counted directly (the core has no field data).
inline SurfaceFacts CheckSurfaceInvariants(const dsurf::TriangleMesh& start,
  const dsurf::TriangleMesh& output, const std::string& label,
  const SurfaceAllowance& allow = SurfaceAllowance())
{
  DS_CHECK_LE(
    dsurf::CountSelfIntersections(output), allow.SelfIntersections, label + ": self-intersections");
  return CheckSurfaceInvariants(ToPolyData(start), ToPolyData(output), label, allow);
}

/// 64-bit FNV-1a over the bytes given, chained.
inline std::uint64_t Hash(const void* data, std::size_t bytes, std::uint64_t h)
{
  const unsigned char* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i)
  {
    h = (h ^ p[i]) * 1099511628211ULL;
  }
  return h;
}

inline std::uint64_t HashArray(vtkDataArray* a, std::uint64_t h)
{
  if (!a)
  {
    return Hash("-", 1, h);
  }
  const int nc = a->GetNumberOfComponents();
  h = Hash(&nc, sizeof nc, h);
  for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < nc; ++c)
    {
      const double v = a->GetComponent(t, c); // bit pattern: NaN == NaN here
      h = Hash(&v, sizeof v, h);
    }
  }
  return h;
}

inline std::uint64_t HashCells(vtkCellArray* cells, std::uint64_t h)
{
  if (!cells)
  {
    return Hash("-", 1, h);
  }
  vtkNew<vtkIdList> ids;
  for (cells->InitTraversal(); cells->GetNextCell(ids);)
  {
    const vtkIdType n = ids->GetNumberOfIds();
    h = Hash(&n, sizeof n, h);
    h = Hash(ids->GetPointer(0), sizeof(vtkIdType) * static_cast<std::size_t>(n), h);
  }
  return h;
}

/// A fingerprint of what a filter must leave unchanged in its input: for an image the extent,
/// spacing, origin, direction and every point array; for a poly data the points, the four cell
/// arrays and every point array.
inline std::uint64_t InputFingerprint(vtkDataObject* data)
{
  std::uint64_t h = 1469598103934665603ULL;
  if (auto* image = vtkImageData::SafeDownCast(data))
  {
    int extent[6];
    image->GetExtent(extent);
    h = Hash(extent, sizeof extent, h);
    h = Hash(image->GetSpacing(), 3 * sizeof(double), h);
    h = Hash(image->GetOrigin(), 3 * sizeof(double), h);
    h = Hash(image->GetDirectionMatrix()->GetData(), 9 * sizeof(double), h);
  }
  if (auto* poly = vtkPolyData::SafeDownCast(data))
  {
    h = HashArray(poly->GetPoints() ? poly->GetPoints()->GetData() : nullptr, h);
    for (vtkCellArray* cells :
      { poly->GetVerts(), poly->GetLines(), poly->GetPolys(), poly->GetStrips() })
    {
      h = HashCells(cells, h);
    }
  }
  if (auto* set = vtkDataSet::SafeDownCast(data))
  {
    vtkPointData* pd = set->GetPointData();
    for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
    {
      const char* name = pd->GetArrayName(i);
      h = Hash(name ? name : "", name ? std::strlen(name) : 0, h);
      h = HashArray(pd->GetArray(i), h);
    }
  }
  return h;
}

/// Fingerprints its inputs when made; Check() counts a failure for each that changed since.
class InputGuard
{
public:
  InputGuard(std::initializer_list<vtkDataObject*> inputs)
    : InputGuard(std::vector<vtkDataObject*>(inputs))
  {
  }
  explicit InputGuard(const std::vector<vtkDataObject*>& inputs)
  {
    for (vtkDataObject* d : inputs)
    {
      if (d)
      {
        this->Inputs.emplace_back(d, InputFingerprint(d));
      }
    }
  }
  void Check(const std::string& label) const
  {
    for (const auto& in : this->Inputs)
    {
      DS_CHECK(InputFingerprint(in.first) == in.second,
        label + ": input " + in.first->GetClassName() + " unchanged (bit-identical)");
    }
  }

private:
  std::vector<std::pair<vtkSmartPointer<vtkDataObject>, std::uint64_t>> Inputs;
};

/// Updates `filter` with every input fingerprinted before (their producers updated first) and
/// compared after: a filter must never change what it reads.
inline void UpdateWithInputsUnchanged(vtkAlgorithm* filter, const std::string& label)
{
  std::vector<vtkDataObject*> inputs;
  for (int port = 0; port < filter->GetNumberOfInputPorts(); ++port)
  {
    for (int c = 0; c < filter->GetNumberOfInputConnections(port); ++c)
    {
      filter->GetInputAlgorithm(port, c)->Update(filter->GetInputConnection(port, c)->GetIndex());
      inputs.push_back(filter->GetInputDataObject(port, c));
    }
  }
  const InputGuard guard(inputs);
  filter->Update();
  guard.Check(label);
}

/// A vtkDeformableSurfaceFilter run checked whole: updated with its inputs unchanged, then its
/// output surface (port 0) checked against the start surface (input port 1).
inline SurfaceFacts UpdateAndCheckSurface(vtkAlgorithm* filter, const std::string& label,
  const SurfaceAllowance& allow = SurfaceAllowance())
{
  UpdateWithInputsUnchanged(filter, label);
  return CheckSurfaceInvariants(vtkPolyData::SafeDownCast(filter->GetInputDataObject(1, 0)),
    vtkPolyData::SafeDownCast(filter->GetOutputDataObject(0)), label, allow);
}

/// Records the errors and warnings an object emits (keeping them off vtkOutputWindow), with
/// their text, so a test can assert what the user is told.
class MessageCounter : public vtkCommand
{
public:
  static MessageCounter* New() { return new MessageCounter; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    const char* text = static_cast<const char*>(data);
    const bool error = event == vtkCommand::ErrorEvent;
    std::cout << "  [" << (error ? "error" : "warning") << "] " << (text ? text : "") << std::endl;
    (error ? this->Errors : this->Warnings)++;
    (error ? this->ErrorText : this->WarningText) += std::string(text ? text : "") + "\n";
  }
  /// Observe errors and warnings of `object`.
  void Watch(vtkObject* object)
  {
    object->AddObserver(vtkCommand::ErrorEvent, this);
    object->AddObserver(vtkCommand::WarningEvent, this);
  }
  void Reset()
  {
    this->Errors = this->Warnings = 0;
    this->ErrorText.clear();
    this->WarningText.clear();
  }
  int Errors = 0;
  int Warnings = 0;
  std::string ErrorText, WarningText;
};
} // namespace dstest

#endif
