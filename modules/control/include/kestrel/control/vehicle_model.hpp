#pragma once
// The attitude-stabilised quadrotor as paper 000 equation 1 models it: each degree of freedom
// is a gain and an offset on its command,
//   x''_b = k_pitch u_pitch + b_pitch     y''_b = k_roll u_roll + b_roll
//   z''   = k_thrust u_thrust + b_thrust  psi'  = k_yaw u_yaw + b_yaw
// with accelerations in the body frame (x forward, y left, z up) and the AttitudeSetpoint sign
// conventions (pitch > 0 accelerates along +x body, roll > 0 along +y body).
//
// Nominal defaults, close to an AscTec Hummingbird under its attitude controller: for small
// angles a tilt of u rad gives g u of horizontal acceleration, so k_pitch = k_roll = g; the
// vehicle hovers at half of the normalised thrust and full thrust gives about 2 g, so
// k_thrust = 2 g and b_thrust = -g (hover thrust -b/k = 0.5); the yaw-rate loop follows its
// command one to one. Offsets are zero until identified (ModelFit).
#include "kestrel/core/status.hpp"

namespace kestrel::control {

inline constexpr float kGravity = 9.80665f;

struct AxisModel {
  float k = 1.0f;  // response per unit command (m/s^2 per rad, m/s^2 per unit thrust, 1 for yaw)
  float b = 0.0f;  // offset (m/s^2, or rad/s for yaw)

  // The command that produces `response`; k must be non-zero (validate()).
  float command_for(float response) const { return (response - b) / k; }
};

struct VehicleModel {
  AxisModel pitch{kGravity, 0.0f};           // x''_b per rad
  AxisModel roll{kGravity, 0.0f};            // y''_b per rad
  AxisModel thrust{2.0f * kGravity, -kGravity};  // z'' per unit normalised thrust
  AxisModel yaw{1.0f, 0.0f};                 // psi' per rad/s commanded

  float hover_thrust() const { return thrust.command_for(0.0f); }
};

// Gains must be positive and finite (a zero or reversed gain cannot be controlled), offsets
// finite.
Status validate(const VehicleModel& m);

}  // namespace kestrel::control
