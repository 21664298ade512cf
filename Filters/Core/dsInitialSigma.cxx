// SPDX-License-Identifier: BSD-3-Clause
#include "dsInitialSigma.h"

#include "dsPieceInitialSigma.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace dsurf
{
namespace
{
constexpr double SpanFraction = 0.9;     // bounding-box cover that counts as "spans the image"
constexpr double EdgeSignificance = 0.2; // of the strongest (normalised) edge
constexpr double DistanceQuantile = 0.9;
/// Rays cast at most (about): larger starts cast from every k-th vertex and triangle.
constexpr std::size_t MaxRays = 100000;

/// How far a ray looks each way for an edge: twice the paper's sigma_0.
double RayReach(double paperSigma)
{
  return 2.0 * paperSigma;
}

/// The rays' step: half a voxel.
double RayStep(const ImageGeometry& geometry)
{
  return 0.5 * geometry.MeanSpacing();
}

/// Axis-aligned world bounds of the image (its corner voxel centres, half a voxel out).
void ImageBounds(const ImageGeometry& g, double lo[3], double hi[3])
{
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = std::numeric_limits<double>::max();
    hi[a] = std::numeric_limits<double>::lowest();
  }
  for (int corner = 0; corner < 8; ++corner)
  {
    const double ijk[3] = { (corner & 1) ? g.Dimensions[0] - 0.5 : -0.5,
      (corner & 2) ? g.Dimensions[1] - 0.5 : -0.5, (corner & 4) ? g.Dimensions[2] - 0.5 : -0.5 };
    double x[3];
    g.IndexToWorld(ijk, x);
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], x[a]);
      hi[a] = std::max(hi[a], x[a]);
    }
  }
}

} // namespace

bool StartSpansImage(const ImageGeometry& g, const TriangleMesh& mesh)
{
  double ilo[3], ihi[3];
  ImageBounds(g, ilo, ihi);
  for (int a = 0; a < 3; ++a)
  {
    double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
    for (const Vec3& p : mesh.Points)
    {
      lo = std::min(lo, p[a]);
      hi = std::max(hi, p[a]);
    }
    const double cover = std::min(hi, ihi[a]) - std::max(lo, ilo[a]);
    if (cover < SpanFraction * (ihi[a] - ilo[a]))
    {
      return false;
    }
  }
  return true;
}

namespace
{
/// The point x + t n of a ray.
Vec3 RayPoint(const Vec3& x, const Vec3& n, double t)
{
  return { x[0] + t * n[0], x[1] + t * n[1], x[2] + t * n[2] };
}

/// One ray's walk to the nearest significant local maximum of the edge strength along +-n
/// from x: 0 when x itself is one (an earlier result used as the start); else the first sample,
/// going either way, that the strength rose to and falls after (a start on the flank of an
/// edge has not reached it yet); `reach` when there is none within it. Fed the strengths one
/// by one in the order of the steps (Next), so that all rays can be sampled together.
struct RayWalk
{
  Vec3 X, N;
  double G0 = 0, Best = 0; ///< the strength at x; the distance found so far (reach: none)
  double T = 0;            ///< the next step's distance along Sign * n
  double Prev2 = 0, Prev1 = 0, StartMinus = 0;
  int Sign = 1;
  bool Done = false;

  /// Starts from the strengths at x and one step either way.
  void Begin(double g0, double plus, double minus, double step, double reach)
  {
    this->G0 = g0;
    this->StartMinus = minus;
    this->Best = reach;
    if (g0 >= EdgeSignificance && g0 >= plus && g0 >= minus)
    {
      this->Best = 0.0;
      this->Done = true;
      return;
    }
    this->Direction(1, plus, step);
  }
  /// Walks along sign * n from the first step's strength on (or ends when it cannot go on).
  void Direction(int sign, double first, double step)
  {
    this->Sign = sign;
    this->Prev2 = this->G0;
    this->Prev1 = first;
    this->T = 2 * step;
    this->EndIfOver(step);
  }
  bool CanGoOn(double step) const { return this->T <= this->Best + step && this->Prev1 >= 0; }
  void EndIfOver(double step)
  {
    if (!this->CanGoOn(step))
    {
      this->EndDirection(step);
    }
  }
  void EndDirection(double step)
  {
    if (this->Sign > 0)
    {
      this->Direction(-1, this->StartMinus, step);
    }
    else
    {
      this->Done = true;
    }
  }
  /// The strength at the step T.
  void Next(double g, double step)
  {
    if (this->Prev1 >= EdgeSignificance && this->Prev1 > this->Prev2 && this->Prev1 >= g)
    {
      this->Best = std::min(this->Best, this->T - step);
      this->EndDirection(step);
      return;
    }
    this->Prev2 = this->Prev1;
    this->Prev1 = g;
    this->T += step;
    this->EndIfOver(step);
  }
};

/// The rays: from the vertices (area-weighted normals) and the triangle centres (face
/// normals); from every k-th of them on a start of more than MaxRays (a million-triangle
/// iso-surface would cast two million rays, ~10 s, for a 90th percentile that a tenth of them
/// fixes).
std::vector<RayWalk> CastRays(const TriangleMesh& mesh)
{
  const std::size_t stride = 1 + (mesh.Points.size() + mesh.Triangles.size()) / MaxRays;
  std::vector<RayWalk> rays;
  rays.reserve((mesh.Points.size() + mesh.Triangles.size()) / stride + 2);
  auto cast = [&](const Vec3& x, const Vec3& n)
  {
    const double len = Norm(n);
    if (len > 0)
    {
      RayWalk ray;
      ray.X = x;
      ray.N = (1.0 / len) * n;
      rays.push_back(ray);
    }
  };
  for (std::size_t v = 0; v < mesh.Points.size(); v += stride)
  {
    cast(mesh.Points[v], mesh.AreaWeightedNormal(static_cast<int>(v)));
  }
  for (std::size_t i = 0; i < mesh.Triangles.size(); i += stride)
  {
    const auto& t = mesh.Triangles[i];
    const Vec3 &a = mesh.Points[t[0]], &b = mesh.Points[t[1]], &c = mesh.Points[t[2]];
    cast((1.0 / 3.0) * (a + b + c), Cross(b - a, c - a));
  }
  return rays;
}

/// Walks every ray to its end, `batch` steps of each still walking per call of sample.
void WalkRays(std::vector<RayWalk>& rays, const EdgeStrengthSampler& sample, int batch, double step,
  double reach)
{
  std::vector<Vec3> points;
  std::vector<double> g;
  for (const RayWalk& ray : rays)
  {
    for (double t : { 0.0, step, -step })
    {
      points.push_back(RayPoint(ray.X, ray.N, t));
    }
  }
  sample(points, g);
  for (std::size_t r = 0; r < rays.size(); ++r)
  {
    rays[r].Begin(g[3 * r], g[3 * r + 1], g[3 * r + 2], step, reach);
  }
  for (;;)
  {
    // Each walking ray's next `batch` steps (fewer where its reach ends).
    std::vector<std::pair<std::size_t, int>> asked; // ray, steps asked
    points.clear();
    for (std::size_t r = 0; r < rays.size(); ++r)
    {
      const RayWalk& ray = rays[r];
      int n = 0;
      for (double t = ray.T; !ray.Done && n < batch && t <= ray.Best + step; t += step, ++n)
      {
        points.push_back(RayPoint(ray.X, ray.N, ray.Sign * t));
      }
      if (n > 0)
      {
        asked.emplace_back(r, n);
      }
    }
    if (asked.empty())
    {
      return;
    }
    sample(points, g);
    std::size_t next = 0;
    for (const auto& a : asked)
    {
      RayWalk& ray = rays[a.first];
      const int sign = ray.Sign;
      for (int k = 0; k < a.second; ++k, ++next)
      {
        if (!ray.Done && ray.Sign == sign) // the rest of the batch is past the direction's end
        {
          ray.Next(g[next], step);
        }
      }
    }
  }
}
} // namespace

double InitialSigmaProbeReach(const ImageGeometry& geometry, double paperSigma)
{
  // A ray walks while its next step lies within reach + step (RayWalk::CanGoOn).
  return RayReach(paperSigma) + RayStep(geometry);
}

ScaleSpaceParameters InitialSigmaProbeParameters(const ImageGeometry& geometry, int numberOfThreads)
{
  ScaleSpaceParameters probeParameters;
  probeParameters.Sigma = geometry.MeanSpacing();
  probeParameters.EdgeNormalization = EdgeNormalization::Local;
  probeParameters.NumberOfThreads = numberOfThreads;
  probeParameters.ComputeForce = false; // the rays sample P only
  return probeParameters;
}

void ChooseInitialSigmaWith(const ImageGeometry& geometry, const TriangleMesh& mesh,
  double paperSigma, const EdgeStrengthSampler& sample, int batch, InitialSigmaChoice& choice)
{
  choice = InitialSigmaChoice();
  choice.Sigma = paperSigma;
  if (StartSpansImage(geometry, mesh))
  {
    choice.SpansVolume = true;
    return;
  }
  const double voxel = geometry.MeanSpacing();
  const double reach = RayReach(paperSigma), step = RayStep(geometry);
  std::vector<RayWalk> rays = CastRays(mesh);
  if (rays.empty())
  {
    return;
  }
  WalkRays(rays, sample, std::max(1, batch), step, reach);
  std::vector<double> distances;
  distances.reserve(rays.size());
  for (const RayWalk& ray : rays)
  {
    distances.push_back(ray.Best);
  }
  choice.Rays = static_cast<int>(distances.size());
  choice.RaysWithEdge = static_cast<int>(
    std::count_if(distances.begin(), distances.end(), [reach](double d) { return d < reach; }));
  const std::size_t k = static_cast<std::size_t>(DistanceQuantile * (distances.size() - 1) + 0.5);
  std::nth_element(distances.begin(), distances.begin() + k, distances.end());
  choice.StartDistance = distances[k];
  choice.Sigma = std::min(paperSigma, std::max(voxel, choice.StartDistance));
}

bool ChooseInitialSigma(const ImageView& image, const TriangleMesh& mesh, double paperSigma,
  int numberOfThreads, InitialSigmaChoice& choice, std::string* error)
{
  // The whole image is one piece that owns every cell: the distributed choice on one process.
  return ChoosePieceInitialSigma(WholeImagePiece(image), mesh, paperSigma, numberOfThreads,
    SingleProcessReductions(), choice, error);
}
} // namespace dsurf
