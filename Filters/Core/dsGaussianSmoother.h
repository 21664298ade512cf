// The separable Gaussian G_sigma of the scale space (docs/METHOD.md §2, §6 item 6, §6c):
// plain C++, used by dsScaleSpace.cxx only.
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

namespace dsurf
{
/// Axes with fewer voxels of sigma than this use the sampled Gaussian: exact, and below 3 voxels
/// no dearer than the recursion (at most 13 multiplies per voxel with its symmetry, against 16).
constexpr double GaussianRecursiveFromSigmaVoxels = 3.0;

/// G_sigma * src into dst (dst may equal src; no other aliasing), sigmaVoxels[a] voxels along
/// axis a (below 0.001: that axis is left alone). Volume of dims voxels, x fastest. Its loops
/// run with vtkSMPTools, so the caller's SMP scope sets the threads; the result does not depend
/// on their number.
void SmoothGaussianSeparable(
  const float* src, float* dst, const int dims[3], const double sigmaVoxels[3]);
} // namespace dsurf

#endif
