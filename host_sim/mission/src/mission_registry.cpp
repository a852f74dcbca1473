#include "kestrel/sim/mission_registry.hpp"

#include "kestrel/sim/manual_mission.hpp"

namespace kestrel::sim {
namespace {

std::unique_ptr<Mission> make_manual(const MissionOptions& options, std::string& error) {
  CommandScript script;
  const auto it = options.values.find("script");
  error = it == options.values.end() ? script.parse(CommandScript::default_text(), "<default script>")
                                     : script.load(it->second);
  for (const auto& [key, value] : options.values)
    if (key != "script") error = "mission 'manual' has no option '" + key + "'";
  if (!error.empty()) return nullptr;
  return std::make_unique<ManualMission>(std::move(script));
}

}  // namespace

const std::vector<MissionInfo>& mission_table() {
  // One row per mission. Later missions (hover, waypoints, explore) add theirs here.
  static const std::vector<MissionInfo> table = {
      {"manual", "replay a command script (--script FILE, default: a tour of iarc-arena)", make_manual},
  };
  return table;
}

const MissionInfo* find_mission(const std::string& name) {
  for (const MissionInfo& m : mission_table())
    if (name == m.name) return &m;
  return nullptr;
}

}  // namespace kestrel::sim
