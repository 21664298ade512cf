// SPDX-License-Identifier: BSD-3-Clause
// Topology of the core mesh: closedness, orientation, Euler characteristic,
// non-manifold detection, and the uniform 1 -> 4 subdivision (also the seed surface's), on
// shapes whose answers are known.
#include "DSTestHelpers.h"
#include "dsSeedSurface.h"
#include "dsTriangleMesh.h"

#include <algorithm>

using dsurf::TriangleMesh;
using dsurf::operator+; // Vec3 is a std::array: its arithmetic is not found by lookup
using dsurf::operator*;

static TriangleMesh Octahedron()
{
  TriangleMesh m;
  m.Points = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
  m.Triangles = { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 }, { 2, 0, 5 }, { 1, 2, 5 },
    { 3, 1, 5 }, { 0, 3, 5 } };
  return m;
}

/// SubdivideUniformly on the octahedron: counts, invariants, shape, numbering, labels; and
/// its failures (an invalid mesh; a folded "pillow" whose split is not a manifold).
static void CheckSubdivideUniformly()
{
  std::string err;
  const TriangleMesh before = []
  {
    TriangleMesh m = Octahedron();
    m.BuildTopology(nullptr);
    return m;
  }();
  TriangleMesh m = Octahedron(); // no topology yet: the split builds it
  m.Labels.assign(6, dsurf::LabelC);
  m.Levels.assign(6, 3);
  DS_CHECK(m.SubdivideUniformly(&err), err);
  DS_CHECK(m.NumberOfPoints() == 18 && m.NumberOfTriangles() == 32 && m.Edges.size() == 48,
    "6 + 12 points, 4 x 8 triangles, 48 edges");
  DS_CHECK(m.IsClosed() && m.IsConsistentlyOriented() && m.EulerCharacteristic() == 2 &&
      m.CountNonManifoldVertices() == 0,
    "closed, oriented, Euler 2, no pinched vertex after the split");
  DS_CHECK_LE(std::abs(m.SignedVolume() - 4.0 / 3.0), 1e-12, "|volume - 4/3| after the split");
  DS_CHECK_LE(std::abs(m.MeanEdgeLength() - 0.5 * before.MeanEdgeLength()), 1e-14,
    "|mean edge - half the octahedron's|");
  bool midpoints = true, children = true;
  for (int e = 0; e < 12; ++e)
  {
    const auto& ends = before.Edges[e];
    midpoints =
      midpoints && m.Points[6 + e] == 0.5 * (before.Points[ends[0]] + before.Points[ends[1]]);
  }
  for (int t = 0; t < 8; ++t)
  {
    const auto& corners = before.Triangles[t];
    const auto& middle = m.Triangles[4 * t + 3];
    children = children && m.Triangles[4 * t][0] == corners[0] &&
      m.Triangles[4 * t + 1][1] == corners[1] && m.Triangles[4 * t + 2][2] == corners[2] &&
      *std::min_element(middle.begin(), middle.end()) >= 6;
  }
  bool found = true;
  for (int e = 0; e < 48; ++e)
  {
    found = found && m.FindEdge(m.Edges[e][1], m.Edges[e][0]) == e;
  }
  DS_CHECK(found && m.FindEdge(0, 1) < 0 && m.FindEdge(-1, 0) < 0 && m.FindEdge(0, 18) < 0,
    "FindEdge finds each of the 48 edges in either order, no other pair");
  DS_CHECK(midpoints, "point 6 + e is the midpoint of edge e");
  DS_CHECK(children, "triangle t's corner children are 4t .. 4t+2, its middle one 4t+3");
  DS_CHECK(std::count(m.Labels.begin(), m.Labels.end(), dsurf::LabelN) == 18 &&
      std::count(m.Levels.begin(), m.Levels.end(), 0) == 18,
    "every point labelled N, level 0");

  TriangleMesh bad = Octahedron();
  bad.Triangles[0][0] = 6;
  DS_CHECK(!bad.SubdivideUniformly(&err) && err.find("out of range") != std::string::npos, err);
  DS_CHECK(bad.NumberOfPoints() == 6 && bad.NumberOfTriangles() == 8, "an invalid mesh unchanged");
  TriangleMesh pillow;
  pillow.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
  pillow.Triangles = { { 0, 1, 2 }, { 0, 2, 1 } };
  DS_CHECK(!pillow.SubdivideUniformly(&err) && err.find("non-manifold") != std::string::npos,
    "a pillow's split puts four triangles on an edge: " + err);
}

/// The seed surface is a TriangleMesh and is subdivided by the same split: a tetrahedron
/// (mean edge (3 + 3 sqrt 2) / 6 = 1.207) with target 0.3 takes two steps (0.604, then
/// 0.302 <= sqrt 2 x 0.3), the midpoints have no source point, a budget stops it early.
static void CheckSubdivideSeedSurface()
{
  const std::vector<dsurf::Vec3> p = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  std::vector<unsigned char> status;
  dsurf::SeedBoundaryReport report;
  const dsurf::SeedSurface tet =
    dsurf::ExtractSeedBoundary(p, { { 0, 1, 2, 3 } }, status, 0, report);
  dsurf::SeedSurface s = tet;
  DS_CHECK(dsurf::SubdivideSeedSurface(s, 0.3) == 2, "two steps to the target");
  DS_CHECK(s.NumberOfPoints() == 34 && s.NumberOfTriangles() == 64, "34 points, 64 triangles");
  DS_CHECK(
    s.SourcePoint.size() == 34 && std::count(s.SourcePoint.begin(), s.SourcePoint.end(), -1) == 30,
    "the 30 midpoints have SourcePoint -1");
  DS_CHECK(s.IsClosed() && s.IsConsistentlyOriented() && s.SignedVolume() > 0,
    "closed and outward after subdivision");
  TriangleMesh same = tet;
  same.SubdivideUniformly(nullptr);
  same.SubdivideUniformly(nullptr);
  DS_CHECK(same.Points == s.Points && same.Triangles == s.Triangles,
    "the seed's subdivision is TriangleMesh::SubdivideUniformly");
  dsurf::SeedSurface capped = tet;
  DS_CHECK(dsurf::SubdivideSeedSurface(capped, 0.3, 16) == 1, "a 16-triangle budget: one step");
  DS_CHECK(dsurf::SubdivideSeedSurface(capped, 0.0) == 0, "target 0: no step");
}

int TestTriangleMesh(int, char*[])
{
  std::string err;
  CheckSubdivideUniformly();
  CheckSubdivideSeedSurface();
  {
    TriangleMesh m = Octahedron();
    DS_CHECK(m.BuildTopology(&err), err);
    DS_CHECK(m.IsClosed(), "octahedron is closed");
    DS_CHECK(m.IsConsistentlyOriented(), "octahedron is consistently oriented");
    DS_CHECK(m.EulerCharacteristic() == 2, "Euler characteristic of a sphere is 2");
    DS_CHECK(m.Edges.size() == 12, "12 edges");
    DS_CHECK(m.CountNonManifoldVertices() == 0, "no pinched vertex");
    DS_CHECK_LE(std::abs(m.SignedVolume() - 4.0 / 3.0), 1e-12, "|volume - 4/3|");
    DS_CHECK(m.NeighborOffsets[1] - m.NeighborOffsets[0] == 4, "valence 4");
    DS_CHECK(m.FindEdge(4, 0) >= 0 && m.FindEdge(0, 1) < 0, "edge lookup");
    DS_CHECK_GE(m.MinAngleDegrees(0), 59.999, "min angle of an equilateral face");
  }
  {
    TriangleMesh m = Octahedron();
    std::swap(m.Triangles[0][1], m.Triangles[0][2]); // flip one face
    DS_CHECK(m.BuildTopology(&err), err);
    DS_CHECK(!m.IsConsistentlyOriented(), "a flipped face is detected");
    DS_CHECK(m.OrientConsistently() == 1, "one triangle flipped back (the majority wins)");
    DS_CHECK(m.IsConsistentlyOriented(), "consistent after OrientConsistently");
    DS_CHECK_LE(std::abs(m.SignedVolume() - 4.0 / 3.0), 1e-12, "|volume - 4/3| after re-orienting");
  }
  {
    // Five of eight faces flipped: the majority is now inward, and it is kept.
    TriangleMesh m = Octahedron();
    for (int t : { 0, 1, 2, 3, 4 })
    {
      std::swap(m.Triangles[t][1], m.Triangles[t][2]);
    }
    DS_CHECK(m.BuildTopology(&err), err);
    DS_CHECK(m.OrientConsistently() == 3, "the three minority faces flipped");
    DS_CHECK(
      m.IsConsistentlyOriented() && m.SignedVolume() < 0, "consistent, inward like the majority");
  }
  {
    TriangleMesh m = Octahedron();
    m.Triangles.push_back({ 0, 2, 1 }); // edge (0,2) now has three triangles
    DS_CHECK(!m.BuildTopology(&err), "non-manifold edge is an error");
    DS_CHECK(err.find("non-manifold") != std::string::npos, err);
  }
  {
    TriangleMesh m = Octahedron();
    m.Triangles.pop_back();
    DS_CHECK(m.BuildTopology(&err), err);
    DS_CHECK(!m.IsClosed(), "a removed face opens the surface");
    int boundary = 0;
    for (auto b : m.BoundaryVertex)
    {
      boundary += b;
    }
    DS_CHECK(boundary == 3, "three boundary vertices around the hole");
  }
  {
    // Two tetrahedra sharing one vertex: manifold edges, one pinched vertex.
    TriangleMesh m;
    m.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { -1, 0, 0 }, { 0, -1, 0 },
      { 0, 0, -1 } };
    m.Triangles = { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 }, { 0, 4, 5 }, { 0, 6, 4 },
      { 0, 5, 6 }, { 4, 6, 5 } };
    DS_CHECK(m.BuildTopology(&err), err);
    DS_CHECK(m.CountNonManifoldVertices() == 1, "one pinched vertex");
  }
  return dstest::Result("TestTriangleMesh");
}

int main(int argc, char* argv[])
{
  return TestTriangleMesh(argc, argv);
}
