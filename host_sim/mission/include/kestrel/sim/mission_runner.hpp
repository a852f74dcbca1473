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

// Optional callbacks around the loop (each may be empty): `progress(fraction)` every simulated
// second; `loop_begins` after the mission has started, just before the first tick (the
// system is armed: kestrel-sim arms the allocation guard there), and `loop_ends` right after
// the last step, before anything is formatted for people.
struct RunHooks {
  std::function<void(double)> progress;
  std::function<void()> loop_begins;
  std::function<void()> loop_ends;
};

RunResult run_mission(Simulation& sim, Mission& mission, Duration duration, const RunHooks& hooks = {});

}  // namespace kestrel::sim
