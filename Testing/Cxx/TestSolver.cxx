// SPDX-License-Identifier: BSD-3-Clause
// Unit test of the single-level solver core (dsSolver): colouring, umbrella weights,
// internal forces without an external field (tau = 1 shrinks, tau = 0 keeps a sphere
// round), a hand-made force field, determinism over thread counts, fixed boundaries, and
// sweeps against the docs/METHOD.md §3-4 formulas evaluated directly (label weights on and
// off, open and isolated vertices, several pieces).
#include "DSSurfaceInvariants.h"
#include "TestSolverMeshes.h"

#include "dsRedGreen.h"
#include "dsScaleSpace.h"
#include "dsSolver.h"
#include "dsTriangleMesh.h"

#include <algorithm>
#include <map>
#include <random>
#include <set>

using namespace dsurf;
using dstest::MakeIcosphere;

namespace
{
void RadiusStats(const TriangleMesh& m, const Vec3& c, double& mean, double& minR, double& maxR)
{
  mean = 0;
  minR = 1e300;
  maxR = 0;
  for (const auto& x : m.Points)
  {
    const double r = Norm(x - c);
    mean += r;
    minR = std::min(minR, r);
    maxR = std::max(maxR, r);
  }
  mean /= m.NumberOfPoints();
}

Vec3 Centroid(const TriangleMesh& m)
{
  Vec3 c{ 0, 0, 0 };
  for (const auto& x : m.Points)
  {
    c = c + x;
  }
  return (1.0 / m.NumberOfPoints()) * c;
}

/// A force field on a 64^3 grid pulling every point radially onto the sphere of radius
/// R around the grid centre, F = (R - r) * rhat (in world units; direct test data).
ForceField RadialField(double R)
{
  ForceField field;
  field.Geometry.Dimensions[0] = field.Geometry.Dimensions[1] = field.Geometry.Dimensions[2] = 64;
  field.Sigma = 1;
  const long long n = field.Geometry.NumberOfVoxels();
  field.Potential.assign(n, 0.0f);
  field.Force.assign(3 * n, 0.0f);
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
      {
        const Vec3 d{ i - 31.5, j - 31.5, k - 31.5 };
        const double r = Norm(d);
        const long long idx = i + 64LL * (j + 64LL * k);
        for (int a = 0; a < 3; ++a)
        {
          field.Force[3 * idx + a] = static_cast<float>(r > 0 ? (R - r) * d[a] / r : 0.0);
        }
      }
  return field;
}

/// The normalised weight v gives each slot of its ring (aligned with m.Neighbors), as the
/// solver's Umbrella() reports it: with only that neighbour at (1, 0, 0) and every other point
/// at the origin, U(v) = (w, 0, 0). 1/n each when the label weights are off.
std::vector<double> SlotWeights(const TriangleMesh& m, bool useLabelWeights)
{
  std::vector<double> w(m.Neighbors.size(), 0.0);
  TriangleMesh probe = m;
  std::fill(probe.Points.begin(), probe.Points.end(), Vec3{ 0, 0, 0 });
  Solver s;
  s.SetMesh(&probe);
  for (int v = 0; v < m.NumberOfPoints(); ++v)
  {
    const int begin = m.NeighborOffsets[v], end = m.NeighborOffsets[v + 1];
    for (int i = begin; i < end; ++i)
    {
      Vec3& q = probe.Points[m.Neighbors[i]];
      q = { 1, 0, 0 };
      w[i] = useLabelWeights ? s.Umbrella(v)[0] : 1.0 / (end - begin);
      q = { 0, 0, 0 };
    }
  }
  return w;
}

/// One sweep without external force as docs/METHOD.md §3-4 state it, in the solver's colour
/// order: at each vertex p, U(p) and every U(q_i) from the current points, U^2(p) =
/// sum_i w_i U(q_i) - U(p), alpha = 1 + sum_i w_i w_(q_i)p, p += gamma (tau U - (1 - tau) U^2).
void ReferenceSweep(
  TriangleMesh& m, const std::vector<double>& w, const Solver& s, const SolverParameters& p)
{
  const auto umbrella = [&](int v, int other, double& weightOfOther)
  {
    Vec3 sum{ 0, 0, 0 };
    for (int i = m.NeighborOffsets[v]; i < m.NeighborOffsets[v + 1]; ++i)
    {
      sum = sum + w[i] * m.Points[m.Neighbors[i]];
      weightOfOther = m.Neighbors[i] == other ? w[i] : weightOfOther;
    }
    return sum - m.Points[v];
  };
  for (int k = 0; k < s.ColorOffsets().back(); ++k) // colour after colour
  {
    const int v = s.ColorVertices()[k];
    double unused = 0;
    const Vec3 u = umbrella(v, -1, unused);
    Vec3 u2 = -1.0 * u;
    double alpha = 1.0;
    for (int i = m.NeighborOffsets[v]; i < m.NeighborOffsets[v + 1]; ++i)
    {
      double back = 0;
      u2 = u2 + w[i] * umbrella(m.Neighbors[i], v, back);
      alpha += w[i] * back;
    }
    const Vec3 c2 = (-1.0 / alpha) * u2;
    m.Points[v] = m.Points[v] + p.Gamma * (p.Tau * u + ((1.0 - p.Tau) * alpha) * c2);
  }
}

/// Several pieces with the label weights of red-green refinement: an icosphere and an open cap
/// (the upper half of a second one, whose lower points are left isolated), both refined twice
/// on their x > 31.5 side, every point then moved by up to 0.3 (fixed seed) so that no
/// correction is small.
TriangleMesh RefinedPieces()
{
  TriangleMesh m = MakeIcosphere(2, 20, { 31.5, 31.5, 31.5 });
  const TriangleMesh second = MakeIcosphere(2, 12, { 31.5, 31.5, 70 });
  const int offset = m.NumberOfPoints();
  m.Points.insert(m.Points.end(), second.Points.begin(), second.Points.end());
  for (const auto& t : second.Triangles)
  {
    if (second.Points[t[0]][2] > 70 && second.Points[t[1]][2] > 70 && second.Points[t[2]][2] > 70)
    {
      m.Triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
    }
  }
  RedGreenRefiner rg;
  std::string err;
  DS_CHECK(rg.Initialize(m, &err), err);
  for (int step = 0; step < 2; ++step)
  {
    std::vector<char> marks(m.NumberOfTriangles(), 0);
    for (int t = 0; t < m.NumberOfTriangles(); ++t)
    {
      const auto& tri = m.Triangles[t];
      marks[t] = m.Points[tri[0]][0] + m.Points[tri[1]][0] + m.Points[tri[2]][0] > 3 * 31.5;
    }
    DS_CHECK(rg.Refine(m, marks, Prolongation::Linear).Ok, "refinement of the pieces");
  }
  std::mt19937 random(4711);
  std::uniform_real_distribution<double> offsetOf(-0.3, 0.3);
  for (auto& x : m.Points)
  {
    x = x + Vec3{ offsetOf(random), offsetOf(random), offsetOf(random) };
  }
  return m;
}

/// The worst distance between the solver's points after one Sweep() and the reference's,
/// relative to the largest coordinate (the rounding of p + c alone makes an ulp of it).
double SweepError(TriangleMesh& m, Solver& s, const SolverParameters& p)
{
  TriangleMesh reference = m;
  ReferenceSweep(reference, SlotWeights(m, p.UseLabelWeights), s, p);
  s.SetParameters(p);
  s.Sweep();
  double worst = 0, largest = 0;
  for (int v = 0; v < m.NumberOfPoints(); ++v)
  {
    worst = std::max(worst, Norm(m.Points[v] - reference.Points[v]));
    largest = std::max(largest, Norm(m.Points[v]));
  }
  return worst / largest;
}

/// The solver's sweeps against ReferenceSweep on RefinedPieces(): for 1 and 2 threads, with
/// and without a force exchange (a colour then swept in two phases), the label weights switched
/// off and on again between the sweeps of one solver. Every sweep's points to 1e-14 of the
/// largest coordinate (an umbrella of the wrong weights or left behind by a move is ~1e-3 off,
/// measured 2e-16: the rounding of p + c), and the same points for any number of threads.
void CheckAgainstReference()
{
  const TriangleMesh start = RefinedPieces();
  int labelled = 0, boundary = 0, isolated = 0;
  for (int v = 0; v < start.NumberOfPoints(); ++v)
  {
    labelled += start.Labels[v] != LabelN;
    boundary += start.BoundaryVertex[v] != 0;
    isolated += start.NeighborOffsets[v + 1] == start.NeighborOffsets[v];
  }
  std::cout << "reference sweeps: " << start.NumberOfPoints() << " points, " << labelled
            << " labelled, " << boundary << " on the boundary, " << isolated << " isolated"
            << std::endl;
  DS_CHECK(labelled > 100 && boundary > 10 && isolated > 10, "pieces with every kind of vertex");
  std::vector<Vec3> firstResult;
  for (const bool exchange : { false, true })
  {
    for (const int threads : { 1, 2 })
    {
      TriangleMesh m = start;
      Solver s;
      s.SetMesh(&m);
      if (exchange)
      {
        s.SetForceExchange([](VertexForce*, int) {});
      }
      SolverParameters p;
      p.NumberOfThreads = threads;
      double worst = 0;
      for (const bool labels : { true, false, true })
      {
        p.UseLabelWeights = labels;
        worst = std::max(worst, SweepError(m, s, p));
      }
      const std::string label =
        std::to_string(threads) + " thread(s)" + (exchange ? " and a force exchange" : "");
      DS_CHECK_LE(worst, 1e-14, label + ": distance to the reference sweep / largest coordinate");
      firstResult = firstResult.empty() ? m.Points : firstResult;
      DS_CHECK(m.Points == firstResult, label + ": the same points as 1 thread");
    }
  }
}
} // namespace

int TestSolver(int, char*[])
{
  const Vec3 centre{ 31.5, 31.5, 31.5 };

  // --- distance-2 colouring ---
  {
    TriangleMesh m = MakeIcosphere(3, 10, centre);
    std::string err;
    DS_CHECK(m.BuildTopology(&err), err);
    Solver s;
    s.SetMesh(&m);
    std::vector<int> color(m.NumberOfPoints(), -1);
    int assigned = 0;
    for (int c = 0; c < s.NumberOfColors(); ++c)
    {
      for (int k = s.ColorOffsets()[c]; k < s.ColorOffsets()[c + 1]; ++k)
      {
        color[s.ColorVertices()[k]] = c;
        ++assigned;
      }
    }
    int conflicts = 0;
    for (int v = 0; v < m.NumberOfPoints(); ++v)
    {
      std::set<int> ring2;
      for (int i = m.NeighborOffsets[v]; i < m.NeighborOffsets[v + 1]; ++i)
      {
        const int q = m.Neighbors[i];
        ring2.insert(q);
        for (int j = m.NeighborOffsets[q]; j < m.NeighborOffsets[q + 1]; ++j)
        {
          ring2.insert(m.Neighbors[j]);
        }
      }
      ring2.erase(v);
      for (int u : ring2)
      {
        conflicts += color[u] == color[v];
      }
    }
    std::cout << "colouring: " << s.NumberOfColors() << " colours for " << m.NumberOfPoints()
              << " vertices" << std::endl;
    DS_CHECK(assigned == m.NumberOfPoints(), "every vertex of a closed mesh is coloured once");
    DS_CHECK_LE(conflicts, 0, "distance-2 colour conflicts");
    DS_CHECK_LE(s.NumberOfColors(), 24, "number of colours");
  }

  // --- weighted umbrella (docs/METHOD.md §6.4): a C vertex gives N/C/M neighbours weight 2, D
  // weight 1 ---
  {
    TriangleMesh m;
    // A fan: centre 0 and a hexagon 1..6 in the plane z = 0, plus one lifted vertex.
    m.Points.push_back({ 0, 0, 0 });
    for (int i = 0; i < 6; ++i)
    {
      const double a = i * 3.14159265358979323846 / 3;
      m.Points.push_back({ std::cos(a), std::sin(a), i == 0 ? 1.0 : 0.0 });
    }
    for (int i = 0; i < 6; ++i)
    {
      m.Triangles.push_back({ 0, 1 + i, 1 + (i + 1) % 6 });
    }
    std::string err;
    DS_CHECK(m.BuildTopology(&err), err);
    m.Labels[0] = LabelC;
    m.Labels[1] = LabelD; // the lifted vertex gets weight 1, the others 2
    Solver s;
    s.SetMesh(&m);
    const Vec3 u = s.Umbrella(0);
    // W = 1 + 5 * 2 = 11; z component = 1 * 1 / 11.
    DS_CHECK_LE(
      std::abs(u[2] - 1.0 / 11.0), 1e-12, "|U_z - 1/11| for a C vertex with one D neighbour");
    m.Labels[0] = LabelN;
    s.SetMesh(&m);
    DS_CHECK_LE(std::abs(s.Umbrella(0)[2] - 1.0 / 6.0), 1e-12, "|U_z - 1/6| for an N vertex");
    // An M vertex whose neighbours are all M gives them weight 0: uniform fallback.
    for (auto& l : m.Labels)
    {
      l = LabelM;
    }
    s.SetMesh(&m);
    DS_CHECK_LE(
      std::abs(s.Umbrella(0)[2] - 1.0 / 6.0), 1e-12, "|U_z - 1/6| for the uniform fallback");
  }

  // --- tau = 1 (membrane), no external force: the sphere shrinks monotonically ---
  {
    TriangleMesh m = MakeIcosphere(3, 20, centre);
    std::string err;
    m.BuildTopology(&err);
    Solver s;
    SolverParameters p;
    p.Tau = 1.0;
    s.SetParameters(p);
    s.SetMesh(&m);
    double mean, minR, maxR;
    RadiusStats(m, Centroid(m), mean, minR, maxR);
    const double r0 = mean;
    int increases = 0;
    double prev = mean;
    for (int i = 0; i < 200; ++i)
    {
      s.Sweep();
      RadiusStats(m, Centroid(m), mean, minR, maxR);
      increases += mean >= prev;
      prev = mean;
    }
    std::cout << "tau=1: mean radius " << r0 << " -> " << mean << std::endl;
    dstest::CheckSurfaceInvariants(MakeIcosphere(3, 20, centre), m, "tau=1 after 200 sweeps");
    DS_CHECK_LE(increases, 0, "sweeps where the mean radius did not shrink (tau = 1)");
    DS_CHECK_LE(mean, 0.9 * r0, "mean radius after 200 membrane sweeps");
  }

  // --- tau = 0 (thin plate), no external force: the sphere stays round ---
  {
    TriangleMesh m = MakeIcosphere(4, 20, centre);
    std::string err;
    m.BuildTopology(&err);
    Solver s;
    SolverParameters p;
    p.Tau = 0.0;
    s.SetParameters(p);
    s.SetMesh(&m);
    double worstSpread = 0, mean = 0, minR, maxR;
    for (int i = 0; i < 500; ++i)
    {
      s.Sweep();
      RadiusStats(m, Centroid(m), mean, minR, maxR);
      worstSpread = std::max(worstSpread, (maxR - minR) / mean);
    }
    std::cout << "tau=0: mean radius after 500 sweeps " << mean << std::endl;
    dstest::CheckSurfaceInvariants(MakeIcosphere(4, 20, centre), m, "tau=0 after 500 sweeps");
    DS_CHECK_LE(worstSpread, 0.01, "worst (max r - min r) / mean r over 500 thin-plate sweeps");
    DS_CHECK_GE(mean, 19.0, "mean radius after 500 thin-plate sweeps");
  }

  // --- a hand-made radial force field pulls a sphere of radius 25 onto radius 20 ---
  const ForceField field = RadialField(20.0);
  {
    TriangleMesh m = MakeIcosphere(3, 25, centre);
    std::string err;
    m.BuildTopology(&err);
    Solver s;
    s.SetMesh(&m);
    s.SetForceField(&field, 1.0);
    SweepStatistics st;
    int sweeps = 0;
    for (; sweeps < 2000; ++sweeps)
    {
      st = s.Sweep();
      if (st.MeanCorrection < 1e-6)
      {
        break;
      }
    }
    double mean, minR, maxR;
    RadiusStats(m, centre, mean, minR, maxR);
    std::cout << "radial field: " << sweeps << " sweeps, r in [" << minR << ", " << maxR << "]"
              << std::endl;
    // The internal forces pull inward by about tau * h^2 / (2 r) per unit force; small.
    DS_CHECK_LE(std::abs(mean - 20.0), 0.2, "|mean radius - 20| under the radial field");
    DS_CHECK_LE(maxR - minR, 0.05, "radius spread under the radial field");
    DS_CHECK(st.OutsideVertices == 0, "no vertex outside the field");
    double maxErr = 0;
    for (double e : s.ErrorIndicator())
    {
      maxErr = std::max(maxErr, e);
    }
    DS_CHECK_GE(maxErr, 1e-6, "error indicator (internal correction) at rest is non-zero");
  }

  // --- determinism: 1 and 2 threads give bit-identical points ---
  {
    TriangleMesh a = MakeIcosphere(4, 26, centre), b;
    for (auto& x : a.Points)
    {
      x[0] += 0.3 * std::sin(x[1]); // break the symmetry
    }
    b = a;
    std::string err;
    a.BuildTopology(&err);
    b.BuildTopology(&err);
    Solver sa, sb;
    SolverParameters pa, pb;
    pa.NumberOfThreads = 1;
    pb.NumberOfThreads = 2;
    sa.SetParameters(pa);
    sb.SetParameters(pb);
    sa.SetMesh(&a);
    sb.SetMesh(&b);
    sa.SetForceField(&field, 1.0);
    sb.SetForceField(&field, 1.0);
    double meanA = 0, meanB = 0;
    for (int i = 0; i < 30; ++i)
    {
      meanA = sa.Sweep().MeanCorrection;
      meanB = sb.Sweep().MeanCorrection;
    }
    int differing = 0;
    for (int v = 0; v < a.NumberOfPoints(); ++v)
    {
      differing += a.Points[v] != b.Points[v];
    }
    DS_CHECK_LE(differing, 0, "points differing between 1 and 2 threads");
    DS_CHECK(meanA == meanB, "mean correction identical for 1 and 2 threads");

    // Sweeps(): the batched form (one parallel region) gives the same points and
    // statistics as single sweeps, and stops when the callback says so.
    for (int threads : { 1, 2 })
    {
      TriangleMesh c = b;
      Solver sc;
      SolverParameters pc;
      pc.NumberOfThreads = threads;
      sc.SetParameters(pc);
      sc.SetMesh(&c);
      sc.SetForceField(&field, 1.0);
      std::vector<double> means;
      const int done = sc.Sweeps(100,
        [&](const SweepStatistics& st)
        {
          means.push_back(st.MeanCorrection);
          return means.size() < 7;
        });
      for (int i = 0; i < 7; ++i)
      {
        sb.Sweep();
      }
      // 30 + 7 sweeps on b against 30 + 7 on c (c started from b after 30).
      const double meanLast = sb.Sweep().MeanCorrection;
      const int done2 = sc.Sweeps(1,
        [&](const SweepStatistics& st)
        {
          means.push_back(st.MeanCorrection);
          return true;
        });
      int differ = 0;
      for (int v = 0; v < b.NumberOfPoints(); ++v)
      {
        differ += b.Points[v] != c.Points[v];
      }
      const std::string label = "Sweeps() with " + std::to_string(threads) + " thread(s)";
      DS_CHECK(done == 7 && done2 == 1 && means.size() == 8,
        label + ": stops when the callback returns false");
      DS_CHECK_LE(differ, 0, label + ": points differing from single sweeps");
      DS_CHECK(means.back() == meanLast, label + ": statistics identical to single sweeps");
      b = c; // continue the comparison from the same state
      sb.SetMesh(&b);
    }
  }

  // --- open surface: boundary vertices stay fixed ---
  {
    TriangleMesh sphere = MakeIcosphere(3, 20, centre);
    TriangleMesh m;
    m.Points = sphere.Points;
    for (const auto& t : sphere.Triangles)
    {
      if (sphere.Points[t[0]][2] > centre[2] && sphere.Points[t[1]][2] > centre[2] &&
        sphere.Points[t[2]][2] > centre[2])
      {
        m.Triangles.push_back(t);
      }
    }
    std::string err;
    DS_CHECK(m.BuildTopology(&err), err);
    DS_CHECK(!m.IsClosed(), "the cap is open");
    const std::vector<Vec3> before = m.Points;
    Solver s;
    SolverParameters p;
    p.Tau = 1.0;
    s.SetParameters(p);
    s.SetMesh(&m);
    for (int i = 0; i < 50; ++i)
    {
      s.Sweep();
    }
    int boundaryMoved = 0, interiorMoved = 0, boundary = 0;
    for (int v = 0; v < m.NumberOfPoints(); ++v)
    {
      const bool moved = m.Points[v] != before[v];
      if (m.BoundaryVertex[v])
      {
        ++boundary;
        boundaryMoved += moved;
      }
      else if (m.NeighborOffsets[v + 1] > m.NeighborOffsets[v])
      {
        interiorMoved += moved;
      }
    }
    std::cout << "open cap: " << boundary << " boundary vertices" << std::endl;
    DS_CHECK_GE(boundary, 10, "boundary vertices of the cap");
    DS_CHECK_LE(boundaryMoved, 0, "boundary vertices that moved");
    DS_CHECK_GE(interiorMoved, 10, "interior vertices that moved");
  }

  // --- the kept umbrellas give the corrections of docs/METHOD.md §3-4 in every weight mode ---
  CheckAgainstReference();

  return dstest::Result("TestSolver");
}

int main(int argc, char* argv[])
{
  return TestSolver(argc, argv);
}
