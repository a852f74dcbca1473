#include "kestrel/sim/fake_autopilot.hpp"

#include <cmath>

namespace kestrel::sim {

FakeAutopilot::FakeAutopilot(const TimeSource& clock, Duration command_delay, Duration status_period)
    : clock_(clock), delay_(command_delay), status_period_(status_period) {}

Status FakeAutopilot::arm(bool armed) {
  armed_ = armed;
  if (!armed) {
    line_.clear();
    active_ = AttitudeSetpoint{};
  }
  return Status::kOk;
}

Status FakeAutopilot::send(const AttitudeSetpoint& sp) {
  if (!std::isfinite(sp.pitch_rad) || !std::isfinite(sp.roll_rad) || !std::isfinite(sp.thrust) ||
      !std::isfinite(sp.yaw_rate_radps))
    return Status::kNotFinite;
  return line_.push(clock_.now() + delay_, sp) ? Status::kOk : Status::kCapacityExceeded;
}

Status FakeAutopilot::poll_status(FlightStatus& out) {
  if (!status_fresh_) return Status::kNoData;
  out = status_;
  status_fresh_ = false;
  return Status::kOk;
}

const AttitudeSetpoint& FakeAutopilot::active(TimeUs now) {
  line_.release(now, active_);
  return active_;
}

void FakeAutopilot::update_status(const VehicleState& s) {
  if (s.stamp < next_status_) return;
  status_.stamp = s.stamp;
  status_.armed = armed_;
  status_.battery_v = 11.1f;
  status_.roll_rad = static_cast<float>(s.roll_rad);  // right-handed, as FlightStatus says
  status_.pitch_rad = static_cast<float>(s.pitch_rad);
  status_.yaw_rad = static_cast<float>(s.yaw_rad);
  status_fresh_ = true;
  next_status_ = s.stamp + status_period_;
}

}  // namespace kestrel::sim
