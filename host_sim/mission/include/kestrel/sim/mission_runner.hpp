#pragma once
// The loop of kestrel-sim, shared with the tests: start the mission, then step the world a
// tick at a time and tick the mission until the duration is over, the mission ends, or a
// contact ends the flight.
#include <functional>
#include <string>

#include "kestrel/sim/mission.hpp"
#include "kestrel/sim/simulation.hpp"

namespace kestrel::sim {

struct RunResult {
  Status status = Status::kOk;     // kOk unless the mission could not start
  MissionState state = MissionState::kRunning;  // kRunning when the duration ran out
  TimeUs end;                      // simulated time at the end
  bool collided = false;
  std::string message;             // why it ended, for people
};

// `progress(fraction)` is called every simulated second (may be empty).
RunResult run_mission(Simulation& sim, Mission& mission, Duration duration,
                      const std::function<void(double)>& progress = {});

}  // namespace kestrel::sim
