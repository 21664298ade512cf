// SPDX-License-Identifier: BSD-3-Clause
// The separable Gaussian G_sigma of the scale space (docs/METHOD.md §2, §6 item 6, §6c):
// plain C++, used by the scale space (dsScaleSpace.cxx, dsLocalPotential.cxx) and its slabs and
// pieces (dsSmoothSlabs.cxx, dsPieceGaussian.cxx and their kin).
//
// Along each axis, with s = sigma in voxels of that axis:
//   s < 3:   the sampled Gaussian exp(-k^2 / 2 s^2), |k| <= ceil(4 s), normalised to unit sum
//            (for s < ~0.8 its width is raised slightly so the taps keep the variance s^2,
//            which sampling a narrow Gaussian loses).
//   s >= 3:  a recursive filter, forward then backward, constant cost per voxel whatever s:
//            the 5th-order poles of van Vliet, Young & Verbeek (1998, Table 1, L2-optimised
//            smoothing filter) scaled as d^(1/q), q solved so the impulse response has the
//            variance s^2, run as a cascade of three sections; replicated border through the
//            Triggs & Sdika (2006) start of the backward pass, so a constant stays constant
//            and the border does not ring. More than 1e5 voxels of sigma is refused
//            (dsScaleSpace.cxx Validate).
// The choice and its measured accuracy are in docs/METHOD.md §6c.
#ifndef dsGaussianSmoother_h
#define dsGaussianSmoother_h

#include <memory>
#include <vector>

namespace dsurf
{
/// Axes with fewer voxels of sigma than this use the sampled Gaussian: exact, and below 3 voxels
/// no dearer than the recursion (at most 13 multiplies per voxel with its symmetry, against 16).
constexpr double GaussianRecursiveFromSigmaVoxels = 3.0;

/// G_sigma * src into dst (dst may equal src; no other aliasing), sigmaVoxels[a] voxels along
/// axis a (below 0.001: that axis is left alone), along z first, then x, then y (every path
/// that must equal it bit for bit passes in that order). Volume of dims voxels, x fastest. Its
/// loops run with vtkSMPTools, so the caller's SMP scope sets the threads; the result does not
/// depend on their number.
void SmoothGaussianSeparable(
  const float* src, float* dst, const int dims[3], const double sigmaVoxels[3]);

/// Voxels on either side that the pass along an axis of sigmaVoxels reads for one output: the
/// sampled Gaussian's radius, 0 when the axis is left alone, -1 for the recursive filter (the
/// whole line).
int GaussianAxisReach(double sigmaVoxels);

/// The sampled Gaussian's pass along z (sigmaVoxels below GaussianRecursiveFromSigmaVoxels)
/// of a volume of dims voxels, out of place and only at slices [k0, k1): dst holds those slices,
/// each bit for bit SmoothGaussianAxis's there (the same sums in the same order).
void SampledAxisZ(
  const float* src, float* dst, const int dims[3], double sigmaVoxels, int k0, int k1);

/// The pass of SmoothGaussianSeparable along axis a alone, in place (the same code).
void SmoothGaussianAxis(float* volume, const int dims[3], int a, double sigmaVoxels);

/// The recursive pass along one axis of a volume whose lines go on in other processes' pieces
/// (docs/METHOD.md §9.8): the forward recursion starts from the state the previous piece ended
/// with, the backward one from the next piece's, and the states at chosen positions are
/// recorded for the pieces that go on from there. The arithmetic is SmoothGaussianSeparable's,
/// so the pieces' lines equal the whole lines bit for bit. A line's state is States doubles;
/// the lines are the voxels of the other two axes, the lower one fastest.
class RecursiveAxisPass
{
public:
  static constexpr int States = 5;
  /// sigmaVoxels at least GaussianRecursiveFromSigmaVoxels; `volume` (dims voxels) is filtered
  /// in place by Forward then Backward.
  RecursiveAxisPass(float* volume, const int dims[3], int axis, double sigmaVoxels);
  ~RecursiveAxisPass();
  long long Lines() const { return this->NumberOfLines; }

  /// The forward recursion over every line, from `start` (States per line: the state after the
  /// position before this volume's first) or, when null, the replicated first sample as the
  /// serial filter starts at the image's end. After the position record[r] (along the axis) each
  /// line's state is stored in recorded[r].
  void Forward(const double* start, const std::vector<int>& record,
    std::vector<std::vector<double>>& recorded);
  /// Then the backward recursion, from `ahead` (States per line: the backward state after the
  /// position past this volume's last) or, when null, the replicated last sample (Triggs &
  /// Sdika, as the serial filter); records likewise.
  void Backward(const double* ahead, const std::vector<int>& record,
    std::vector<std::vector<double>>& recorded);

private:
  struct Filter;
  std::unique_ptr<Filter> Coefficients;
  float* Volume;
  int Dims[3];
  int Axis;
  long long NumberOfLines;
  /// Axis 0: the forward start of each line (its outputs are recomputed before the backward
  /// pass, which reads them as doubles). Axes 1 and 2: the forward end state and the last input.
  std::vector<double> Saved;
};
} // namespace dsurf

#endif
