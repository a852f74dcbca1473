#include "kestrel/exploration/sector_scan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

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

uint32_t SectorScan::erode_beam(const LaserScan& scan, std::size_t i) {
  const uint16_t r_mm = scan.range_mm[i];
  const float r = static_cast<float>(r_mm) * 1e-3f;
  // Only returns nearer than the cap plus rho can shorten a ray.
  if (r_mm < kMinValidRangeMm || r >= cap_ + rho_) return 0;
  const int rays = static_cast<int>(count_) * kRaysPerSector;
  const float ray_width = width_rad_ / kRaysPerSector;
  const std::size_t k = beam_slot(i);
  const float rel = (static_cast<float>(k) + 0.5f) * std::fabs(scan.angle_step_rad);  // from start_rad_
  const float half = r <= rho_ ? 0.5f * kPi<float> : std::asin(rho_ / r);
  const int k0 = std::max(0, static_cast<int>(std::floor((rel - half) / ray_width - 0.5f)));
  const int k1 = std::min(rays - 1, static_cast<int>(std::ceil((rel + half) / ray_width - 0.5f)));
  uint32_t used = work::kErodeBeam;
  if (k0 > k1) return used;
  // phi = ray angle - rel: cos and sin by the angle-difference identities, from the tables.
  const float rc = r * beam_cos_[k], rs = r * beam_sin_[k];
  for (int q = k0; q <= k1; ++q) {
    const std::size_t u = static_cast<std::size_t>(q);
    const float along = ray_cos_[u] * rc + ray_sin_[u] * rs;
    used += work::kErodeRay;
    if (along <= 0.0f && r > rho_) continue;
    float& c = clear_[u];
    // The disc blocks the ray at along - sqrt(h2) >= along - rho: when even that is beyond
    // the ray's clear length, the square root (software floating point on the Verdex) and
    // the rest cannot change it.
    if (along - rho_ >= c) continue;
    const float side = ray_sin_[u] * rc - ray_cos_[u] * rs;
    const float h2 = rho_ * rho_ - side * side;
    used += work::kErodeSide;
    if (h2 <= 0.0f) continue;
    const float block = std::max(along - std::sqrt(h2), 0.0f);
    c = std::min(c, block);
    used += work::kErodeRoot;
  }
  return used;
}

void SectorScan::finish() {
  const std::size_t rays = static_cast<std::size_t>(count_) * kRaysPerSector;
  for (std::size_t q = 0; q < rays; ++q)
    clear_mm_[q] = static_cast<uint16_t>(std::lround(std::max(clear_[q], 0.0f) * 1000.0f * 0.999f));

  // Frontiers. Mid-points of obstacle-free sectors, at R_p.
  for (uint16_t s = 0; s < count_; ++s) {
    if (free_[s]) (void)frontiers_.push_back({static_cast<uint8_t>(s), FrontierKind::kMid, mid_angle(s), rp_m_});
  }
  // Discontinuities between neighbours: the point of the farther-reaching sector on the
  // shared edge, at that sector's radius (where the safe region borders the unknown beyond the
  // nearer obstacle's edge). Two obstacle-free neighbours are no discontinuity.
  for (uint16_t s = 0; s + 1 < count_; ++s) {
    if (needs_beam_jump_ && !beam_jump_[s] && !beam_jump_[s + 1]) continue;  // a wall seen aslant
    const int32_t right = radius_mm_[s], left = radius_mm_[s + 1];
    const float edge = start_rad_ + static_cast<float>(s + 1) * width_rad_;
    if (left - right > jump_mm_) {  // sector s+1 reaches farther: its right (clockwise) point
      (void)frontiers_.push_back(
          {static_cast<uint8_t>(s + 1), FrontierKind::kRight, edge, static_cast<float>(left) * 1e-3f});
    } else if (right - left > jump_mm_) {  // sector s reaches farther: its left point
      (void)frontiers_.push_back(
          {static_cast<uint8_t>(s), FrontierKind::kLeft, edge, static_cast<float>(right) * 1e-3f});
    }
  }
}

float SectorScan::start_of(const LaserScan& scan) {
  const float step = scan.angle_step_rad;
  const float last_angle = scan.first_angle_rad + step * static_cast<float>(scan.beam_count - 1);
  return (step > 0.0f ? scan.first_angle_rad : last_angle) - 0.5f * std::fabs(step);
}

Status SectorScan::build(const LaserScan& scan, const SrtParams& params) {
  if (Status st = begin(scan, params); st != Status::kOk) return st;
  (void)advance(scan, work::kUnbounded);
  return Status::kOk;
}

Status SectorScan::begin(const LaserScan& scan, const SrtParams& params) {
  count_ = 0;
  stage_ = Stage::kEmpty;
  frontiers_.clear();
  const std::size_t beams = scan.beam_count;
  if (!scan.fan_well_formed()) return Status::kInvalidArgument;
  if (params.sector_count < 2 || params.sector_count > kMaxSectors || !(params.perception_range_m > 0.0f) ||
      !(params.discontinuity_m > 0.0f))
    return Status::kInvalidArgument;

  const uint16_t sectors = static_cast<uint16_t>(std::min<std::size_t>(params.sector_count, beams));
  const float step = scan.angle_step_rad;
  // Sectors are ordered counter-clockwise whatever the scan direction.
  ccw_ = step > 0.0f;
  beams_ = beams;
  const float span = std::fabs(step) * static_cast<float>(beams);
  width_rad_ = span / static_cast<float>(sectors);
  start_rad_ = start_of(scan);

  const long rp_long = std::lround(params.perception_range_m * 1000.0f);
  const uint16_t rp_mm = static_cast<uint16_t>(std::clamp<long>(rp_long, kMinValidRangeMm, 65535));
  const long jump_long = std::lround(params.discontinuity_m * 1000.0f);
  jump_mm_ = static_cast<int32_t>(std::clamp<long>(jump_long, 1, 65535));
  needs_beam_jump_ = params.discontinuity_needs_beam_jump;
  std::array<bool, kMaxSectors> seen{};
  for (uint16_t s = 0; s < sectors; ++s) {
    radius_mm_[s] = rp_mm;
    free_[s] = true;
    beam_jump_[s] = false;
  }
  // The last beam that said something about its direction, for the jumps between neighbours:
  // a dropout or a deflected beam between two returns is stepped over. No return is the
  // sensor's reach: a wall seen aslant leaving the URG-04LX's 4 m is no jump.
  const int32_t no_return_mm = scan.max_range_mm >= kMinValidRangeMm ? int32_t{scan.max_range_mm} : int32_t{65535};
  int32_t previous_mm = -1;
  std::size_t previous_sector = 0;
  for (std::size_t i = 0; i < beams; ++i) {
    // Beam i's centre lies in sector floor((i + 1/2) S / B), counted from the clockwise end.
    const std::size_t k = beam_slot(i);
    const std::size_t s = ((2 * k + 1) * sectors) / (2 * beams);
    const uint16_t r = scan.range_mm[i];
    if (r >= kMinValidRangeMm || r == range_code::kNoReturn) {
      const int32_t here = r == range_code::kNoReturn ? no_return_mm : int32_t{r};
      if (previous_mm >= 0 && std::abs(here - previous_mm) > jump_mm_)
        beam_jump_[s] = beam_jump_[previous_sector] = true;
      previous_mm = here;
      previous_sector = s;
    }
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

  // The erosion's starting point: every ray as long as its sector's radius, within R_p - rho.
  rho_ = std::max(params.clearance_m, 0.0f);
  rp_m_ = static_cast<float>(rp_mm) * 1e-3f;
  cap_ = std::max(rp_m_ - rho_, 0.0f);
  const std::size_t rays = static_cast<std::size_t>(sectors) * kRaysPerSector;
  for (std::size_t q = 0; q < rays; ++q)
    clear_[q] = std::min(cap_, static_cast<float>(radius_mm_[q / kRaysPerSector]) * 1e-3f);
  cursor_ = 0;
  if (ray_table_count_ != sectors || ray_table_width_ != width_rad_) {
    ray_table_width_ = 0;
    stage_ = Stage::kRayTable;
  } else if (beam_table_size_ != beams || beam_table_step_ != std::fabs(step)) {
    beam_table_step_ = 0;
    stage_ = Stage::kBeamTable;
  } else {
    stage_ = Stage::kErode;
  }
  return Status::kOk;
}

uint32_t SectorScan::advance(const LaserScan& scan, uint32_t budget) {
  uint32_t used = 0;
  uint32_t skipped = 0;
  const float step = std::fabs(scan.angle_step_rad);
  while (stage_ != Stage::kReady && stage_ != Stage::kEmpty && used < budget) {
    switch (stage_) {
      case Stage::kRayTable: {
        // Ray directions once per geometry: each beam then needs no sine or cosine of its own
        // per ray it touches (tens of them; software floating point on the Verdex).
        const std::size_t rays = static_cast<std::size_t>(count_) * kRaysPerSector;
        for (; cursor_ < rays && used < budget; ++cursor_) {
          const float a = (static_cast<float>(cursor_) + 0.5f) * width_rad_ / kRaysPerSector;
          ray_cos_[cursor_] = std::cos(a);
          ray_sin_[cursor_] = std::sin(a);
          used += work::kTableEntry;
        }
        if (cursor_ == rays) {
          ray_table_count_ = count_;
          ray_table_width_ = width_rad_;
          cursor_ = 0;
          stage_ = beam_table_size_ == beams_ && beam_table_step_ == step ? Stage::kErode : Stage::kBeamTable;
          if (stage_ == Stage::kBeamTable) beam_table_step_ = 0;
        }
        break;
      }
      case Stage::kBeamTable: {
        for (; cursor_ < beams_ && used < budget; ++cursor_) {
          const float rel = (static_cast<float>(cursor_) + 0.5f) * step;
          beam_cos_[cursor_] = std::cos(rel);
          beam_sin_[cursor_] = std::sin(rel);
          used += work::kTableEntry;
        }
        if (cursor_ == beams_) {
          beam_table_size_ = beams_;
          beam_table_step_ = step;
          cursor_ = 0;
          stage_ = Stage::kErode;
        }
        break;
      }
      case Stage::kErode: {
        for (; cursor_ < beams_ && used < budget; ++cursor_) {
          const uint32_t units = erode_beam(scan, cursor_);
          if (units > 0) {
            used += units;
          } else if (++skipped == work::kSkipBeams) {
            skipped = 0;
            ++used;
          }
        }
        if (cursor_ == beams_) stage_ = Stage::kFinish;
        break;
      }
      case Stage::kFinish:
        finish();
        used += work::kFinish;
        stage_ = Stage::kReady;
        break;
      case Stage::kEmpty:
      case Stage::kReady:
        break;
    }
  }
  return used;
}

}  // namespace kestrel::exploration
