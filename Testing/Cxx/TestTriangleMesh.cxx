// Topology of the core mesh: closedness, orientation, Euler characteristic,
// non-manifold detection, on shapes whose answers are known.
#include "DSTestHelpers.h"
#include "dsTriangleMesh.h"

using dsurf::TriangleMesh;

static TriangleMesh Octahedron()
{
  TriangleMesh m;
  m.Points = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
  m.Triangles = { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 }, { 2, 0, 5 }, { 1, 2, 5 },
    { 3, 1, 5 }, { 0, 3, 5 } };
  return m;
}

int TestTriangleMesh(int, char*[])
{
  std::string err;
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
