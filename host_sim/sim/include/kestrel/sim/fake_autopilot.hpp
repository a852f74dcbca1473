#pragma once
// The autopilot (level 1 of paper 000, Figure 4) behind hal::FlightController: set-points go
// through a CommandDelayLine before they reach the vehicle model; status (armed, attitude)
// comes back at a fixed rate. Disarming cuts the motors at once (a safety action is not
// delayed); arming takes effect at once too.
#include "kestrel/core/time.hpp"
#include "kestrel/hal/flight_controller.hpp"
#include "kestrel/sim/command_delay_line.hpp"
#include "kestrel/sim/vehicle.hpp"

namespace kestrel::sim {

class FakeAutopilot final : public hal::FlightController {
 public:
  static constexpr std::size_t kDelayCapacity = 512;

  FakeAutopilot(const TimeSource& clock, Duration command_delay, Duration status_period);

  Status arm(bool armed) override;
  // kNotFinite for NaN/inf fields, kCapacityExceeded when the delay line is full.
  Status send(const AttitudeSetpoint& setpoint) override;
  Status poll_status(FlightStatus& out) override;

  // Simulation side: the set-point in force at `now`, and the status at the vehicle's state.
  const AttitudeSetpoint& active(TimeUs now);
  void update_status(const VehicleState& s);
  bool armed() const { return armed_; }
  Duration command_delay() const { return delay_; }

 private:
  const TimeSource& clock_;
  Duration delay_;
  Duration status_period_;
  CommandDelayLine<kDelayCapacity> line_;
  AttitudeSetpoint active_;
  bool armed_ = false;
  FlightStatus status_;
  bool status_fresh_ = false;
  TimeUs next_status_;
};

}  // namespace kestrel::sim
