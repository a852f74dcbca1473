#pragma once
// A SegmentWorld's returns as ScanPoints, in the sensor frame, as the scan matcher hands them
// to the compact SLAM and the relocaliser.
#include <cmath>

#include "kestrel/scan_matching/scan_points.hpp"
#include "synthetic_world.hpp"

namespace kestrel::test {

// A scan's returns as points. turn_per_beam, dx_per_beam, dy_per_beam: the sensor turned and
// moved this much with each beam (sensor frame at the first beam: a scan taken turning and
// flying), and the points are deskewed to the first beam's pose, as ScanMatcher::deskew leaves
// them (the sweep_* fields say so).
inline scan_matching::ScanPoints points_of_scan(const LaserScan& s, float turn_per_beam = 0.0f,
                                                float dx_per_beam = 0.0f, float dy_per_beam = 0.0f) {
  scan_matching::ScanPoints p;
  p.angle_step_rad = std::fabs(s.angle_step_rad);
  p.sweep_dtheta_rad = turn_per_beam;
  p.sweep_dx_m = dx_per_beam;
  p.sweep_dy_m = dy_per_beam;
  for (uint16_t i = 0; i < s.beam_count; ++i) {
    const uint16_t r = s.range_mm[i];
    if (!LaserScan::is_return(r) || r >= s.max_range_mm) continue;
    const float a = s.angle_of(i) + static_cast<float>(i) * turn_per_beam;
    p.x[p.count] = static_cast<float>(i) * dx_per_beam + 1e-3f * r * std::cos(a);
    p.y[p.count] = static_cast<float>(i) * dy_per_beam + 1e-3f * r * std::sin(a);
    p.range_mm[p.count] = r;
    p.beam[p.count] = i;
    ++p.count;
  }
  return p;
}

inline scan_matching::ScanPoints scan_points(const SegmentWorld& w, const LaserModel& m, const Pose2& sensor) {
  return points_of_scan(w.scan(m, sensor.x, sensor.y, sensor.theta));
}

}  // namespace kestrel::test
