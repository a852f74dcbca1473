#pragma once
// Synthetic scans for the scan-matching tests: a laser ray-cast against line segments.
#include <cmath>
#include <vector>

#include "kestrel/core/messages.hpp"
#include "kestrel/scan_matching/scan_points.hpp"

namespace kestrel::test {

struct Wall {
  float ax, ay, bx, by;
  int skip_every = 0;  // a railing: beams with index % skip_every == 0 pass through
};

// How the sensor moves while it sweeps: beam i is taken i * beam_interval after the stamp,
// from the stamp's pose carried along at this velocity (world frame) and yaw rate.
struct SweepMotion {
  Duration beam_interval;
  float vx_mps = 0, vy_mps = 0, yaw_rate_radps = 0;
};

inline LaserScan cast_sweep(const Pose2& pose, const SweepMotion& motion, const std::vector<Wall>& walls,
                            int beams = 1081, float fov = 4.71238898f, TimeUs t = {}) {
  LaserScan s;
  s.stamp = t;
  s.beam_count = static_cast<uint16_t>(beams);
  s.first_angle_rad = -fov / 2;
  s.angle_step_rad = fov / static_cast<float>(beams - 1);
  s.max_range_mm = 30000;
  s.beam_interval = motion.beam_interval;
  for (int i = 0; i < beams; ++i) {
    const float dt = static_cast<float>(motion.beam_interval.seconds()) * static_cast<float>(i);
    const float px = pose.x + motion.vx_mps * dt, py = pose.y + motion.vy_mps * dt;
    const float a = pose.theta + motion.yaw_rate_radps * dt + s.angle_of(static_cast<std::size_t>(i));
    const float dx = std::cos(a), dy = std::sin(a);
    float best = 1e9f;
    for (const Wall& g : walls) {
      if (g.skip_every > 0 && i % g.skip_every == 0) continue;
      const float ex = g.bx - g.ax, ey = g.by - g.ay;
      const float den = dx * ey - dy * ex;
      if (std::fabs(den) < 1e-9f) continue;
      const float wx = g.ax - px, wy = g.ay - py;
      const float t1 = (wx * ey - wy * ex) / den, u = (wx * dy - wy * dx) / den;
      if (t1 > 0.02f && u >= 0 && u <= 1 && t1 < best) best = t1;
    }
    s.range_mm[static_cast<std::size_t>(i)] = best < 29.0f ? static_cast<uint16_t>(std::lround(best * 1000)) : 0;
  }
  return s;
}

inline LaserScan cast_scan(const Pose2& pose, const std::vector<Wall>& walls, int beams = 1081,
                           float fov = 4.71238898f, TimeUs t = {}) {
  return cast_sweep(pose, SweepMotion{}, walls, beams, fov, t);
}

inline scan_matching::ScanPoints to_points(const LaserScan& s) {
  scan_matching::ScanPoints p;
  p.angle_step_rad = std::fabs(s.angle_step_rad);
  for (uint16_t i = 0; i < s.beam_count; ++i) {
    const uint16_t r = s.range_mm[i];
    if (!LaserScan::is_return(r)) continue;
    const float a = s.angle_of(i);
    p.x[p.count] = r * 1e-3f * std::cos(a);
    p.y[p.count] = r * 1e-3f * std::sin(a);
    p.range_mm[p.count] = r;
    p.beam[p.count] = i;
    ++p.count;
  }
  return p;
}

inline std::vector<Wall> room() {
  return {{-3, -2, 3, -2}, {3, -2, 3, 2}, {3, 2, 0.5f, 2}, {-0.5f, 2, -3, 2}, {-3, 2, -3, -2},
          {1.2f, 0.3f, 1.5f, 0.3f}, {1.5f, 0.3f, 1.5f, 0.6f}, {1.2f, 0.6f, 1.5f, 0.6f}, {1.2f, 0.3f, 1.2f, 0.6f}};
}

}  // namespace kestrel::test
