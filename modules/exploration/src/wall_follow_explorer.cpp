#include "kestrel/exploration/wall_follow_explorer.hpp"

#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel::exploration {

Status WallFollowExplorer::plan(const Pose2& pose, const LaserScan& scan, TimeUs /*now*/, GuidanceSetpoint& out,
                                float& heading_target) {
  Eigen::Vector2f v = wall_following_velocity(scan, pose.theta);
  const float cruise = params_.guidance.cruise_speed_mps;
  const bool wall = status_.field.nearest_beam != 0xFFFFu;
  if (wall) {
    const float bearing = pose.theta + scan.angle_of(status_.field.nearest_beam);
    const float error = static_cast<float>(status_.field.nearest_mm) * 1e-3f - params_.wall.target_range_m;
    v += params_.guidance.wall_hold_gain * error * Eigen::Vector2f{std::cos(bearing), std::sin(bearing)};
  }
  if (cruise > 0.0f) {
    float travel = pose.theta;  // no wall in range: straight on until one is found
    if (wall) travel = wrap_angle(pose.theta + scan.angle_of(status_.field.nearest_beam) + 0.5f * kPi<float>);
    v += cruise * Eigen::Vector2f{std::cos(travel), std::sin(travel)};
    heading_target = travel;
  }
  out.mode = GuidanceSetpoint::Mode::kVelocity;
  out.velocity_mps = {v.x(), v.y(), 0.0f};
  return Status::kOk;
}

}  // namespace kestrel::exploration
