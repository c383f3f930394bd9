// The frame that centres points and scales them to unit size: the centre of their bounding
// box and half its longest side. The mesh index works in it (lengths, areas and Newton on
// numbers near 1 whatever the mesh's units) and so do the distortion measures (areas of a
// mesh or a layout at 1e-300 or 1e+300 neither underflow nor overflow).

#ifndef ICM_INTERNAL_UNIT_FRAME_H
#define ICM_INTERNAL_UNIT_FRAME_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace ICM {
namespace internal {

/// A point p is (p - center) / scale in the frame.
template <std::size_t N>
struct Unit_frame
{
  std::array<double, N> center{};
  double scale = 1;

  /// The frame of a bounding box: its centre, and half its longest side as the unit (1 if
  /// the box is a point). Halves are taken before differences, so a box that spans the
  /// whole range of doubles does not overflow.
  static Unit_frame of_box(const std::array<double, N>& low, const std::array<double, N>& high)
  {
    Unit_frame frame;
    double half = 0;
    for(std::size_t k = 0; k < N; ++k)
    {
      frame.center[k] = low[k] / 2 + high[k] / 2;
      half = std::max(half, high[k] / 2 - low[k] / 2);
    }
    if(half > 0 && std::isfinite(half))
      frame.scale = half;
    for(double& c : frame.center)
      if(!std::isfinite(c))
        c = 0;
    return frame;
  }

  std::array<double, N> apply(const std::array<double, N>& p) const
  {
    std::array<double, N> q;
    for(std::size_t k = 0; k < N; ++k)
      q[k] = (p[k] - center[k]) / scale;
    return q;
  }
};

/// The `Unit_frame` of the bounding box of `points` (any range of `std::array<double, N>`),
/// non-finite points left out; the identity for no finite point.
template <std::size_t N, class PointRange>
Unit_frame<N> unit_frame_of(const PointRange& points)
{
  std::array<double, N> low{}, high{};
  bool first = true;
  for(const std::array<double, N>& p : points)
  {
    if(!std::all_of(p.begin(), p.end(), [](double x) { return std::isfinite(x); }))
      continue;
    for(std::size_t k = 0; k < N; ++k)
    {
      low[k] = first ? p[k] : std::min(low[k], p[k]);
      high[k] = first ? p[k] : std::max(high[k], p[k]);
    }
    first = false;
  }
  return Unit_frame<N>::of_box(low, high);
}

} // namespace internal
} // namespace ICM

#endif // ICM_INTERNAL_UNIT_FRAME_H
