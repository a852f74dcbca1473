#pragma once
// Writes the files of a kestrel-sim run into --out DIR: metrics.json and
// trajectory_truth.tum (render.png is world_render's). Nothing time-of-day or host dependent
// goes into them, so equal runs give equal bytes.
#include <string>

#include "kestrel/sim/flight_recorder.hpp"
#include "kestrel/sim/mission.hpp"
#include "kestrel/sim/mission_runner.hpp"
#include "sim_options.hpp"

namespace kestrel::sim::tools {

Status write_metrics(const std::string& path, const SimOptions& opt, Simulation& sim, const FlightRecorder& rec,
                     const RunResult& run, const Mission& mission);
Status write_truth_tum(const std::string& path, const FlightRecorder& rec);

}  // namespace kestrel::sim::tools
