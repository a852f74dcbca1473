#include "kestrel/core/scan_free_space.hpp"

#include <algorithm>
#include <cmath>

#include "kestrel/core/chamfer_distance.hpp"
#include "kestrel/core/fixed_point.hpp"

namespace kestrel {
namespace {
constexpr int32_t kCellMm = 100;  // ScanFreeSpace::kCellM
constexpr int32_t kHalfCellMm = kCellMm / 2;
constexpr int32_t kReachMm = kCellMm * (ScanFreeSpace::kSide / 2 - 1);
constexpr int kOne = 30;  // beam directions in Q30

int32_t q30(float v) { return static_cast<int32_t>(std::lround(static_cast<double>(v) * (1 << kOne))); }
int32_t rotate(int32_t a, int32_t b, int32_t ca, int32_t sb) {
  return static_cast<int32_t>((static_cast<int64_t>(a) * ca - static_cast<int64_t>(b) * sb) >> kOne);
}
// A Q30 direction component as the Q8 step of half a cell, rounded to nearest with ties away
// from zero, so that a beam and its mirror image step alike.
int32_t half_cell_step(int32_t component_q30) {
  return static_cast<int32_t>(fixed_detail::round_shift(component_q30, kOne - 7));
}
}  // namespace

Status ScanFreeSpace::build(const LaserScan& scan, const Pose2& laser, float near_m, float wide_m) {
  cells_.fill(kDistance);  // unseen, no return near
  built_ = false;
  if (!laser.finite() || !(near_m > 0.0f) || !(wide_m >= near_m) || !(wide_m <= 1.0f) || !scan.fan_well_formed())
    return Status::kInvalidArgument;
  constexpr float kHalfM = kCellM * (kSide / 2);
  corner_ = {laser.x - kHalfM, laser.y - kHalfM};
  near_units_ = chamfer::units_of(near_m, kCellM, kDistance);
  wide_units_ = chamfer::units_of(wide_m, kCellM, kDistance);
  // Beam directions by an integer rotation: two trigonometric pairs in all.
  int32_t c = q30(std::cos(laser.theta + scan.first_angle_rad)), s = q30(std::sin(laser.theta + scan.first_angle_rad));
  const int32_t step_c = q30(std::cos(scan.angle_step_rad)), step_s = q30(std::sin(scan.angle_step_rad));
  const int32_t no_return_mm = std::min<int32_t>(scan.max_range_mm, kReachMm);
  const int32_t origin_q8 = (kSide / 2) << 8;  // the laser, in cell units
  for (std::size_t i = 0; i < scan.beam_count; ++i) {
    const int32_t beam_c = c, beam_s = s;
    c = rotate(beam_c, beam_s, step_c, step_s);
    s = rotate(beam_s, -beam_c, step_c, step_s);
    const uint16_t r_mm = scan.range_mm[i];
    int32_t ray_mm;
    bool ends_at_return = false;
    if (LaserScan::is_return(r_mm)) {
      ends_at_return = r_mm <= kReachMm;
      ray_mm = std::min<int32_t>(r_mm, kReachMm);
    } else if (r_mm == range_code::kNoReturn) {
      ray_mm = no_return_mm;  // nothing in range: open space
    } else {
      continue;  // deflected, dropped out, too near: no word on this direction
    }
    // Half a cell a step: the direction times 128 in Q8 cell units, rounded (a floor would lean
    // every ray towards -x and -y, by up to a quarter cell at the grid's edge).
    draw_ray(origin_q8, origin_q8, half_cell_step(beam_c), half_cell_step(beam_s), ray_mm / kHalfCellMm,
             ends_at_return);
  }
  chamfer();
  built_ = true;
  return Status::kOk;
}

void ScanFreeSpace::draw_ray(int32_t x_q8, int32_t y_q8, int32_t step_x_q8, int32_t step_y_q8, int steps,
                             bool ends_at_return) {
  int x = 0, y = 0;
  for (int k = 0; k <= steps; ++k, x_q8 += step_x_q8, y_q8 += step_y_q8) {
    x = x_q8 >> 8;
    y = y_q8 >> 8;
    if (x < 0 || y < 0 || x >= kSide || y >= kSide) return;
    cell(x, y) |= kSeen;
  }
  if (ends_at_return) cell(x, y) &= kSeen;  // the return: distance zero
}

void ScanFreeSpace::chamfer() {
  // Seven bits of distance beside the flag of a ray's crossing, which stays.
  struct Distances {
    ScanFreeSpace& grid;
    int distance(int x, int y) const { return grid.cell(x, y) & kDistance; }
    void lower(int x, int y, int d) {
      uint8_t& v = grid.cell(x, y);
      v = static_cast<uint8_t>((v & kSeen) | d);
    }
  };
  Distances cells{*this};
  chamfer::propagate(cells, 0, 0, kSide - 1, kSide - 1);
}

ScanFreeSpace::Cell ScanFreeSpace::cell_of(Point2 world) const {
  const float fx = (world.x - corner_.x) / kCellM, fy = (world.y - corner_.y) / kCellM;
  // Not finite, or far beyond the grid: a cell outside it that offsets cannot bring back.
  if (!(std::fabs(fx) < 1e6f && std::fabs(fy) < 1e6f)) return {-1'000'000, -1'000'000};
  return {static_cast<int>(std::floor(fx)), static_cast<int>(std::floor(fy))};
}

ScanFreeSpace::Clearance ScanFreeSpace::at(Cell c) const {
  if (!built_ || c.x < 0 || c.y < 0 || c.x >= kSide || c.y >= kSide) return Clearance::kNotFree;
  const uint8_t v = cells_[static_cast<std::size_t>(c.y * kSide + c.x)];
  if ((v & kSeen) == 0) return Clearance::kNotFree;
  const uint8_t d = v & kDistance;
  if (d >= wide_units_) return Clearance::kWide;
  return d >= near_units_ ? Clearance::kNear : Clearance::kNotFree;
}

}  // namespace kestrel
