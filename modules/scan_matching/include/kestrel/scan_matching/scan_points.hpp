#pragma once
// The returns of one laser scan as points in the sensor frame: the common input of contour
// extraction (paper 000, 5.1.1) and of the search (5.1.2). Fixed capacity, no heap.
#include <array>
#include <cstdint>

#include "kestrel/core/messages.hpp"

namespace kestrel::scan_matching {

inline constexpr std::size_t kMaxPoints = kMaxBeams;

struct ScanPoints {
  std::array<float, kMaxPoints> x{};       // m, sensor frame
  std::array<float, kMaxPoints> y{};       // m, sensor frame
  std::array<uint16_t, kMaxPoints> range_mm{};
  std::array<uint16_t, kMaxPoints> beam{};  // beam index the point came from (gaps matter)
  float angle_step_rad = 0;                // |angle between consecutive beams|
  // The sensor's motion over the sweep, per beam index, that the points were deskewed with
  // (ScanMatcher::deskew), in the sensor frame at the stamp: beam b was taken from
  // (b * sweep_dx_m, b * sweep_dy_m) looking b * sweep_dtheta_rad further round. Zero when the
  // scan was taken as instantaneous. Lets a walk along a beam that found nothing follow it.
  float sweep_dx_m = 0, sweep_dy_m = 0, sweep_dtheta_rad = 0;
  uint16_t count = 0;
};

}  // namespace kestrel::scan_matching
