#include "kestrel/sim/vehicle.hpp"

#include <algorithm>
#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel::sim {

Eigen::Matrix3d VehicleState::rotation() const {
  return (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Vehicle::Vehicle(const VehicleParams& params, const VehicleState& initial, Rng gust_rng)
    : p_(params), s_(initial), gust_rng_(gust_rng) {
  step_ = Duration::from_us(static_cast<int64_t>(std::llround(p_.step_s * 1e6)));
  if (step_.us <= 0) step_ = Duration::from_us(1000);
  dt_ = step_.seconds();
  alpha_ = p_.attitude_tau_s > 0 ? 1.0 - std::exp(-dt_ / p_.attitude_tau_s) : 1.0;
  // Equation-1 convention: positive pitch accelerates +x (nose down), positive roll +y,
  // which is a negative right-handed roll about x.
  pitch_cmd_f_ = s_.pitch_rad;
  roll_cmd_f_ = -s_.roll_rad;
}

void Vehicle::freeze() {
  s_.velocity_mps.setZero();
  s_.accel_mps2.setZero();
  s_.body_rate_radps.setZero();
  s_.yaw_rate_radps = 0;
}

void Vehicle::step(const AttitudeSetpoint& u_in, bool armed) {
  auto finite_or_zero = [](float v) { return std::isfinite(v) ? static_cast<double>(v) : 0.0; };
  const double tilt = p_.max_tilt_rad;
  double u_pitch = std::clamp(finite_or_zero(u_in.pitch_rad), -tilt, tilt);
  double u_roll = std::clamp(finite_or_zero(u_in.roll_rad), -tilt, tilt);
  double u_thrust = std::clamp(finite_or_zero(u_in.thrust), 0.0, 1.0);
  double u_yaw = std::clamp(finite_or_zero(u_in.yaw_rate_radps), -p_.max_yaw_rate_radps,
                            p_.max_yaw_rate_radps);
  if (!armed) u_pitch = u_roll = u_thrust = u_yaw = 0;

  const Eigen::Matrix3d r_before = s_.rotation();
  pitch_cmd_f_ += (u_pitch - pitch_cmd_f_) * alpha_;
  roll_cmd_f_ += (u_roll - roll_cmd_f_) * alpha_;

  const double az = armed ? p_.k_thrust * u_thrust + p_.b_thrust : -9.81;
  const bool grounded = s_.position_m.z() <= 0 && az <= 0;
  double yaw_rate = armed ? p_.k_yaw * u_yaw + p_.b_yaw : 0.0;
  if (grounded) yaw_rate = 0;  // standing on the floor: friction holds it

  // Body-frame accelerations in the heading frame, rotated with the heading at mid-step.
  const double axb = p_.k_pitch * pitch_cmd_f_ + p_.b_pitch;
  const double ayb = p_.k_roll * roll_cmd_f_ + p_.b_roll;
  const double yaw_mid = s_.yaw_rad + 0.5 * yaw_rate * dt_;
  const double c = std::cos(yaw_mid), sn = std::sin(yaw_mid);
  Eigen::Vector3d a(c * axb - sn * ayb, sn * axb + c * ayb, az);
  if (p_.gust_std_mps2 > 0) {
    // Exact OU discretisation keeps the stationary standard deviation at gust_std_mps2.
    const double phi = std::exp(-dt_ / p_.gust_tau_s);
    const double q = p_.gust_std_mps2 * std::sqrt(1 - phi * phi);
    gust_.x() = phi * gust_.x() + q * gust_rng_.gaussian();
    gust_.y() = phi * gust_.y() + q * gust_rng_.gaussian();
    a.x() += gust_.x();
    a.y() += gust_.y();
  }
  if (grounded) a.setZero();

  s_.position_m += s_.velocity_mps * dt_ + 0.5 * a * dt_ * dt_;
  s_.velocity_mps += a * dt_;
  s_.accel_mps2 = a;
  s_.on_ground = grounded;
  if (s_.position_m.z() < 0) {  // touch-down: the floor absorbs the motion
    s_.position_m.z() = 0;
    s_.velocity_mps.setZero();
    s_.accel_mps2.setZero();
    s_.on_ground = true;
  }
  if (s_.on_ground) {
    s_.velocity_mps.setZero();
  }
  s_.yaw_rad = wrap_angle(s_.yaw_rad + yaw_rate * dt_);
  s_.yaw_rate_radps = yaw_rate;
  s_.pitch_rad = s_.on_ground ? 0.0 : pitch_cmd_f_;
  s_.roll_rad = s_.on_ground ? 0.0 : -roll_cmd_f_;
  s_.stamp += step_;

  // Body rates from the attitude change over the step (exact for the step's rotation).
  const Eigen::Matrix3d dr = r_before.transpose() * s_.rotation();
  const Eigen::AngleAxisd aa(dr);
  s_.body_rate_radps = aa.axis() * (aa.angle() / dt_);
  if (!std::isfinite(s_.body_rate_radps.x())) s_.body_rate_radps.setZero();
}

}  // namespace kestrel::sim
