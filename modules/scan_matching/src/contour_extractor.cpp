#include "kestrel/scan_matching/contour_extractor.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::scan_matching {

uint16_t ContourExtractor::find(uint16_t i) {
  while (parent_[i] != i) {
    parent_[i] = parent_[parent_[i]];  // path halving keeps the trees flat
    i = parent_[i];
  }
  return i;
}

bool ContourExtractor::may_join(const ScanPoints& pts, uint16_t i, uint16_t j, int32_t& key) const {
  const float dx = pts.x[j] - pts.x[i];
  const float dy = pts.y[j] - pts.y[i];
  const float d = std::sqrt(dx * dx + dy * dy);
  // The spacing of returns on a surface grows with range and with the beams in between; a
  // join longer than a few such spacings is a depth discontinuity, not a surface.
  const float r = static_cast<float>(std::min(pts.range_mm[i], pts.range_mm[j])) * 1e-3f;
  const float beams = static_cast<float>(pts.beam[j] - pts.beam[i]);
  const float allowed = std::min(params_.join_max_m,
                                 std::max(params_.join_base_m,
                                          params_.join_gap_factor * r * pts.angle_step_rad * beams));
  if (!(d <= allowed)) return false;
  key = static_cast<int32_t>(d * 1e4f);
  return true;
}

void ContourExtractor::extract(const ScanPoints& pts, Contours& out) {
  const uint16_t n = pts.count;
  const std::size_t window = std::clamp<std::size_t>(params_.join_beam_window, 1, kMaxJoinWindow);
  heap_.clear();
  for (uint16_t i = 0; i < n; ++i) {
    parent_[i] = i;
    out.degree[i] = 0;
  }
  for (uint16_t i = 0; i < n; ++i) {
    for (std::size_t k = 1; k <= window && i + k < n; ++k) {
      int32_t key = 0;
      if (may_join(pts, i, static_cast<uint16_t>(i + k), key)) {
        (void)heap_.push(static_cast<uint16_t>(i * window + (k - 1)), key);
      }
    }
  }
  out.segment_count = 0;
  while (!heap_.empty()) {
    const uint16_t id = heap_.pop();
    const auto i = static_cast<uint16_t>(id / window);
    const auto j = static_cast<uint16_t>(i + id % window + 1);
    if (out.degree[i] >= 2 || out.degree[j] >= 2) continue;  // only endpoints may join
    const uint16_t ri = find(i), rj = find(j);
    if (ri == rj) continue;  // would close a loop
    parent_[ri] = rj;
    ++out.degree[i];
    ++out.degree[j];
    out.seg_a[out.segment_count] = i;
    out.seg_b[out.segment_count] = j;
    ++out.segment_count;
  }
  out.point_count = n;
  out.contour_count = 0;
  for (uint16_t i = 0; i < n; ++i) {
    out.contour[i] = find(i);
    if (out.contour[i] == i) ++out.contour_count;
  }
}

}  // namespace kestrel::scan_matching
