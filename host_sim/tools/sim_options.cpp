#include "sim_options.hpp"

#include <cmath>
#include <cstdlib>

namespace kestrel::sim::tools {

std::string sim_usage() {
  std::string u =
      "usage: kestrel-sim [--world NAME|FILE] [--laser utm30lx|urg04lx] [--duration S] [--seed N]\n"
      "                   --out DIR [--mission NAME] [--script FILE] [--waypoints FILE]\n"
      "                   [--explorer blend|wallfollow|srt] [--mission-arg KEY=VALUE]\n"
      "                   [--config FILE] [--record]\n"
      "  --world     a compiled-in world (iarc-arena, gt-building, lobby, hallway, cluttered-lab)\n"
      "              or a world file (default iarc-arena)\n"
      "  --laser     utm30lx (1081 beams, 270 deg, 40 Hz, 30 m) or urg04lx (682 beams, 240 deg,\n"
      "              10 Hz, 4 m); default utm30lx\n"
      "  --duration  simulated seconds (default 60)\n"
      "  --seed      random seed: same world + config + seed = same outputs (default 1)\n"
      "  --out       output directory: metrics.json, trajectory_truth.tum, render.png, sim.log\n"
      "  --mission   what flies the vehicle:";
  for (const MissionInfo& m : mission_table()) u += std::string("\n                ") + m.name + ": " + m.summary;
  u +=
      "\n  --config    key = value file overriding vehicle.*, laser.*, imu.*, sim.* parameters\n"
      "  --record    also write the run as a CARMEN log (sim.log) with the true poses\n";
  return u;
}

ParseOutcome parse_sim_options(int argc, char** argv) {
  ParseOutcome r;
  SimOptions& o = r.options;
  auto fail = [&](const std::string& why) {
    r.ok = false;
    r.error = why;
    return r;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= argc) return false;
      out = argv[++i];
      return true;
    };
    std::string v;
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--record") {
      o.record = true;
    } else if (a == "--world" || a == "--laser" || a == "--duration" || a == "--seed" || a == "--out" ||
               a == "--mission" || a == "--config" || a == "--script" || a == "--mission-arg" || a == "--waypoints" ||
               a == "--explorer") {
      if (!value(v)) return fail("option " + a + " needs a value");
      if (a == "--world") {
        o.world = v;
      } else if (a == "--laser") {
        if (v != "utm30lx" && v != "urg04lx")
          return fail("--laser: unknown laser '" + v + "' (utm30lx or urg04lx)");
        o.laser = v;
      } else if (a == "--duration") {
        char* end = nullptr;
        o.duration_s = std::strtod(v.c_str(), &end);
        if (end != v.c_str() + v.size() || !std::isfinite(o.duration_s) || o.duration_s <= 0 ||
            o.duration_s > 1e6)
          return fail("--duration: '" + v + "' is not a positive number of seconds");
      } else if (a == "--seed") {
        char* end = nullptr;
        o.seed = std::strtoull(v.c_str(), &end, 10);
        if (v.empty() || v[0] == '-' || end != v.c_str() + v.size())
          return fail("--seed: '" + v + "' is not a non-negative integer");
      } else if (a == "--out") {
        o.out_dir = v;
      } else if (a == "--mission") {
        if (!find_mission(v)) {
          std::string known;
          for (const MissionInfo& m : mission_table()) known += std::string(known.empty() ? "" : ", ") + m.name;
          return fail("--mission: unknown mission '" + v + "' (known: " + known + ")");
        }
        o.mission = v;
      } else if (a == "--config") {
        o.config_path = v;
      } else if (a == "--script") {
        o.mission_options.values["script"] = v;
      } else if (a == "--waypoints") {
        o.mission_options.values["waypoints"] = v;
      } else if (a == "--explorer") {
        o.mission_options.values["explorer"] = v;
      } else {
        const auto eq = v.find('=');
        if (eq == std::string::npos || eq == 0) return fail("--mission-arg: expected KEY=VALUE, got '" + v + "'");
        o.mission_options.values[v.substr(0, eq)] = v.substr(eq + 1);
      }
    } else {
      return fail("unknown option '" + a + "' (see --help)");
    }
  }
  if (!o.help && o.out_dir.empty()) return fail("--out DIR is required");
  r.ok = true;
  return r;
}

}  // namespace kestrel::sim::tools
