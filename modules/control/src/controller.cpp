#include "kestrel/control/controller.hpp"

#include <algorithm>
#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel::control {
namespace {

bool finite_nav(const NavState& n) {
  return n.position_m.allFinite() && n.velocity_mps.allFinite() && std::isfinite(n.heading_rad);
}

bool finite_setpoint(const GuidanceSetpoint& s) {
  return s.position_m.allFinite() && s.velocity_mps.allFinite() && std::isfinite(s.heading_rad);
}

float clip(float v, float limit, uint32_t& flags, uint32_t flag) {
  if (v > limit) {
    flags |= flag;
    return limit;
  }
  if (v < -limit) {
    flags |= flag;
    return -limit;
  }
  return v;
}

float clamp_to(float v, float lo, float hi, uint32_t& flags, uint32_t flag) {
  if (v > hi || v < lo) flags |= flag;
  return std::clamp(v, lo, hi);
}

}  // namespace

Controller::Controller(const ControllerParams& params) {
  if (!ok(set_params(params))) params_ = default_controller_params();
}

Status Controller::set_params(const ControllerParams& params) {
  const Status s = validate(params);
  if (ok(s)) params_ = params;
  return s;
}

ControlOutput Controller::safe_output(TimeUs stamp, uint32_t flags) const {
  ControlOutput out;
  out.command.stamp = stamp;
  out.command.thrust = std::clamp(params_.model.hover_thrust(), params_.min_thrust, params_.max_thrust);
  out.flags = flags;
  return out;
}

ControlOutput Controller::step(const NavState& nav, const GuidanceSetpoint& sp) const {
  if (!nav.valid || !finite_nav(nav)) return safe_output(nav.stamp, control_flag::kInvalidNav);
  if (!finite_setpoint(sp)) return safe_output(nav.stamp, control_flag::kInvalidSetpoint);
  const ControllerParams& p = params_;
  uint32_t flags = 0;

  const bool position_mode = sp.mode == GuidanceSetpoint::Mode::kPosition;
  Eigen::Vector3f e_p = nav.position_m - sp.position_m;
  if (!position_mode) e_p.x() = e_p.y() = 0.0f;
  Eigen::Vector3f e_v = nav.velocity_mps - sp.velocity_mps;
  if (!position_mode) e_v.z() = nav.velocity_mps.z();  // altitude hold: no vertical feed-forward
  // Clip the horizontal errors by their norm (keeps the direction), the vertical one alone.
  const float n_p = e_p.head<2>().norm();
  if (n_p > p.max_position_error_m) {
    e_p.head<2>() *= p.max_position_error_m / n_p;
    flags |= control_flag::kClippedError;
  }
  const float n_v = e_v.head<2>().norm();
  if (n_v > p.max_velocity_error_mps) {
    e_v.head<2>() *= p.max_velocity_error_mps / n_v;
    flags |= control_flag::kClippedError;
  }
  e_p.z() = clip(e_p.z(), p.max_position_error_m, flags, control_flag::kClippedError);
  e_v.z() = clip(e_v.z(), p.max_velocity_error_mps, flags, control_flag::kClippedError);

  // World to body with the heading.
  const float c = std::cos(nav.heading_rad), s = std::sin(nav.heading_rad);
  const float ex = c * e_p.x() + s * e_p.y(), ey = -s * e_p.x() + c * e_p.y();
  const float evx = c * e_v.x() + s * e_v.y(), evy = -s * e_v.x() + c * e_v.y();

  ControlOutput out;
  out.command.stamp = nav.stamp;
  // Each gain maps the error to a command directly; the offset is cancelled through the model.
  const float pitch = -(p.gain_x_p * ex + p.gain_x_d * evx) + p.model.pitch.command_for(0.0f);
  const float roll = -(p.gain_y_p * ey + p.gain_y_d * evy) + p.model.roll.command_for(0.0f);
  const float thrust = -(p.gain_z_p * e_p.z() + p.gain_z_d * e_v.z()) + p.model.thrust.command_for(0.0f);
  const float yaw_rate = -p.gain_yaw * angle_diff(nav.heading_rad, sp.heading_rad) + p.model.yaw.command_for(0.0f);
  out.command.pitch_rad = clip(pitch, p.max_tilt_rad, flags, control_flag::kSatPitch);
  out.command.roll_rad = clip(roll, p.max_tilt_rad, flags, control_flag::kSatRoll);
  out.command.thrust = clamp_to(thrust, p.min_thrust, p.max_thrust, flags, control_flag::kSatThrust);
  out.command.yaw_rate_radps = clip(yaw_rate, p.max_yaw_rate_radps, flags, control_flag::kSatYawRate);
  out.flags = flags;
  const AttitudeSetpoint& a = out.command;
  if (!std::isfinite(a.pitch_rad) || !std::isfinite(a.roll_rad) || !std::isfinite(a.thrust) ||
      !std::isfinite(a.yaw_rate_radps)) {
    return safe_output(nav.stamp, control_flag::kInvalidNav);
  }
  return out;
}

}  // namespace kestrel::control
