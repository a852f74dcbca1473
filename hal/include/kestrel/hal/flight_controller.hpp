#pragma once
// The attitude-stabilising autopilot (level 1, not ours): it takes the set-points of paper 000
// equation 1 (pitch, roll, thrust, yaw rate) and reports its status.
#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::hal {

class FlightController {
 public:
  virtual Status arm(bool armed) = 0;
  virtual Status send(const AttitudeSetpoint& setpoint) = 0;
  // Newest status into `out`: kOk, or kNoData when nothing new has arrived.
  virtual Status poll_status(FlightStatus& out) = 0;

 protected:
  ~FlightController() = default;
};

}  // namespace kestrel::hal
