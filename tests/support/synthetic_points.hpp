#pragma once
// A SegmentWorld's returns as ScanPoints, in the sensor frame, as the scan matcher hands them
// to the compact SLAM and the relocaliser.
#include <cmath>

#include "kestrel/scan_matching/scan_points.hpp"
#include "synthetic_world.hpp"

namespace kestrel::test {

inline scan_matching::ScanPoints scan_points(const SegmentWorld& w, const LaserModel& m, const Pose2& sensor) {
  const LaserScan s = w.scan(m, sensor.x, sensor.y, sensor.theta);
  scan_matching::ScanPoints p;
  p.angle_step_rad = std::fabs(s.angle_step_rad);
  for (uint16_t i = 0; i < s.beam_count; ++i) {
    const uint16_t r = s.range_mm[i];
    if (!LaserScan::is_return(r) || r >= s.max_range_mm) continue;
    const float a = s.angle_of(i);
    p.x[p.count] = 1e-3f * r * std::cos(a);
    p.y[p.count] = 1e-3f * r * std::sin(a);
    p.range_mm[p.count] = r;
    p.beam[p.count] = i;
    ++p.count;
  }
  return p;
}

}  // namespace kestrel::test
