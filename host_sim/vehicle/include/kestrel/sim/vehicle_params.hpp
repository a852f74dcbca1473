#pragma once
// Parameters of the simulated quadrotor, defaults close to an AscTec Hummingbird under its
// attitude-stabilising autopilot (paper 000, section 4 and equation 1).
#include <cstddef>

#include "kestrel/sim/config_file.hpp"

namespace kestrel::sim {

// Every field has a valid range (validate() checks it, NaN-safe), wide enough for any indoor
// multirotor and narrow enough that the physics stays finite: a b_thrust of 1e200 or a
// gust_std_mps2 of 1e10 flew NaN and absurd metrics.
struct VehicleParams {
  // Equation 1: body-frame acceleration = k * u + b.
  double k_pitch = 9.81;    // m/s² per rad of pitch (small-angle g·tan); (0, 100]
  double b_pitch = 0;       // m/s²; [-10, 10]
  double k_roll = 9.81;     // m/s² per rad of roll; (0, 100]
  double b_roll = 0;        // m/s²; [-10, 10]
  double k_thrust = 19.62;  // m/s² per unit of normalised thrust: hover at 0.5; (0, 200]
  double b_thrust = -9.81;  // m/s² (gravity); [-50, 50]
  double k_yaw = 1.0;       // (rad/s) per (rad/s) of yaw-rate command; (0, 10]
  double b_yaw = 0;         // rad/s; [-10, 10]
  // The autopilot's attitude loop, as a first-order lag from command to attitude.
  double attitude_tau_s = 0.08;     // s; 0 = instantaneous; [0, 10]
  double max_tilt_rad = 0.5;        // commands are clamped to ±this; (0, 1.5)
  double max_yaw_rate_radps = 3.0;  // (0, 20]
  // Gusts: an Ornstein-Uhlenbeck horizontal acceleration disturbance (0 = off).
  double gust_std_mps2 = 0;  // [0, 20]: 2 g of gusts is already a storm indoors
  double gust_tau_s = 2.0;   // (0, 3600]
  // The body for collisions: a cylinder around the rotors, centred on the vehicle.
  double body_radius_m = 0.27;  // Hummingbird: ~0.54 m rotor tip to tip; (0, 5]
  double body_height_m = 0.12;  // (0, 5]
  // Fixed integration step.
  double step_s = 0.001;

  // Binds every field to "vehicle.<name>" for ConfigFile.
  static constexpr std::size_t kBindingCount = 16;
  void bindings(ConfigBinding (&out)[kBindingCount]);
  // "" or the reason the parameters are unusable.
  const char* validate() const;
};

}  // namespace kestrel::sim
