#pragma once
// The practical limits of paper 002 section V that shape the commands: a speed limit (the sum
// of many incremental velocities is hard to predict) and a yaw-rate limit on the heading
// command (a new waypoint, above all when backtracking, would otherwise turn the vehicle fast
// enough to hurt scan matching). The waypoint time limit lives in SrtStarPlanner.
#include <Eigen/Core>

#include "kestrel/core/time.hpp"

namespace kestrel::exploration {

// Scales v down to at most max_mps, keeping its direction. Non-finite input gives zero.
Eigen::Vector2f limit_speed(const Eigen::Vector2f& v, float max_mps);

// Moves a heading command towards its target by at most rate * dt per call.
class YawRateLimiter {
 public:
  void reset(float heading_rad, TimeUs now);
  bool initialised() const { return initialised_; }
  // The new command; a time that did not advance leaves the command where it was.
  float step(float target_rad, TimeUs now, float max_rate_radps);
  float command() const { return command_; }

 private:
  float command_ = 0;
  TimeUs last_{};
  bool initialised_ = false;
};

}  // namespace kestrel::exploration
