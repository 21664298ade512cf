#include "dsInitialSigma.h"

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
/// Edge strength -P (in [0, 1]) at x + t n; negative outside the image.
double EdgeStrengthAt(const ForceField& probe, const Vec3& x, const Vec3& n, double t)
{
  const double p[3] = { x[0] + t * n[0], x[1] + t * n[1], x[2] + t * n[2] };
  bool inside = false;
  const double g = -SampleVolume(probe.Potential.data(), probe.Geometry, p, &inside);
  return inside ? g : -1.0;
}

/// Distance along +-n from x to the nearest significant local maximum of the edge strength:
/// 0 when x itself is one (an earlier result used as the start); else the first sample, going
/// either way, that the strength rose to and falls after (a start on the flank of an edge
/// has not reached it yet); `reach` when there is none within it.
double DistanceToEdge(
  const ForceField& probe, const Vec3& x, const Vec3& n, double step, double reach)
{
  const double g0 = EdgeStrengthAt(probe, x, n, 0);
  if (g0 >= EdgeSignificance && g0 >= EdgeStrengthAt(probe, x, n, step) &&
    g0 >= EdgeStrengthAt(probe, x, n, -step))
  {
    return 0.0;
  }
  double best = reach;
  for (double sign : { 1.0, -1.0 })
  {
    double prev2 = g0, prev1 = EdgeStrengthAt(probe, x, n, sign * step);
    for (double t = 2 * step; t <= best + step && prev1 >= 0; t += step)
    {
      const double g = EdgeStrengthAt(probe, x, n, sign * t);
      if (prev1 >= EdgeSignificance && prev1 > prev2 && prev1 >= g)
      {
        best = std::min(best, t - step);
        break;
      }
      prev2 = prev1;
      prev1 = g;
    }
  }
  return best;
}
} // namespace

bool ChooseInitialSigma(const ImageView& image, const TriangleMesh& mesh, double paperSigma,
  int numberOfThreads, InitialSigmaChoice& choice, std::string* error)
{
  const ImageGeometry& geometry = image.Geometry;
  choice = InitialSigmaChoice();
  choice.Sigma = paperSigma;
  if (StartSpansImage(geometry, mesh))
  {
    choice.SpansVolume = true;
    return true;
  }
  const double voxel = geometry.MeanSpacing();
  ScaleSpaceParameters probeParameters;
  probeParameters.Sigma = voxel;
  probeParameters.EdgeNormalization = EdgeNormalization::Local;
  probeParameters.NumberOfThreads = numberOfThreads;
  ForceField probe;
  if (!ComputeScaleSpaceForce(image, probeParameters, probe, error))
  {
    return false;
  }
  probe.Force.clear(); // only the potential is sampled
  probe.Force.shrink_to_fit();

  // Rays from the vertices (area-weighted normals) and the triangle centres (face normals);
  // from every k-th of them on a start of more than MaxRays (a million-triangle iso-surface
  // would cast two million rays, ~10 s, for a 90th percentile that a tenth of them fixes).
  const double reach = 2.0 * paperSigma, step = 0.5 * voxel;
  const std::size_t stride = 1 + (mesh.Points.size() + mesh.Triangles.size()) / MaxRays;
  std::vector<double> distances;
  distances.reserve((mesh.Points.size() + mesh.Triangles.size()) / stride + 2);
  auto cast = [&](const Vec3& x, const Vec3& n)
  {
    const double len = Norm(n);
    if (len > 0)
    {
      distances.push_back(DistanceToEdge(probe, x, (1.0 / len) * n, step, reach));
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
  if (distances.empty())
  {
    return true;
  }
  choice.Rays = static_cast<int>(distances.size());
  choice.RaysWithEdge = static_cast<int>(
    std::count_if(distances.begin(), distances.end(), [reach](double d) { return d < reach; }));
  const std::size_t k = static_cast<std::size_t>(DistanceQuantile * (distances.size() - 1) + 0.5);
  std::nth_element(distances.begin(), distances.begin() + k, distances.end());
  choice.StartDistance = distances[k];
  choice.Sigma = std::min(paperSigma, std::max(voxel, choice.StartDistance));
  return true;
}
} // namespace dsurf
