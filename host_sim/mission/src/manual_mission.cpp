#include "kestrel/sim/manual_mission.hpp"

#include "kestrel/sim/simulation.hpp"

namespace kestrel::sim {

Status ManualMission::start(Simulation& sim) {
  next_ = 0;
  disarmed_ = false;
  current_ = AttitudeSetpoint{};
  return sim.flight_controller().arm(true);
}

MissionState ManualMission::tick(Simulation& sim) {
  // Compare in whole microseconds: a script time must switch at exactly one tick.
  const TimeUs t = sim.clock().now();
  hal::FlightController& fc = sim.flight_controller();
  while (next_ < script_.steps.size() && TimeUs::from_s(script_.steps[next_].t_s) <= t) {
    const ScriptStep& st = script_.steps[next_++];
    if (st.disarm) {
      (void)fc.arm(false);
      disarmed_ = true;
    } else {
      current_ = st.setpoint;
    }
  }
  if (!disarmed_) {
    current_.stamp = sim.clock().now();
    if (fc.send(current_) != Status::kOk) ++rejected_;
  }
  FlightStatus status;
  while (fc.poll_status(status) == Status::kOk) {
  }
  return MissionState::kRunning;
}

void ManualMission::metrics(MissionMetrics& out) const {
  out.emplace_back("manual.commands_rejected", static_cast<double>(rejected_));
  out.emplace_back("manual.script_steps", static_cast<double>(script_.steps.size()));
}

}  // namespace kestrel::sim
