#include "kestrel/scan_matching/covariance_estimator.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::scan_matching {
namespace {

// Vertex of the parabola through (-1, a), (0, b), (1, c), clamped to half a step.
float parabola_peak(float a, float b, float c) {
  const float den = a - 2.0f * b + c;
  if (!(den < 0)) return 0.0f;
  return std::clamp(0.5f * (a - c) / den, -0.5f, 0.5f);
}

}  // namespace

CovarianceEstimate CovarianceEstimator::estimate(const uint16_t* slice, int half, const int32_t* curve,
                                                 int count, int peak, int32_t floor, float degenerate_ratio) {
  CovarianceEstimate e;
  const int w = 2 * half + 1;
  const std::size_t n = static_cast<std::size_t>(w) * w;
  std::copy(slice, slice + n, scratch_.begin());
  const std::size_t p95 = std::min(n - 1, (n * 95) / 100);
  std::nth_element(scratch_.begin(), scratch_.begin() + static_cast<std::ptrdiff_t>(p95),
                   scratch_.begin() + static_cast<std::ptrdiff_t>(n));
  const uint16_t thr = std::max<uint16_t>(scratch_[p95], 1);
  // Second moments of the binary image {score >= 95th percentile}.
  double m = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  bool touches_edge = false;
  for (int y = 0; y < w; ++y) {
    for (int x = 0; x < w; ++x) {
      if (slice[y * w + x] < thr) continue;
      touches_edge = touches_edge || x == 0 || y == 0 || x == w - 1 || y == w - 1;
      const double fx = x - half, fy = y - half;
      m += 1; sx += fx; sy += fy; sxx += fx * fx; syy += fy * fy; sxy += fx * fy;
    }
  }
  // Quantisation alone leaves a cell's worth of uncertainty (uniform: 1/12 cell^2).
  double cxx = 1.0 / 12, cyy = 1.0 / 12, cxy = 0;
  if (m > 0) {
    const double mx = sx / m, my = sy / m;
    cxx += sxx / m - mx * mx;
    cyy += syy / m - my * my;
    cxy = sxy / m - mx * my;
  }
  const double tr = cxx + cyy, det = cxx * cyy - cxy * cxy;
  const double disc = std::sqrt(std::max(0.0, tr * tr / 4 - det));
  double l1 = tr / 2 + disc;
  const double l2 = std::max(1e-9, tr / 2 - disc);
  e.major_axis_rad = static_cast<float>(0.5 * std::atan2(2 * cxy, cxx - cyy));
  e.degenerate = l1 / l2 > degenerate_ratio;
  // A likely region cut off by the window is wider than what we can see: in a corridor the
  // score is flat along it, the 95th-percentile cells run from edge to edge, and their moments
  // measure the window, not the uncertainty. Then the major axis gets a variance that makes
  // the match say nothing along it (the EKF carries that direction on the IMU) instead of
  // silently pinning the pose to the window's middle.
  if (touches_edge && e.degenerate) l1 = std::max(l1, kUnboundedVarianceCells2);
  e.truncated = touches_edge;
  e.axis_ratio = static_cast<float>(l1 / l2);
  const double c = std::cos(e.major_axis_rad), sn = std::sin(e.major_axis_rad);
  cxx = l1 * c * c + l2 * sn * sn;
  cyy = l1 * sn * sn + l2 * c * c;
  cxy = (l1 - l2) * c * sn;
  e.translation_cells << static_cast<float>(cxx), static_cast<float>(cxy), static_cast<float>(cxy),
      static_cast<float>(cyy);

  const auto at = [&](int x, int y) { return static_cast<float>(slice[y * w + x]); };
  if (half >= 1) {
    e.dx = parabola_peak(at(half - 1, half), at(half, half), at(half + 1, half));
    e.dy = parabola_peak(at(half, half - 1), at(half, half), at(half, half + 1));
  }

  // Rotation: full width at half height of the best-score-per-rotation curve above its floor.
  const int32_t top = curve[peak];
  const int32_t lo = std::min(floor, top);
  const double half_height = lo + 0.5 * (top - lo);
  int left = peak, right = peak;
  while (left > 0 && curve[left - 1] >= half_height) --left;
  while (right < count - 1 && curve[right + 1] >= half_height) ++right;
  const double fwhm = right - left + 1;
  const double sigma = fwhm / 2.3548;
  e.rotation_steps2 = static_cast<float>(std::max(sigma * sigma, 1.0 / 12));
  if (peak > 0 && peak < count - 1) {
    e.dk = parabola_peak(static_cast<float>(curve[peak - 1]), static_cast<float>(top),
                         static_cast<float>(curve[peak + 1]));
  }
  return e;
}

}  // namespace kestrel::scan_matching
