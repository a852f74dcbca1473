#pragma once
// The table of missions kestrel-sim knows, by name.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "kestrel/sim/mission.hpp"

namespace kestrel::sim {

// Free-form options from the command line (`--mission-arg key=value`, `--script FILE`).
struct MissionOptions {
  std::map<std::string, std::string> values;
};

struct MissionInfo {
  const char* name;
  const char* summary;
  // Builds the mission or returns nullptr with `error` set (bad option, unreadable script).
  std::unique_ptr<Mission> (*create)(const MissionOptions& options, std::string& error);
};

const std::vector<MissionInfo>& mission_table();
// nullptr if unknown.
const MissionInfo* find_mission(const std::string& name);

}  // namespace kestrel::sim
