#include "kestrel/planning/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace kestrel::planning {

Status GridParams::validate() const {
  const bool ok = cell_m >= 0.02f && cell_m <= 1.0f && reach_m > 0.0f && reach_m <= 60.0f && hit_step >= 1 &&
                  hit_step <= 127 && miss_step >= 1 && miss_step <= 127 && footprint_m >= 0.0f && footprint_m <= 2.0f;
  return ok ? Status::kOk : Status::kInvalidArgument;
}

Status OccupancyGrid::configure(const GridParams& params, Point2 home, uint16_t beam_count, float first_angle_rad,
                                float angle_step_rad) {
  configured_ = false;
  if (params.validate() != Status::kOk) return Status::kInvalidArgument;
  if (!fan_angles_well_formed(beam_count, first_angle_rad, angle_step_rad)) return Status::kInvalidArgument;
  const Result<GridGeometry> g = GridGeometry::around(home, params.cell_m);
  if (!g.ok()) return Status::kInvalidArgument;
  params_ = params;
  geometry_ = g.value();
  beam_count_ = beam_count;
  first_angle_rad_ = first_angle_rad;
  angle_step_rad_ = angle_step_rad;
  for (std::size_t i = 0; i < beam_count; ++i) {
    const double a =
        static_cast<double>(first_angle_rad) + static_cast<double>(angle_step_rad) * static_cast<double>(i);
    cos_q14_[i] = static_cast<int16_t>(std::lround(std::cos(a) * 16384.0));
    sin_q14_[i] = static_cast<int16_t>(std::lround(std::sin(a) * 16384.0));
  }
  mm_to_q8_q16_ = std::llround(65536.0 * 256.0 / (1000.0 * static_cast<double>(params.cell_m)));
  reach_mm_ = static_cast<int32_t>(std::lround(params.reach_m * 1000.0f));
  footprint_cells_ = static_cast<int>(std::lround(params.footprint_m / params.cell_m));
  configured_ = true;
  clear();
  return Status::kOk;
}

void OccupancyGrid::clear() {
  cells_.fill(occupancy::kUnknown);
  looks_.fill(0);
  tag_ = 0;
  drawn_ = {};
  scans_drawn_ = 0;
  known_cells_ = 0;
}

void OccupancyGrid::set(Cell c, uint8_t v) {
  if (!on_grid(c.x, c.y)) return;
  uint8_t& cell = cells_[cell_index(c.x, c.y)];
  if (cell == occupancy::kUnknown && v != occupancy::kUnknown) ++known_cells_;
  if (cell != occupancy::kUnknown && v == occupancy::kUnknown) --known_cells_;
  cell = v;
  drawn_.include(c.x, c.y);
}

bool OccupancyGrid::first_look(std::size_t i, uint8_t bit) {
  uint8_t& l = looks_[i];
  if ((l >> 2) != tag_) l = static_cast<uint8_t>(tag_ << 2);
  if ((l & bit) != 0) return false;
  l = static_cast<uint8_t>(l | bit);
  return true;
}

void OccupancyGrid::free_cell(std::size_t i) {
  if (!first_look(i, 1u)) return;
  const uint8_t v = cells_[i];
  if (v == occupancy::kUnknown) ++known_cells_;
  const int base = v == occupancy::kUnknown ? occupancy::kEven : v;
  cells_[i] = static_cast<uint8_t>(std::max(1, base - params_.miss_step));
}

void OccupancyGrid::hit_cell(std::size_t i) {
  if (!first_look(i, 2u)) return;
  const uint8_t v = cells_[i];
  if (v == occupancy::kUnknown) ++known_cells_;
  const int base = v == occupancy::kUnknown ? occupancy::kEven : v;
  cells_[i] = static_cast<uint8_t>(std::min(255, base + params_.hit_step));
}

Status OccupancyGrid::draw(const LaserScan& scan, const Pose2& pose) {
  if (!configured_) return Status::kNotFound;
  if (scan.beam_count != beam_count_ ||
      std::fabs(scan.first_angle_rad - first_angle_rad_) > 1e-3f * std::fabs(angle_step_rad_) ||
      std::fabs(scan.angle_step_rad - angle_step_rad_) > 1e-6f * std::fabs(angle_step_rad_))
    return Status::kInvalidArgument;
  if (!pose.finite()) return Status::kNotFinite;
  Cell sensor;
  if (!geometry_.to_cell(pose.x, pose.y, sensor)) return Status::kOutOfRange;
  // The scan's only floating point: the sensor's position in Q8 cells and its heading in Q14.
  const int64_t sx = std::llround((pose.x - geometry_.origin.x) / geometry_.cell_m * 256.0f);
  const int64_t sy = std::llround((pose.y - geometry_.origin.y) / geometry_.cell_m * 256.0f);
  const int64_t hc = std::lround(std::cos(pose.theta) * 16384.0f), hs = std::lround(std::sin(pose.theta) * 16384.0f);
  drawn_.include(sensor.x, sensor.y);
  // A new tag for this scan's looks; every 63 scans the marks are wiped (64 KiB words).
  if (++tag_ > 63) {
    looks_.fill(0);
    tag_ = 1;
  }
  for (std::size_t b = 0; b < beam_count_; ++b) {
    const uint16_t r = scan.range_mm[b];
    int32_t ray_mm = 0;
    bool hit = false;
    if (LaserScan::is_return(r)) {
      hit = r <= reach_mm_;
      ray_mm = hit ? r : reach_mm_;
    } else if (r == range_code::kNoReturn && params_.no_return_is_free) {
      ray_mm = std::min<int32_t>(reach_mm_, scan.max_range_mm);
    } else {
      continue;
    }
    const int64_t r_q8 = (static_cast<int64_t>(ray_mm) * mm_to_q8_q16_) >> 16;
    // The beam's direction in the navigation frame, Q14.
    const int64_t dc = (hc * cos_q14_[b] - hs * sin_q14_[b]) >> 14;
    const int64_t ds = (hs * cos_q14_[b] + hc * sin_q14_[b]) >> 14;
    const int64_t ex = sx + ((r_q8 * dc) >> 14), ey = sy + ((r_q8 * ds) >> 14);
    // One sample per cell along the major axis.
    const int64_t steps = std::max(std::llabs(ex - sx), std::llabs(ey - sy)) / 256 + 1;
    const int64_t step_x = (ex - sx) / steps, step_y = (ey - sy) / steps;
    const int end_x = static_cast<int>(ex >> 8), end_y = static_cast<int>(ey >> 8);
    int64_t px = sx, py = sy;
    bool left_grid = false;
    for (int64_t k = 0; k < steps; ++k, px += step_x, py += step_y) {
      const int cx = static_cast<int>(px >> 8), cy = static_cast<int>(py >> 8);
      if (cx == end_x && cy == end_y) break;
      if (!on_grid(cx, cy)) {
        left_grid = true;
        break;
      }
      const std::size_t i = cell_index(cx, cy);
      // The sample just before a return is known but not a miss: it may be the same wall.
      if (hit && k == steps - 1) {
        if (cells_[i] == occupancy::kUnknown) {
          cells_[i] = occupancy::kEven;
          ++known_cells_;
        }
      } else {
        free_cell(i);
      }
    }
    if (left_grid || !on_grid(end_x, end_y)) continue;
    drawn_.include(end_x, end_y);
    if (hit)
      hit_cell(cell_index(end_x, end_y));
    else
      free_cell(cell_index(end_x, end_y));
  }
  // The vehicle's disc: the cells the laser cannot see under and behind it.
  const int f = footprint_cells_;
  for (int dy = -f; dy <= f; ++dy)
    for (int dx = -f; dx <= f; ++dx)
      if (dx * dx + dy * dy <= f * f && on_grid(sensor.x + dx, sensor.y + dy)) {
        free_cell(cell_index(sensor.x + dx, sensor.y + dy));
        drawn_.include(sensor.x + dx, sensor.y + dy);
      }
  ++scans_drawn_;
  return Status::kOk;
}

}  // namespace kestrel::planning
