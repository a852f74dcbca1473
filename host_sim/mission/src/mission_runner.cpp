#include "kestrel/sim/mission_runner.hpp"

namespace kestrel::sim {

RunResult run_mission(Simulation& sim, Mission& mission, Duration duration, const RunHooks& hooks) {
  const std::function<void(double)>& progress = hooks.progress;
  RunResult r;
  r.status = mission.start(sim);
  if (r.status != Status::kOk) {
    r.end = sim.now();
    r.message = std::string("mission '") + mission.name() + "' did not start: " + to_string(r.status);
    if (const std::string why = mission.failure(); !why.empty()) r.message += " (" + why + ")";
    return r;
  }
  const TimeUs start = sim.now();
  const TimeUs stop = start + duration;
  const Duration tick = mission.tick_period().us > 0 ? mission.tick_period() : Duration::from_ms(10);
  TimeUs next_progress = start + Duration::from_s(1.0);
  if (hooks.loop_begins) hooks.loop_begins();
  // The first tick is at the start time, then one every tick period after each step.
  r.state = mission.tick(sim);
  while (r.state == MissionState::kRunning && sim.now() < stop) {
    TimeUs next = sim.now() + tick;
    if (next > stop) next = stop;
    (void)sim.step_until(next);
    if (sim.flight_ended()) {
      r.collided = true;
      break;
    }
    r.state = mission.tick(sim);
    if (r.state != MissionState::kRunning) break;
    if (progress && sim.now() >= next_progress) {
      progress(static_cast<double>((sim.now() - start).us) / static_cast<double>(duration.us));
      next_progress = next_progress + Duration::from_s(1.0);
    }
  }
  r.end = sim.now();
  if (hooks.loop_ends) hooks.loop_ends();
  if (progress) progress(1.0);
  if (r.collided) {
    const Contact& c = sim.contacts().front();
    r.message = "collision at t=" + std::to_string(c.stamp.seconds()) + " s";
  } else if (r.state == MissionState::kDone) {
    r.message = "mission done";
  } else if (r.state == MissionState::kFailed) {
    r.message = "mission failed: " + mission.failure();
  } else {
    r.message = "duration reached";
  }
  return r;
}

}  // namespace kestrel::sim
