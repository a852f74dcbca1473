#pragma once
// The attitude-stabilised quadrotor of paper 000, equation 1:
//     ẍ_b = k_φ u_φ + b_φ     ÿ_b = k_ψ u_ψ + b_ψ     z̈ = k_t u_t + b_t     θ̇ = k_θ u_θ + b_θ
// (x_b, y_b: the heading-aligned body frame). The autopilot's attitude loop is a first-order
// lag from the commanded pitch and roll to the actual ones, which drive the accelerations
// and tilt the sensors; optional gusts add a horizontal Ornstein-Uhlenbeck acceleration.
// The floor stops the vehicle (it lands, it does not bounce).
//
// Integration: fixed step (1 ms by default); within a step the acceleration is constant and
// position and velocity are advanced exactly for it, so a constant command reproduces the
// closed-form parabola of equation 1 to rounding.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kestrel/core/messages.hpp"
#include "kestrel/sim/random.hpp"
#include "kestrel/sim/vehicle_params.hpp"

namespace kestrel::sim {

struct VehicleState {
  TimeUs stamp;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();     // world frame, z up
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();   // world frame
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();     // world frame, kinematic
  double roll_rad = 0;    // about body x, right-handed (positive rolls the left side up)
  double pitch_rad = 0;   // about body y (left), right-handed: positive is nose down
  double yaw_rad = 0;     // about world z, counter-clockwise, wrapped to (-pi, pi]
  double yaw_rate_radps = 0;
  Eigen::Vector3d body_rate_radps = Eigen::Vector3d::Zero();  // angular velocity, body frame
  bool on_ground = true;

  // Body-to-world rotation: Rz(yaw) * Ry(pitch) * Rx(roll).
  Eigen::Matrix3d rotation() const;
  Eigen::Quaterniond attitude() const { return Eigen::Quaterniond(rotation()); }
};

class Vehicle {
 public:
  Vehicle(const VehicleParams& params, const VehicleState& initial, Rng gust_rng);

  // Advances one fixed step with set-point `u` (thrust is ignored when `armed` is false: the
  // motors are off). The set-point's own stamp is not used.
  void step(const AttitudeSetpoint& u, bool armed);
  const VehicleState& state() const { return s_; }
  const VehicleParams& params() const { return p_; }
  Duration step_duration() const { return step_; }
  // Stops the vehicle where it is (after a collision): velocity and acceleration zero.
  void freeze();
  // Advances time by one step without moving (a frozen vehicle after the flight ended).
  void idle_step() { s_.stamp += step_; }

 private:
  VehicleParams p_;
  VehicleState s_;
  Rng gust_rng_;
  Duration step_;
  double dt_;
  double alpha_;  // attitude lag per step: 1 - exp(-dt / tau)
  double pitch_cmd_f_ = 0, roll_cmd_f_ = 0;  // lagged commands in equation-1 convention
  Eigen::Vector2d gust_ = Eigen::Vector2d::Zero();
};

}  // namespace kestrel::sim
