#include "kestrel/sim/mission_registry.hpp"

#include "kestrel/flight/autonomy_mission.hpp"
#include "kestrel/hil/hil_bridge_mission.hpp"
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

template <mission::MissionKind Kind>
std::unique_ptr<Mission> make_flight(const MissionOptions& options, std::string& error) {
  flight::FlightOptions f;
  error = flight::parse_flight_options(Kind, options, f);
  if (!error.empty()) return nullptr;
  return std::make_unique<flight::AutonomyMission>(std::move(f));
}

}  // namespace

const std::vector<MissionInfo>& mission_table() {
  // One row per mission.
  static const std::vector<MissionInfo> table = {
      {"manual", "replay a command script (--script FILE, default: a tour of iarc-arena)", make_manual},
      {"hover", "autonomy stack: take off, hover at 1 m (hover_s, default 60 s), land",
       make_flight<mission::MissionKind::kHover>},
      {"waypoints", "autonomy stack: fly the waypoints of --waypoints FILE (x y z [heading_deg [hold_s]]), land",
       make_flight<mission::MissionKind::kWaypoints>},
      {"explore", "autonomy stack: explore (--explorer blend|wallfollow|srt|frontier), fly home along the trail, land",
       make_flight<mission::MissionKind::kExplore>},
      {"hil", "hardware in the loop: serve the devices to kestrel-fw --hil 127.0.0.1:PORT (port=5760), real time",
       hil::make_hil_bridge},
  };
  return table;
}

const MissionInfo* find_mission(const std::string& name) {
  for (const MissionInfo& m : mission_table())
    if (name == m.name) return &m;
  return nullptr;
}

}  // namespace kestrel::sim
