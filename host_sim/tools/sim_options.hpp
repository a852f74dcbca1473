#pragma once
// Command-line options of kestrel-sim. Every mistake is reported with the option's name and
// exit status 2.
#include <cstdint>
#include <string>

#include "kestrel/sim/mission_registry.hpp"

namespace kestrel::sim::tools {

struct SimOptions {
  std::string world = "iarc-arena";
  std::string laser = "utm30lx";
  double duration_s = 60;
  uint64_t seed = 1;
  std::string out_dir;
  std::string mission = "manual";
  std::string config_path;
  MissionOptions mission_options;
  bool record = false;
  bool trace_scans = false;  // scan_trace.csv: one row per scan the autonomy stack processed
  bool help = false;
};

struct ParseOutcome {
  bool ok = false;
  SimOptions options;
  std::string error;
};

ParseOutcome parse_sim_options(int argc, char** argv);
std::string sim_usage();

}  // namespace kestrel::sim::tools
