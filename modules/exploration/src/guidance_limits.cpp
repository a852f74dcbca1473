#include "kestrel/exploration/guidance_limits.hpp"

#include <algorithm>
#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel::exploration {

Eigen::Vector2f limit_speed(const Eigen::Vector2f& v, float max_mps) {
  if (!v.allFinite()) return Eigen::Vector2f::Zero();
  const float n = v.norm();
  if (n <= max_mps || n <= 0.0f) return v;
  return v * (max_mps / n);
}

void YawRateLimiter::reset(float heading_rad, TimeUs now) {
  command_ = std::isfinite(heading_rad) ? wrap_angle(heading_rad) : 0.0f;
  last_ = now;
  initialised_ = true;
}

float YawRateLimiter::step(float target_rad, TimeUs now, float max_rate_radps) {
  if (!initialised_) reset(target_rad, now);
  const double dt = (now - last_).seconds();
  if (!(dt > 0.0) || !std::isfinite(target_rad)) {
    if (dt > 0.0) last_ = now;
    return command_;
  }
  last_ = now;
  const float max_turn = max_rate_radps * static_cast<float>(dt);
  const float turn = std::clamp(angle_diff(target_rad, command_), -max_turn, max_turn);
  command_ = wrap_angle(command_ + turn);
  return command_;
}

}  // namespace kestrel::exploration
