#pragma once
// Parameters of the position controller: the identified model (paper 000 equation 1), the LQR
// gains computed for it, and the command limits; with their parameter-file binding.
// design_controller() computes the gains from the model and the LQR weights: the host tool
// runs it after the model fit and writes the file the firmware loads (load_controller_params).
//
// Gains are in command units per unit of error, for body-frame errors: gain_x_p is rad of
// pitch per metre of x error, gain_z_p normalised thrust per metre, gain_yaw rad/s per rad.
//
// API
//   ControllerParams, LqrWeights
//   Result<ControllerParams> design_controller(model, weights, dt, limits_from)
//   controller_param_fields(p), validate(p), load_controller_params(path, p, error)
#include <array>

#include "kestrel/control/vehicle_model.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/params/param_file.hpp"

namespace kestrel::control {

struct ControllerParams {
  VehicleModel model;
  // LQR gains. Zero here, which validate() refuses: default_controller_params() designs them
  // for the nominal model (design_controller() with LqrWeights{} at 25 ms).
  float gain_x_p = 0.0f;   // rad/m
  float gain_x_d = 0.0f;   // rad/(m/s)
  float gain_y_p = 0.0f;   // rad/m
  float gain_y_d = 0.0f;   // rad/(m/s)
  float gain_z_p = 0.0f;   // 1/m (normalised thrust)
  float gain_z_d = 0.0f;   // 1/(m/s)
  float gain_yaw = 0.0f;   // (rad/s)/rad
  // Limits.
  float max_tilt_rad = 0.25f;        // rad: |pitch| and |roll| commands
  float min_thrust = 0.25f;          // normalised
  float max_thrust = 0.85f;          // normalised
  float max_yaw_rate_radps = 1.0f;   // rad/s
  float max_position_error_m = 1.5f; // m: larger errors are clipped (limits the approach speed)
  float max_velocity_error_mps = 2.0f;  // m/s
};

// Weights of the quadratic cost, per axis: q_p e_p^2 + q_v e_v^2 + r u^2 with u in command units.
struct LqrWeights {
  double q_pos_xy = 4.0, q_vel_xy = 1.0, r_tilt = 40.0;
  double q_pos_z = 4.0, q_vel_z = 1.0, r_thrust = 4.0;
  double q_yaw = 1.0, r_yaw = 1.0;
};

// Gains for `model` sampled at dt; limits and the model copied into the result.
Result<ControllerParams> design_controller(const VehicleModel& model, const LqrWeights& weights, double dt,
                                           const ControllerParams& limits_from = {});
// The default parameters: design_controller(VehicleModel{}, LqrWeights{}, 0.025).
ControllerParams default_controller_params();

inline constexpr std::size_t kControllerParamCount = 21;
std::array<params::ParamField, kControllerParamCount> controller_param_fields(ControllerParams& p);
Status validate(const ControllerParams& p);
Status load_controller_params(const char* path, ControllerParams& out, params::ParamError& error);

}  // namespace kestrel::control
