#include "kestrel/scan_matching/contour_drawing.hpp"

#include <cmath>

namespace kestrel::scan_matching {

Status draw_contours(LikelihoodMap& map, const Pose2& pose, const ScanPoints& pts, const Contours& contours) {
  const float inv = static_cast<float>(kSub) / map.resolution_m();
  const float lim = static_cast<float>(map.dim() * kSub - 1);
  const float c = std::cos(pose.theta), s = std::sin(pose.theta);
  // NaN and infinite coordinates fail the range test too.
  const auto to_map = [&](uint16_t i, int16_t& mx, int16_t& my) {
    const float wx = pose.x + c * pts.x[i] - s * pts.y[i];
    const float wy = pose.y + s * pts.x[i] + c * pts.y[i];
    const float fx = (wx - map.origin_x_m()) * inv, fy = (wy - map.origin_y_m()) * inv;
    if (!(fx >= 0 && fx <= lim && fy >= 0 && fy <= lim)) return false;
    mx = static_cast<int16_t>(fx);
    my = static_cast<int16_t>(fy);
    return true;
  };
  Status result = Status::kOk;
  MapSegment seg;
  for (uint16_t i = 0; i < contours.segment_count; ++i) {
    if (to_map(contours.seg_a[i], seg.ax, seg.ay) && to_map(contours.seg_b[i], seg.bx, seg.by)) {
      if (!ok(map.draw(seg))) result = Status::kCapacityExceeded;
    }
  }
  for (uint16_t i = 0; i < contours.point_count; ++i) {
    if (contours.degree[i] != 0 || !to_map(i, seg.ax, seg.ay)) continue;
    seg.bx = seg.ax;
    seg.by = seg.ay;
    if (!ok(map.draw(seg))) result = Status::kCapacityExceeded;
  }
  return result;
}

}  // namespace kestrel::scan_matching
