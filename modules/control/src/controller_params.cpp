#include "kestrel/control/controller_params.hpp"

#include <cmath>

#include "kestrel/control/lqr.hpp"

namespace kestrel::control {

Result<ControllerParams> design_controller(const VehicleModel& model, const LqrWeights& w, double dt,
                                           const ControllerParams& limits_from) {
  if (!ok(validate(model))) return Status::kInvalidArgument;
  if (!(dt > 0.0 && dt < 1.0)) return Status::kInvalidArgument;
  ControllerParams p = limits_from;
  p.model = model;
  auto axis = [&](double k, double q_p, double q_v, double r, float& kp, float& kd) {
    const DiscreteModel2 m = double_integrator(dt, k);
    const Eigen::Matrix2d Q = Eigen::Vector2d(q_p, q_v).asDiagonal();
    const Eigen::Matrix<double, 1, 1> R(r);
    Eigen::Matrix<double, 1, 2> K = Eigen::Matrix<double, 1, 2>::Zero();
    const Status s = solve_dlqr<2, 1>(m.A, m.B, Q, R, K);
    kp = static_cast<float>(K(0));
    kd = static_cast<float>(K(1));
    return s;
  };
  Status s = axis(model.pitch.k, w.q_pos_xy, w.q_vel_xy, w.r_tilt, p.gain_x_p, p.gain_x_d);
  if (ok(s)) s = axis(model.roll.k, w.q_pos_xy, w.q_vel_xy, w.r_tilt, p.gain_y_p, p.gain_y_d);
  if (ok(s)) s = axis(model.thrust.k, w.q_pos_z, w.q_vel_z, w.r_thrust, p.gain_z_p, p.gain_z_d);
  if (ok(s)) {
    // Heading: first order, psi_{n+1} = psi_n + k dt u.
    const Eigen::Matrix<double, 1, 1> A(1.0), B(model.yaw.k * dt), Q(w.q_yaw), R(w.r_yaw);
    Eigen::Matrix<double, 1, 1> K = Eigen::Matrix<double, 1, 1>::Zero();
    s = solve_dlqr<1, 1>(A, B, Q, R, K);
    p.gain_yaw = static_cast<float>(K(0));
  }
  if (!ok(s)) return s;
  return p;
}

ControllerParams default_controller_params() {
  const Result<ControllerParams> r = design_controller(VehicleModel{}, LqrWeights{}, 0.025);
  return r.ok() ? r.value() : ControllerParams{};
}

std::array<params::ParamField, kControllerParamCount> controller_param_fields(ControllerParams& p) {
  return {{
      {"k_pitch", &p.model.pitch.k, 1e-3f, 100.0f, "m/s^2/rad", "eq. 1: x''_b = k_pitch u_pitch + b_pitch"},
      {"b_pitch", &p.model.pitch.b, -20.0f, 20.0f, "m/s^2", "eq. 1 offset, body x"},
      {"k_roll", &p.model.roll.k, 1e-3f, 100.0f, "m/s^2/rad", "eq. 1: y''_b = k_roll u_roll + b_roll"},
      {"b_roll", &p.model.roll.b, -20.0f, 20.0f, "m/s^2", "eq. 1 offset, body y"},
      {"k_thrust", &p.model.thrust.k, 1e-3f, 200.0f, "m/s^2", "eq. 1: z'' = k_thrust u_thrust + b_thrust"},
      {"b_thrust", &p.model.thrust.b, -100.0f, 100.0f, "m/s^2", "eq. 1 offset, vertical"},
      {"k_yaw", &p.model.yaw.k, 1e-3f, 10.0f, "1", "eq. 1: psi' = k_yaw u_yaw + b_yaw"},
      {"b_yaw", &p.model.yaw.b, -5.0f, 5.0f, "rad/s", "eq. 1 offset, yaw rate"},
      {"gain_x_p", &p.gain_x_p, 1e-4f, 10.0f, "rad/m", "LQR pitch per m of body-x error"},
      {"gain_x_d", &p.gain_x_d, 1e-4f, 10.0f, "rad/(m/s)", "LQR pitch per m/s of body-x velocity error"},
      {"gain_y_p", &p.gain_y_p, 1e-4f, 10.0f, "rad/m", "LQR roll per m of body-y error"},
      {"gain_y_d", &p.gain_y_d, 1e-4f, 10.0f, "rad/(m/s)", "LQR roll per m/s of body-y velocity error"},
      {"gain_z_p", &p.gain_z_p, 1e-4f, 10.0f, "1/m", "LQR thrust per m of height error"},
      {"gain_z_d", &p.gain_z_d, 1e-4f, 10.0f, "1/(m/s)", "LQR thrust per m/s of vertical velocity error"},
      {"gain_yaw", &p.gain_yaw, 1e-4f, 50.0f, "1/s", "LQR yaw rate per rad of heading error"},
      {"max_tilt_rad", &p.max_tilt_rad, 0.01f, 0.7f, "rad", "limit of |pitch| and |roll|"},
      {"min_thrust", &p.min_thrust, 0.0f, 1.0f, "1", "lowest thrust command"},
      {"max_thrust", &p.max_thrust, 0.0f, 1.0f, "1", "highest thrust command"},
      {"max_yaw_rate_radps", &p.max_yaw_rate_radps, 0.01f, 10.0f, "rad/s", "limit of |yaw rate|"},
      {"max_position_error_m", &p.max_position_error_m, 0.01f, 100.0f, "m", "position errors are clipped to this"},
      {"max_velocity_error_mps", &p.max_velocity_error_mps, 0.01f, 100.0f, "m/s",
       "velocity errors are clipped to this"},
  }};
}

Status validate(const ControllerParams& p) {
  ControllerParams copy = p;
  if (params::check_ranges(controller_param_fields(copy)) != Status::kOk) return Status::kInvalidArgument;
  if (!(p.min_thrust < p.max_thrust)) return Status::kInvalidArgument;
  const float hover = p.model.hover_thrust();
  if (!(hover > p.min_thrust && hover < p.max_thrust)) return Status::kInvalidArgument;
  return validate(p.model);
}

Status load_controller_params(const char* path, ControllerParams& out, params::ParamError& error) {
  return params::load_params_struct(
      path, out, controller_param_fields, [](const ControllerParams& p) { return validate(p); },
      "inconsistent controller parameters: need min_thrust < hover thrust (-b_thrust/k_thrust) < max_thrust", error);
}

}  // namespace kestrel::control
