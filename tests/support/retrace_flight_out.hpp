#pragma once
// The flight out that srt.retrace's tests and its benchmark give an SRT-Star planner, 0.25 m a
// pose: east along y = 0 to x = 22, a narrow loop north (to y = 8, back down at x = 20 to
// y = 0.4, every cell of it flown), then
// Outward::kLawnMower: east again to x = 26 and a lawn-mower over x 26..38, y 0.4..10 with
// lines 2 m apart, so that where it ends everything in reach is flown while the rooms beside the
// start (y 2..10, x under 19) are not.
// Outward::kLong: east to x = 23.5 and a lawn-mower over x 23.5..30.5, y -27..27 with lines 1 m
// apart (more than kRetraceLoopM: no place is passed twice), some 860 trail points, the
// history nearly full, inside the visited grid; the rooms beside the start reach y 27 and -27.
#include <cmath>
#include <cstddef>
#include <vector>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/time.hpp"
#include "planner_settle.hpp"
#include "synthetic_world.hpp"

namespace kestrel::test {

enum class Outward { kLawnMower, kLong };

inline std::vector<Point2> retrace_flight_out(Outward shape = Outward::kLawnMower) {
  const bool wide = shape == Outward::kLong;
  const float x0 = wide ? 23.5f : 26.0f, pitch = wide ? 1.0f : 2.0f;
  const float low = wide ? -27.0f : 0.4f, high = wide ? 27.0f : 10.0f;
  const int lines = wide ? 8 : 7;
  std::vector<Point2> corners = {{0, 0}, {22, 0}, {22, 8}, {20, 8}, {20, 0.4f}, {x0, 0.4f}};
  for (int line = 0; line < lines; ++line) {
    const float x = x0 + pitch * static_cast<float>(line);
    const bool up = line % 2 == 0;
    if (line > 0) corners.push_back({x, up ? low : high});
    corners.push_back({x, up ? high : low});
  }
  std::vector<Point2> poses;
  for (std::size_t c = 0; c + 1 < corners.size(); ++c) {
    const Point2 a = corners[c], b = corners[c + 1];
    const int steps = static_cast<int>(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / 0.25f));
    for (int k = 0; k < steps; ++k) {
      const float f = static_cast<float>(k) / static_cast<float>(steps);
      poses.push_back({a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)});
    }
  }
  poses.push_back(corners.back());
  return poses;
}

// The scans of that flight (URG-04LX, every return 1 m away): at the start, open only to the
// west, behind the flight, so no waypoint is reached on the way out; and everywhere after it,
// enclosed, so that a fresh tree grown where it ends runs out at once.
inline LaserScan retrace_start_scan() {
  LaserScan s = uniform_scan(LaserModel::urg04lx(), 1000);
  for (int i = 0; i < s.beam_count; ++i)
    if (std::fabs(s.angle_of(i)) < 0.6) s.range_mm[i] = range_code::kNoReturn;
  return s;
}
inline LaserScan retrace_enclosed_scan() { return uniform_scan(LaserModel::urg04lx(), 1000); }

// The flight's start: the root grown at the origin facing west from retrace_start_scan().
template <typename Planner, typename Each>
void retrace_take_start(Planner& planner, bool& fresh, Each&& each) {
  update_until_settled(planner, {0, 0, static_cast<float>(M_PI)}, retrace_start_scan(), TimeUs{}, fresh, each);
}

// The flight out after the start: one update a pose of retrace_flight_out(shape), 0.1 s apart,
// facing east, every scan enclosed (no waypoint is reached on the way, so no call is sliced).
template <typename Planner, typename Each>
void retrace_fly_out(Planner& planner, Outward shape, bool& fresh, Each&& each) {
  const LaserScan enclosed = retrace_enclosed_scan();
  TimeUs t{};
  for (const Point2& p : retrace_flight_out(shape)) {
    t += Duration::from_ms(100);
    each(planner.update({p.x, p.y, 0}, enclosed, t, fresh));
  }
}

}  // namespace kestrel::test
