#pragma once
// The position, velocity and heading controller of paper 000 section 4: LQR state feedback on
// the second-order model of equation 1, with the model's offsets cancelled by feed-forward.
// Steps, once per control period:
//   1. check the inputs: an invalid or non-finite NavState or set-point gives the safe output
//      (level, hover thrust, no yaw rate) and a flag, never NaN; so does a finite input whose
//      error overflows float (e.g. positions of +-3e38 m), flagged kInvalidNav;
//   2. world-frame errors: position (clipped to max_position_error_m; zero in x, y for
//      kVelocity mode, which tracks velocity_mps and holds position_m.z()) and velocity
//      (against the set-point's velocity, the feed-forward of kPosition mode);
//   3. rotate the horizontal errors into the body frame with the estimated heading;
//   4. u = command_for(-K e) per axis: pitch from body x, roll from body y, thrust from z (which
//      also holds the altitude), yaw rate from the wrapped heading error;
//   5. saturate pitch and roll (max_tilt_rad), thrust (min/max_thrust), yaw rate, and flag it.
// Conventions of AttitudeSetpoint: pitch > 0 accelerates along +x body, roll > 0 along +y body.
//
// API
//   Controller(params)                           params validated; invalid ones -> defaults + flag
//   Status set_params(params)
//   ControlOutput step(const NavState&, const GuidanceSetpoint&)
//   ControlOutput safe_output(stamp)              what step() returns on bad input
#include <cstdint>

#include "kestrel/control/controller_params.hpp"
#include "kestrel/core/messages.hpp"

namespace kestrel::control {

namespace control_flag {
inline constexpr uint32_t kInvalidNav = 1u << 0;       // nav.valid false or non-finite: safe output
inline constexpr uint32_t kInvalidSetpoint = 1u << 1;  // non-finite set-point: safe output
inline constexpr uint32_t kSatPitch = 1u << 2;
inline constexpr uint32_t kSatRoll = 1u << 3;
inline constexpr uint32_t kSatThrust = 1u << 4;
inline constexpr uint32_t kSatYawRate = 1u << 5;
inline constexpr uint32_t kClippedError = 1u << 6;     // position or velocity error clipped
}  // namespace control_flag

struct ControlOutput {
  AttitudeSetpoint command;
  uint32_t flags = 0;  // control_flag bits
};

class Controller {
 public:
  explicit Controller(const ControllerParams& params = default_controller_params());
  Status set_params(const ControllerParams& params);
  const ControllerParams& params() const { return params_; }

  ControlOutput step(const NavState& nav, const GuidanceSetpoint& setpoint) const;
  ControlOutput safe_output(TimeUs stamp, uint32_t flags) const;

 private:
  ControllerParams params_;
};

}  // namespace kestrel::control
