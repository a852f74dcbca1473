#include "kestrel/exploration/blend_explorer.hpp"

#include <cmath>

namespace kestrel::exploration {

Status BlendExplorer::plan(const Pose2& pose, const LaserScan& scan, TimeUs now, GuidanceSetpoint& out,
                           float& heading_target) {
  // Algorithm 1, line 1.
  const Eigen::Vector2f v_wf = wall_following_velocity(scan, pose.theta);
  // Lines 2-10.
  bool new_waypoint = false;
  if (Status st = planner_.update(pose, scan, now, new_waypoint); st != Status::kOk) return st;
  const Point2 wp = planner_.waypoint();
  status_.has_target = planner_.has_waypoint();
  status_.target = wp;
  // Lines 11-13: equations 5, 6 and 1.
  const float dx = wp.x - pose.x, dy = wp.y - pose.y;
  const Eigen::Vector2f v_fr{params_.guidance.gain_fr * dx, params_.guidance.gain_fr * dy};
  status_.v_fr = v_fr;
  (void)planner_.heading_target(pose, heading_target);  // else the heading command stays
  const Eigen::Vector2f v = v_wf + v_fr;
  out.mode = GuidanceSetpoint::Mode::kVelocity;
  out.velocity_mps = {v.x(), v.y(), 0.0f};
  return Status::kOk;
}

}  // namespace kestrel::exploration
