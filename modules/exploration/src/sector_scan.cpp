#include "kestrel/exploration/sector_scan.hpp"

#include <algorithm>
#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel::exploration {

const char* to_string(FrontierKind k) {
  switch (k) {
    case FrontierKind::kMid:
      return "mid";
    case FrontierKind::kLeft:
      return "left";
    case FrontierKind::kRight:
      return "right";
  }
  return "unknown";
}

void SectorScan::erode(const LaserScan& scan, const SrtParams& params, uint16_t rp_mm) {
  const float rho = std::max(params.clearance_m, 0.0f);
  const float cap = std::max(static_cast<float>(rp_mm) * 1e-3f - rho, 0.0f);
  const int rays = static_cast<int>(count_) * kRaysPerSector;
  const float ray_width = width_rad_ / kRaysPerSector;
  std::array<float, kMaxSectors * kRaysPerSector> clear{}, ray_cos{}, ray_sin{};
  for (int k = 0; k < rays; ++k) {
    const std::size_t q = static_cast<std::size_t>(k);
    clear[q] = std::min(cap, static_cast<float>(radius_mm_[static_cast<std::size_t>(k / kRaysPerSector)]) * 1e-3f);
    // Ray directions once per call: each beam then needs one sine and cosine of its own
    // angle instead of one per ray it touches (tens of them; software floating point on
    // the Verdex made arrival at a waypoint cost 14 M instructions).
    const float a = (static_cast<float>(k) + 0.5f) * width_rad_ / kRaysPerSector;
    ray_cos[q] = std::cos(a);
    ray_sin[q] = std::sin(a);
  }
  const std::size_t beams = scan.beam_count;
  const bool ccw = scan.angle_step_rad > 0.0f;
  const float step = std::fabs(scan.angle_step_rad);
  for (std::size_t i = 0; i < beams; ++i) {
    const uint16_t r_mm = scan.range_mm[i];
    const float r = static_cast<float>(r_mm) * 1e-3f;
    // Only returns nearer than the cap plus rho can shorten a ray.
    if (r_mm < kMinValidRangeMm || r >= cap + rho) continue;
    const std::size_t k = ccw ? i : beams - 1 - i;
    const float rel = (static_cast<float>(k) + 0.5f) * step;  // beam angle from start_rad_
    const float half = r <= rho ? 0.5f * kPi<float> : std::asin(rho / r);
    const int k0 = std::max(0, static_cast<int>(std::floor((rel - half) / ray_width - 0.5f)));
    const int k1 = std::min(rays - 1, static_cast<int>(std::ceil((rel + half) / ray_width - 0.5f)));
    if (k0 > k1) continue;
    // phi = ray angle - rel: cos and sin by the angle-difference identities.
    const float rc = r * std::cos(rel), rs = r * std::sin(rel);
    for (int q = k0; q <= k1; ++q) {
      const std::size_t u = static_cast<std::size_t>(q);
      const float along = ray_cos[u] * rc + ray_sin[u] * rs;
      if (along <= 0.0f && r > rho) continue;
      float& c = clear[u];
      // The disc blocks the ray at along - sqrt(h2) >= along - rho: when even that is beyond
      // the ray's clear length, the square root (software floating point on the Verdex) and
      // the rest cannot change it.
      if (along - rho >= c) continue;
      const float side = ray_sin[u] * rc - ray_cos[u] * rs;
      const float h2 = rho * rho - side * side;
      if (h2 <= 0.0f) continue;
      const float block = std::max(along - std::sqrt(h2), 0.0f);
      c = std::min(c, block);
    }
  }
  for (int q = 0; q < rays; ++q)
    clear_mm_[static_cast<std::size_t>(q)] =
        static_cast<uint16_t>(std::lround(std::max(clear[static_cast<std::size_t>(q)], 0.0f) * 1000.0f * 0.999f));
}

Status SectorScan::build(const LaserScan& scan, const SrtParams& params) {
  count_ = 0;
  frontiers_.clear();
  const std::size_t beams = scan.beam_count;
  if (beams == 0 || beams > kMaxBeams || !std::isfinite(scan.first_angle_rad) || !std::isfinite(scan.angle_step_rad) ||
      scan.angle_step_rad == 0.0f)
    return Status::kInvalidArgument;
  if (params.sector_count < 2 || params.sector_count > kMaxSectors || !(params.perception_range_m > 0.0f) ||
      !(params.discontinuity_m > 0.0f))
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
  erode(scan, params, rp_mm);

  // Frontiers. Mid-points of obstacle-free sectors, at R_p.
  const float rp_m = static_cast<float>(rp_mm) * 1e-3f;
  for (uint16_t s = 0; s < sectors; ++s) {
    if (free_[s]) (void)frontiers_.push_back({static_cast<uint8_t>(s), FrontierKind::kMid, mid_angle(s), rp_m});
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
      (void)frontiers_.push_back(
          {static_cast<uint8_t>(s + 1), FrontierKind::kRight, edge, static_cast<float>(left) * 1e-3f});
    } else if (right - left > jump_mm) {  // sector s reaches farther: its left point
      (void)frontiers_.push_back(
          {static_cast<uint8_t>(s), FrontierKind::kLeft, edge, static_cast<float>(right) * 1e-3f});
    }
  }
  return Status::kOk;
}

}  // namespace kestrel::exploration
