#include "kestrel/core/clear_path.hpp"

#include <algorithm>
#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel {
namespace {
// A return inside the clearance at the start may come this much nearer along the path: a path
// leaving a wall it starts 0.43 m from at a shallow angle passes its next returns a few
// millimetres nearer first.
constexpr float kCloseInToleranceM = 0.05f;
}  // namespace

bool straight_path_clear(const LaserScan& scan, const Pose2& laser, Point2 target, float clearance_m) {
  if (!laser.finite() || !std::isfinite(target.x) || !std::isfinite(target.y) || !(clearance_m > 0.0f) ||
      !std::isfinite(clearance_m) || !scan.fan_well_formed())
    return false;
  const float dx = target.x - laser.x, dy = target.y - laser.y;
  const float length = std::hypot(dx, dy);
  if (length + clearance_m > static_cast<float>(scan.max_range_mm) * 1e-3f) return false;
  if (length < 1e-3f) return true;
  // The path along +x: a beam's direction relative to it.
  const float bearing = angle_diff(std::atan2(dy, dx), laser.theta);
  // The corridor's edges at the target lie atan(c / L) either side of the path's bearing.
  const float spread = std::atan2(clearance_m, length);
  const float last_angle = scan.angle_of(scan.beam_count - 1u);
  const float lo = std::min(scan.first_angle_rad, last_angle), hi = std::max(scan.first_angle_rad, last_angle);
  if (bearing - spread < lo || bearing + spread > hi) return false;
  const float reach_mm = (length + clearance_m) * 1000.0f;
  const float c2 = clearance_m * clearance_m;
  const float near_m = clearance_m + kCloseInToleranceM;
  const float first = scan.first_angle_rad - bearing;
  float c = std::cos(first), s = std::sin(first);
  const float step_c = std::cos(scan.angle_step_rad), step_s = std::sin(scan.angle_step_rad);
  for (std::size_t i = 0; i < scan.beam_count; ++i) {
    const uint16_t r_mm = scan.range_mm[i];
    // A beam that said nothing (deflected, dropped out, too near) along the path's own
    // directions, the cone its corridor fills to the target: the scan cannot vouch for the way.
    // Paper 000's mirror deflects a fixed arc at the fan's edge, which is no more seen than
    // what lies outside the fan.
    if (!LaserScan::is_return(r_mm) && r_mm != range_code::kNoReturn && c > 0.0f &&
        std::fabs(s) * length <= c * clearance_m)
      return false;
    if (LaserScan::is_return(r_mm) && static_cast<float>(r_mm) < reach_mm) {
      const float r = static_cast<float>(r_mm) * 1e-3f;
      const float qx = r * c, qy = r * s;
      // Nearest point of the path: its start when qx <= 0 (left behind), else along it.
      if (qx > 0.0f) {
        const float along = std::min(qx, length);
        const float ex = qx - along;
        const float d2 = ex * ex + qy * qy;
        if (r >= near_m) {
          if (d2 < c2) return false;
        } else {
          // Already within the clearance at the start: the path may not close in on it.
          const float allowed = r - kCloseInToleranceM;
          if (allowed <= 0.0f || d2 < allowed * allowed) return false;
        }
      }
    }
    // Next beam's direction, rotated by the step.
    const float next_c = c * step_c - s * step_s;
    s = s * step_c + c * step_s;
    c = next_c;
  }
  return true;
}

}  // namespace kestrel
