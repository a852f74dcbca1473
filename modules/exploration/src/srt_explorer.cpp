#include "kestrel/exploration/srt_explorer.hpp"

namespace kestrel::exploration {

Status SrtExplorer::plan(const Pose2& pose, const LaserScan& scan, TimeUs now, GuidanceSetpoint& out,
                         float& heading_target) {
  bool new_waypoint = false;
  if (Status st = planner_.update(pose, scan, now, new_waypoint); st != Status::kOk) return st;
  const Point2 wp = planner_.waypoint();
  status_.has_target = planner_.has_waypoint();
  status_.target = wp;
  (void)planner_.heading_target(pose, heading_target);  // else the heading command stays
  out.mode = GuidanceSetpoint::Mode::kPosition;
  out.position_m = {wp.x, wp.y, 0.0f};
  out.velocity_mps.setZero();
  return Status::kOk;
}

}  // namespace kestrel::exploration
