#pragma once
// Test-only 2D worlds made of wall segments, with an exact ray caster that fills a LaserScan
// the way the Hokuyo driver does (mm ranges, kNoReturn beyond the maximum range). Used by the
// exploration and autonomy tests to make synthetic scans and to fly a kinematic point vehicle.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "kestrel/core/messages.hpp"

namespace kestrel::test {

struct Segment {
  double x0, y0, x1, y1;
};

struct LaserModel {
  uint16_t beams;
  double fov_rad;
  uint16_t max_range_mm;

  static LaserModel urg04lx() { return {682, 240.0 * M_PI / 180.0, 4000}; }
  static LaserModel utm30lx() { return {1081, 270.0 * M_PI / 180.0, 30000}; }
  double first_angle() const { return -fov_rad / 2.0 + 0.5 * step(); }
  double step() const { return fov_rad / beams; }
};

class SegmentWorld {
 public:
  void add(double x0, double y0, double x1, double y1) { walls_.push_back({x0, y0, x1, y1}); }
  // Axis-aligned rectangle outline.
  void add_box(double x0, double y0, double x1, double y1) {
    add(x0, y0, x1, y0);
    add(x1, y0, x1, y1);
    add(x1, y1, x0, y1);
    add(x0, y1, x0, y0);
  }
  const std::vector<Segment>& walls() const { return walls_; }

  // Distance along the ray from (x, y) in direction a to the nearest wall, or +inf.
  double cast(double x, double y, double a) const {
    const double dx = std::cos(a), dy = std::sin(a);
    double best = INFINITY;
    for (const Segment& s : walls_) {
      const double ex = s.x1 - s.x0, ey = s.y1 - s.y0;
      const double den = dx * ey - dy * ex;
      if (std::fabs(den) < 1e-12) continue;
      const double wx = s.x0 - x, wy = s.y0 - y;
      const double t = (wx * ey - wy * ex) / den;  // along the ray
      const double u = (wx * dy - wy * dx) / den;  // along the segment
      if (t > 1e-9 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
    }
    return best;
  }

  // Shortest distance from a point to any wall.
  double clearance(double x, double y) const {
    double best = INFINITY;
    for (const Segment& s : walls_) {
      const double ex = s.x1 - s.x0, ey = s.y1 - s.y0;
      const double len2 = ex * ex + ey * ey;
      double u = len2 > 0 ? ((x - s.x0) * ex + (y - s.y0) * ey) / len2 : 0.0;
      u = std::clamp(u, 0.0, 1.0);
      best = std::min(best, std::hypot(s.x0 + u * ex - x, s.y0 + u * ey - y));
    }
    return best;
  }

  LaserScan scan(const LaserModel& m, double x, double y, double heading, TimeUs stamp = {}) const {
    LaserScan s;
    s.stamp = stamp;
    s.beam_count = m.beams;
    s.first_angle_rad = static_cast<float>(m.first_angle());
    s.angle_step_rad = static_cast<float>(m.step());
    s.max_range_mm = m.max_range_mm;
    for (uint16_t i = 0; i < m.beams; ++i) {
      const double r = cast(x, y, heading + m.first_angle() + m.step() * i);
      const double mm = r * 1000.0;
      s.range_mm[i] =
          mm > m.max_range_mm ? range_code::kNoReturn : static_cast<uint16_t>(std::max(20.0, std::round(mm)));
    }
    return s;
  }

 private:
  std::vector<Segment> walls_;
};

// A valid estimate at (x, y), 1 m up, with this heading, at rest.
inline NavState nav_at(float x, float y, float heading) {
  NavState n;
  n.valid = true;
  n.position_m = {x, y, 1.0f};
  n.heading_rad = heading;
  return n;
}

// A scan with every beam set to the same value (a range in mm or a range code).
inline LaserScan uniform_scan(const LaserModel& m, uint16_t value) {
  LaserScan s;
  s.beam_count = m.beams;
  s.first_angle_rad = static_cast<float>(m.first_angle());
  s.angle_step_rad = static_cast<float>(m.step());
  s.max_range_mm = m.max_range_mm;
  for (uint16_t i = 0; i < m.beams; ++i) s.range_mm[i] = value;
  return s;
}

// gt-building's corridor: 2 m wide (y 7..9) along x, closed at x = 0, with a 1.2 m door in its
// north wall at x 5..6.2 into a room whose west wall is x = 5. Flights home stalled here, held
// off the north wall beside the door's jamb.
inline SegmentWorld corridor_with_a_door() {
  SegmentWorld w;
  w.add(0, 7, 12, 7);
  w.add(0, 9, 5, 9);
  w.add(6.2, 9, 12, 9);
  w.add(0, 7, 0, 9);
  w.add(5, 9, 5, 12);
  return w;
}

}  // namespace kestrel::test
