// SPDX-License-Identifier: BSD-3-Clause
// The region ("balloon") force of the deformable surface: beyond the paper, docs/METHOD.md
// §9. Plain C++, no pipeline types.
//
// A vertex standing where the image lies inside the object's intensity range is pushed out
// along its normal, one standing outside the range is pulled in: Cohen's balloon (CVGIP:IU 53,
// 1991, the paper's reference [3]) with the sign taken from the image as in BET (Smith 2002)
// and ITK-SNAP's thresholding speed image (Yushkevich et al. 2006). The speed is
//   s(I) = clamp(min(I - lo, hi - I) / w, -1, 1),   w = RegionTransition * (hi - lo),
// +1 well inside [lo, hi], -1 well outside, 0 on the range's ends: the surface stops where the
// image crosses lo (or hi). The solver adds RegionWeight * h * min(1, sigma_l / sigma_0) * s * n
// (h the level's mean edge length, n the outward unit normal; the force fades as sigma halves)
// to the edge force before the paper's projection rule, so it cannot fold the surface either.
#ifndef dsRegion_h
#define dsRegion_h

#include "DeformableSurfaceFiltersModule.h" // for export macro
#include "dsPieceField.h"
#include "dsScaleSpace.h"
#include "dsTriangleMesh.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace dsurf
{
/// Transition width of the speed, as a fraction of the range's width.
constexpr double RegionTransition = 0.1;

/// The thresholding speed in [-1, 1] (see above); lo < hi.
inline double RegionSpeed(double intensity, double lo, double hi)
{
  const double w = RegionTransition * (hi - lo);
  const double s = std::min(intensity - lo, hi - intensity) / w;
  return s > 1.0 ? 1.0 : (s < -1.0 ? -1.0 : (s == s ? s : 0.0)); // NaN: no force
}

/// The last level of a click's competition range rests the surface at the local midpoint
/// (docs/METHOD.md §9.3, "A click's last level"): the image is read at these depths, in voxels,
/// inward and outward along the vertex's normal.
constexpr double MidpointDepthsVoxels[3] = { 0.5, 0.75, 1.0 };
/// ... and the midpoint replaces the range's end only where the two sides differ by at least this
/// share of the range's width (an edge, not noise).
constexpr double MidpointContrastShare = 0.2;

/// The region speed at a vertex whose image is `intensity`, `inside` and `outside` the means of
/// the image at MidpointDepthsVoxels inward and outward: where the outside lies beyond one end
/// of [lo, hi] and the inside beyond the same end on the object's side, by at least
/// MidpointContrastShare of the range, a one-sided ramp about the midpoint m of the two sides
/// (the level where the two that meet there are blended half and half): (I - m) / w below
/// (outside < lo), (m - I) / w above, clamped to [-1, 1], w = RegionTransition * |inside -
/// outside|. The range's other end plays no part there: a vertebra's cortex (600 HU) inside a
/// range of [170, 499] and soft tissue (50) outside pushes outward (+1) wherever the image is
/// above the midpoint. Elsewhere `speed`, the speed of the range itself.
inline double MidpointSpeed(
  double intensity, double inside, double outside, double lo, double hi, double speed)
{
  const bool below = (outside < lo);
  const bool above = (outside > hi);
  if (!(below ? inside > lo : (above && inside < hi)) ||
    !(std::abs(inside - outside) >= MidpointContrastShare * (hi - lo)))
  {
    return speed;
  }
  const double mid = 0.5 * (inside + outside);
  const double s =
    (below ? intensity - mid : mid - intensity) / (RegionTransition * std::abs(inside - outside));
  return s > 1.0 ? 1.0 : (s < -1.0 ? -1.0 : (s == s ? s : speed));
}

/// The edge force `force` at a vertex with its component against the unit normal n scaled by
/// 1 - speed, speed the region speed in (0, 1] there: where the image says object, an edge
/// behind the vertex lies inside the object (its far face seen through a click's seed), not
/// where the surface is to stop (a click's first levels, docs/METHOD.md §9.3). A force along n
/// or across it is kept.
inline Vec3 WithoutInwardEdgePull(const Vec3& force, const Vec3& n, double speed)
{
  const double along = Dot(force, n);
  return along < 0 ? force - (speed * along) * n : force;
}

/// A start enclosing fewer voxel centres than this is a click (EstimateIntensityRange): a
/// ball of radius ~6 voxels; a seed sphere around one point (5 mm on 1 mm voxels) holds ~520.
constexpr long long ClickVoxels = 1000;

/// A click given its object's range (IntensityRange, or its row of ObjectIntensityRanges) pulls
/// with at least this RegionWeight (docs/METHOD.md §9.3, "A click given its range"). Its first
/// level's sigma spans the seed's distance to the nearest edges (dsInitialSigma.h), so the edge
/// force pulls the whole seed toward them: at the default weight, meant for a start near its
/// object, it pulled the README's brain click in until it collapsed. A click whose range is
/// estimated keeps RegionWeight: its first levels drop the edge's inward pull where the image
/// says object (WithoutInwardEdgePull), which a given range, whose ends need not be the
/// object's boundaries, cannot (with it the README's click leaked at the default weight).
constexpr double GivenRangeClickWeight = 1.0;

/// Whether a closed start encloses fewer than ClickVoxels voxel centres (a click), counted as
/// EstimatePieceIntensityRange counts them (not counted for a start enclosing more than 8
/// ClickVoxels of volume). Collective, as that is.
DEFORMABLESURFACEFILTERS_EXPORT bool PieceStartIsClick(
  const ImagePiece& piece, const TriangleMesh& mesh, const PieceReductions& reduce);

/// What the estimate saw, for messages and tests.
struct DEFORMABLESURFACEFILTERS_EXPORT RangeEstimate
{
  double Range[2] = { 0, 0 };
  long long Samples = 0;         ///< voxels inside the surface (or vertices, see below)
  long long OutsideSamples = 0;  ///< samples in the shell just outside it
  double Median = 0, Spread = 0; ///< of the inside
  double Separation = 0;         ///< |inside - outside| share of the upper Otsu class
  double ObjectMedian = 0, BackgroundMedian = 0;
  bool FromVertices = false;
  bool Contrast = false; ///< the outside differs: one end of the range is the midpoint
  int Classes = 0; ///< intensity classes around a click (0: not fitted); 2 or more: competitors
};

/// The intensity range of the object the start surface lies on or in. Inside: the voxels
/// whose centres lie inside the closed surface (scan-line parity in index space), their median
/// m and robust spread s = 1.4826 * MAD, floored at 5 % of the image's 1st-99th percentile
/// span; a start enclosing fewer than 16 voxel centres samples the image at its vertices
/// instead. Outside: the image 1, 2 and 3 voxels out along the face normals (outward =
/// `outwardSign` * the triangles' orientation), at about one sample per voxel of the surface.
/// Otsu's threshold of the two samples pooled splits the intensities into two classes; the one
/// more frequent inside than outside is the object's (256-bin histograms). The range runs from
/// the midpoint of the two classes' levels (smoothed histogram modes, the object's from the
/// inside, the background's from the outside) -- on the true edge for any symmetric blur -- to
/// the object's level + 3 s on its side, or to the object's 99.5 % quantile when that is
/// nearer. When the object's class share differs by less than 0.1 between inside and outside,
/// or the levels lie within 2 s of each other, the start lies inside one region (a click), and
/// the range is m -+ 3 s: the whole of that region's class.
/// A click (fewer than ClickVoxels inside) with competitorReach > 0 instead looks for the region's
/// competitors: the classes of intensity within competitorReach of the start (a Gaussian mixture),
/// and the range runs to the decision boundaries between the click's class (or the click's own
/// model, where that class merges its tissue with others) and the classes beside it (region
/// competition, docs/METHOD.md §9.3); the m -+ 3 s range stays when the neighbourhood holds one
/// class.
/// Returns false (with a message) when there is nothing to sample.
DEFORMABLESURFACEFILTERS_EXPORT bool EstimateIntensityRange(const ImageView& image,
  const TriangleMesh& mesh, double outwardSign, RangeEstimate& estimate, std::string* error,
  double competitorReach = 0.0);

/// EstimateIntensityRange of the whole image whose piece this process holds (docs/METHOD.md
/// §9.8): each process samples the inside voxels it counts (ImagePiece::CountedVoxels) and the
/// points whose cell it owns, and the counts, extremes, histograms and quantiles (found digit
/// by digit from summed histograms) are reduced, so every process gets the serial estimate
/// exactly. Collective: every process calls it with the same mesh (its piece checked first,
/// CheckPieces). EstimateIntensityRange is this with the whole image as the one piece.
DEFORMABLESURFACEFILTERS_EXPORT bool EstimatePieceIntensityRange(const ImagePiece& piece,
  const TriangleMesh& mesh, double outwardSign, const PieceReductions& reduce,
  RangeEstimate& estimate, std::string* error, double competitorReach = 0.0);

/// Whether a voxel's value lies in [lo, hi] (a scan that ends at the first).
DEFORMABLESURFACEFILTERS_EXPORT bool AnyVoxelInRange(const ImageView& image, double lo, double hi);

/// Voxels whose value lies in [lo, hi].
DEFORMABLESURFACEFILTERS_EXPORT long long CountVoxelsInRange(
  const ImageView& image, double lo, double hi);
} // namespace dsurf

#endif
