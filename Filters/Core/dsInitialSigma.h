// SPDX-License-Identifier: BSD-3-Clause
// The first sigma of the hierarchy, chosen from the start surface (beyond the paper:
// docs/METHOD.md §9). Plain C++, no pipeline types.
//
// The paper starts at sigma_0 = 1/6 of the volume's mean extent (§6.6): a Gaussian edge
// attracts from ~2 sigma, so a surface enclosing the whole volume (its cube test) is pulled in
// from far away. A start that already lies near its object (a Delaunay seed of picked points,
// a user's mesh, an earlier result) would be blurred into its neighbours by that sigma and end
// farther away than it began. So:
//   - a start that spans the image (its bounding box covers at least 90 % of the image's along
//     every axis: a box around the whole volume) keeps the paper's sigma_0;
//   - any other start is near its object: along the unit normal of every vertex and triangle
//     centre (every k-th on a start of more than 100 000 of them), inward and outward up to 2 * the
//     paper's sigma_0, the nearest local maximum of the edge strength (at a probe sigma of 1 voxel,
//     locally normalised, at least 0.2 of the strongest within that reach of the start: one
//     click in a head probes its own neighbourhood, not the whole image) is found; D is the 90th
//     percentile of those distances (2 * the paper's sigma_0 where no edge was met), and
//     sigma_0 = D, between one voxel and the paper's sigma_0.
// sigma_0 = D leaves a factor of two to the basin (~2 sigma): the nearest edge is not always the
// object's (the skull's lies as near to a seed around a brain as the brain's own).
#ifndef dsInitialSigma_h
#define dsInitialSigma_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsScaleSpace.h"
#include "dsTriangleMesh.h"

#include <functional>
#include <string>
#include <vector>

namespace dsurf
{
struct DEFORMABLESURFACEFILTERS_EXPORT InitialSigmaChoice
{
  double Sigma = 0;         ///< the chosen sigma_0 (world units)
  bool SpansVolume = false; ///< the start spans the image: the paper's sigma_0
  double StartDistance = 0; ///< D, the 90th percentile distance to the nearest edge
  int Rays = 0;             ///< rays cast (0 when the start spans the volume)
  int RaysWithEdge = 0;     ///< rays that met an edge within reach
  int ProbeBlock = 1;       ///< the probe's block size (> 1: the coarse probe's choice was kept)
};

/// True when the start's bounding box covers at least 90 % of the image's along every axis
/// (a box around the whole volume).
DEFORMABLESURFACEFILTERS_EXPORT bool StartSpansImage(
  const ImageGeometry& geometry, const TriangleMesh& mesh);

/// How far from the start (world units) a ray's samples reach: 2 * paperSigma and one step. The
/// probe field's two maxima are taken over the voxels within it of the start's bounding box
/// (SurfaceNeighbourhood, in index space), and the field is computed there and in its ghosts
/// only, so what lies farther from the start does not change sigma_0.
DEFORMABLESURFACEFILTERS_EXPORT double InitialSigmaProbeReach(
  const ImageGeometry& geometry, double paperSigma);

/// The probe field's parameters: sigma one voxel (the mean spacing), locally normalised.
DEFORMABLESURFACEFILTERS_EXPORT ScaleSpaceParameters InitialSigmaProbeParameters(
  const ImageGeometry& geometry, int numberOfThreads);

/// The probe's edge strength -P at world points: strengths[i] for points[i], -1 outside the
/// image. Serial, sampled from the probe field within the rays' reach (InitialSigmaProbeReach;
/// every sample lies there); on a distributed image each process samples the points in its
/// piece and one sum gives every process all of them (ChoosePieceInitialSigma,
/// dsPieceInitialSigma.h).
using EdgeStrengthSampler =
  std::function<void(const std::vector<Vec3>& points, std::vector<double>& strengths)>;

/// Chooses sigma_0 for `mesh` (topology built) as described above; paperSigma is the paper's
/// extent / 6 (or the fraction the caller uses). False with a message when the probe field
/// cannot be computed.
DEFORMABLESURFACEFILTERS_EXPORT bool ChooseInitialSigma(const ImageView& image,
  const TriangleMesh& mesh, double paperSigma, int numberOfThreads, InitialSigmaChoice& choice,
  std::string* error);

/// The rays of ChooseInitialSigma walked with the strengths `sample` gives, all rays together,
/// `batch` steps of each at a time (one call of sample per round, the same number of rounds
/// on every process of a distributed image: the walk depends only on the strengths). The
/// choice depends only on the strengths, not on the batch. sample is not called for a start
/// that spans the image.
DEFORMABLESURFACEFILTERS_EXPORT void ChooseInitialSigmaWith(const ImageGeometry& geometry,
  const TriangleMesh& mesh, double paperSigma, const EdgeStrengthSampler& sample, int batch,
  InitialSigmaChoice& choice);
} // namespace dsurf

#endif
