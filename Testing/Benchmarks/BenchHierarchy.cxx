// SPDX-License-Identifier: BSD-3-Clause
// Whole multilevel solves from the box enclosing the volume on sphere and cube
// phantoms (128^3, 256^3), beside vtkFlyingEdges3D on the same volumes.
// Usage: BenchHierarchy [sizes...]   (default 128 256)
#include "../Cxx/HierarchyPhantoms.h"
#include "dsMultilevel.h"
#include "dsSelfIntersectionCount.h"

#include "vtkFloatArray.h"
#include "vtkFlyingEdges3D.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

using Clock = std::chrono::steady_clock;

namespace
{
double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

struct Case
{
  std::string Name;
  int N;
  std::vector<float> Volume;
  std::function<double(const dsurf::Vec3&)> Distance;
};

void RunFlyingEdges(const Case& c)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(c.N, c.N, c.N);
  vtkNew<vtkFloatArray> s;
  s->SetArray(const_cast<float*>(c.Volume.data()), static_cast<vtkIdType>(c.Volume.size()), 1);
  s->SetName("s");
  image->GetPointData()->SetScalars(s);
  vtkNew<vtkFlyingEdges3D> fe;
  fe->SetInputData(image);
  fe->SetValue(0, 0.5);
  fe->ComputeNormalsOff();
  fe->ComputeGradientsOff();
  const auto t0 = Clock::now();
  fe->Update();
  const auto t1 = Clock::now();
  vtkPolyData* out = fe->GetOutput();
  dsurf::TriangleMesh m;
  m.Points.resize(out->GetNumberOfPoints());
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    out->GetPoint(i, m.Points[i].data());
  }
  vtkCellArray* polys = out->GetPolys();
  vtkIdType npts;
  const vtkIdType* pts;
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
  {
    if (npts == 3)
    {
      m.Triangles.push_back({ int(pts[0]), int(pts[1]), int(pts[2]) });
    }
  }
  const auto acc = dsphantom::Measure(m, c.Distance);
  double minAngle = 180, below20 = 1.0 - dsphantom::FractionMinAngleAtLeast(m, 20.0);
  for (int t = 0; t < m.NumberOfTriangles(); ++t)
  {
    minAngle = std::min(minAngle, m.MinAngleDegrees(t));
  }
  std::printf("| %-12s | FlyingEdges3D (iso 0.5) | %7.3f | - | - | %8d | %6.3f | %6.3f | %5.1f | "
              "%5.1f%% | - |\n",
    c.Name.c_str(), Seconds(t0, t1), m.NumberOfTriangles(), acc.Mean, acc.Max, minAngle,
    100 * below20);
}

void RunDeformable(const Case& c, const dsurf::MultilevelParameters& p, const std::string& label)
{
  dsurf::TriangleMesh mesh = dsphantom::EnclosingBox(c.N, 2);
  dsurf::MultilevelSolver solver;
  solver.SetParameters(p);
  std::string err;
  const auto t0 = Clock::now();
  const bool ok = solver.Run(c.Volume.data(), dsphantom::Geometry(c.N), mesh, &err);
  const auto t1 = Clock::now();
  if (!ok)
  {
    std::printf("| %-12s | %s | failed: %s |\n", c.Name.c_str(), label.c_str(), err.c_str());
    return;
  }
  const auto acc = dsphantom::Measure(mesh, c.Distance);
  double minAngle = 180, below20 = 1.0 - dsphantom::FractionMinAngleAtLeast(mesh, 20.0);
  for (int t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    minAngle = std::min(minAngle, mesh.MinAngleDegrees(t));
  }
  std::string perLevel;
  for (const auto& l : solver.GetLevels())
  {
    perLevel += std::to_string(l.Sweeps) + (l.Converged ? "" : "*") + " ";
  }
  std::printf(
    "| %-12s | %s | %7.3f | %4d (%s) | %zu | %8d | %6.3f | %6.3f | %5.1f | %5.1f%% | %d |\n",
    c.Name.c_str(), label.c_str(), Seconds(t0, t1), solver.GetTotalSweeps(), perLevel.c_str(),
    solver.GetLevels().size(), mesh.NumberOfTriangles(), acc.Mean, acc.Max, minAngle, 100 * below20,
    dsurf::CountSelfIntersections(mesh));
}
} // namespace

int main(int argc, char* argv[])
{
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i)
  {
    sizes.push_back(std::atoi(argv[i]));
  }
  if (sizes.empty())
  {
    sizes = { 128, 256 };
  }
  std::printf("| phantom | method | time s | sweeps (per level, * = cap) | levels | triangles | "
              "mean d | max d | min angle | < 20 deg | self-int |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int n : sizes)
  {
    const double scale = n / 128.0;
    std::vector<Case> cases;
    cases.push_back({ "sphere " + std::to_string(n), n, dsphantom::Sphere(n, 32 * scale),
      [n, scale](const dsurf::Vec3& x) { return dsphantom::SphereDistance(x, n, 32 * scale); } });
    cases.push_back({ "cube " + std::to_string(n), n, dsphantom::Cube(n, 16 * scale),
      [n, scale](const dsurf::Vec3& x) { return dsphantom::CubeDistance(x, n, 16 * scale); } });
    for (const auto& c : cases)
    {
      dsurf::MultilevelParameters p;
      RunDeformable(c, p, "adaptive");
      p.UniformRefinement = true;
      RunDeformable(c, p, "uniform");
      RunFlyingEdges(c);
    }
  }
  return 0;
}
