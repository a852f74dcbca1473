#include "kestrel/exploration/srt_explorer.hpp"

#include <cmath>

namespace kestrel::exploration {

Status SrtExplorer::plan(const Pose2& pose, const LaserScan& scan, TimeUs now, GuidanceSetpoint& out,
                         float& heading_target) {
  bool new_waypoint = false;
  if (Status st = planner_.update(pose, scan, now, new_waypoint); st != Status::kOk) return st;
  const Point2 wp = planner_.waypoint();
  status_.has_target = planner_.has_waypoint();
  status_.target = wp;
  const float dx = wp.x - pose.x, dy = wp.y - pose.y;
  // On top of the waypoint atan2 says nothing, and while the arrival step is worked on the
  // waypoint is the one just reached, a few cm off in any direction: the heading command
  // stays where it is (turning towards it would leave the laser facing anywhere when the
  // next waypoint comes).
  if (!planner_.busy() && dx * dx + dy * dy > 1e-4f) heading_target = std::atan2(dy, dx);
  out.mode = GuidanceSetpoint::Mode::kPosition;
  out.position_m = {wp.x, wp.y, 0.0f};
  out.velocity_mps.setZero();
  return Status::kOk;
}

}  // namespace kestrel::exploration
