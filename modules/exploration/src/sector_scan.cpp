#include "kestrel/exploration/sector_scan.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::exploration {

const char* to_string(FrontierKind k) {
  switch (k) {
    case FrontierKind::kMid: return "mid";
    case FrontierKind::kLeft: return "left";
    case FrontierKind::kRight: return "right";
  }
  return "unknown";
}

Status SectorScan::build(const LaserScan& scan, const SrtParams& params) {
  count_ = 0;
  frontiers_.clear();
  const std::size_t beams = scan.beam_count;
  if (beams == 0 || beams > kMaxBeams || !std::isfinite(scan.first_angle_rad) ||
      !std::isfinite(scan.angle_step_rad) || scan.angle_step_rad == 0.0f)
    return Status::kInvalidArgument;
  if (params.sector_count < 2 || params.sector_count > kMaxSectors ||
      !(params.perception_range_m > 0.0f) || !(params.discontinuity_m > 0.0f))
    return Status::kInvalidArgument;

  const uint16_t sectors = static_cast<uint16_t>(std::min<std::size_t>(params.sector_count, beams));
  const float step = scan.angle_step_rad;
  // Sectors are ordered counter-clockwise whatever the scan direction.
  const bool ccw = step > 0.0f;
  const float span = std::fabs(step) * static_cast<float>(beams);
  width_rad_ = span / static_cast<float>(sectors);
  const float last_angle = scan.first_angle_rad + step * static_cast<float>(beams - 1);
  start_rad_ = (ccw ? scan.first_angle_rad : last_angle) - 0.5f * std::fabs(step);

  const long rp_long = std::lround(params.perception_range_m * 1000.0f);
  const uint16_t rp_mm = static_cast<uint16_t>(std::clamp<long>(rp_long, kMinValidRangeMm, 65535));
  std::array<bool, kMaxSectors> seen{};
  for (uint16_t s = 0; s < sectors; ++s) {
    radius_mm_[s] = rp_mm;
    free_[s] = true;
  }
  for (std::size_t i = 0; i < beams; ++i) {
    // Beam i's centre lies in sector floor((i + 1/2) S / B), counted from the clockwise end.
    const std::size_t k = ccw ? i : beams - 1 - i;
    const std::size_t s = ((2 * k + 1) * sectors) / (2 * beams);
    const uint16_t r = scan.range_mm[i];
    if (r >= kMinValidRangeMm) {
      seen[s] = true;
      if (r < rp_mm) {
        free_[s] = false;
        radius_mm_[s] = std::min(radius_mm_[s], r);
      }
    } else if (r == range_code::kNoReturn) {
      seen[s] = true;
    } else if (r == range_code::kTooNear) {
      seen[s] = true;
      free_[s] = false;
      radius_mm_[s] = 0;
    } else {
      free_[s] = false;  // dropout or deflected: no information either way
    }
  }
  for (uint16_t s = 0; s < sectors; ++s)
    if (!seen[s]) radius_mm_[s] = 0;
  count_ = sectors;

  // Frontiers. Mid-points of obstacle-free sectors, at R_p.
  const float rp_m = static_cast<float>(rp_mm) * 1e-3f;
  for (uint16_t s = 0; s < sectors; ++s) {
    if (free_[s])
      (void)frontiers_.push_back({static_cast<uint8_t>(s), FrontierKind::kMid, mid_angle(s), rp_m});
  }
  // Discontinuities between neighbours: the point of the farther-reaching sector on the
  // shared edge, at that sector's radius (where the safe region borders the unknown beyond the
  // nearer obstacle's edge). Two obstacle-free neighbours are no discontinuity.
  const long jump_long = std::lround(params.discontinuity_m * 1000.0f);
  const int32_t jump_mm = static_cast<int32_t>(std::clamp<long>(jump_long, 1, 65535));
  for (uint16_t s = 0; s + 1 < sectors; ++s) {
    const int32_t right = radius_mm_[s], left = radius_mm_[s + 1];
    const float edge = start_rad_ + static_cast<float>(s + 1) * width_rad_;
    if (left - right > jump_mm) {  // sector s+1 reaches farther: its right (clockwise) point
      (void)frontiers_.push_back({static_cast<uint8_t>(s + 1), FrontierKind::kRight, edge,
                                  static_cast<float>(left) * 1e-3f});
    } else if (right - left > jump_mm) {  // sector s reaches farther: its left point
      (void)frontiers_.push_back({static_cast<uint8_t>(s), FrontierKind::kLeft, edge,
                                  static_cast<float>(right) * 1e-3f});
    }
  }
  return Status::kOk;
}

}  // namespace kestrel::exploration
