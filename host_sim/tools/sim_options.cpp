#include "sim_options.hpp"

#include "kestrel/cli/arg_reader.hpp"
#include "kestrel/core/time.hpp"

#include <cmath>
#include <cstdlib>

namespace kestrel::sim::tools {

std::string sim_usage() {
  std::string u =
      "usage: kestrel-sim [--world NAME|FILE] [--laser utm30lx|urg04lx] [--duration S] [--seed N]\n"
      "                   --out DIR [--mission NAME] [--script FILE] [--waypoints FILE]\n"
      "                   [--explorer blend|wallfollow|srt|frontier] [--mission-arg KEY=VALUE]\n"
      "                   [--config FILE] [--record] [--trace-scans]\n"
      "  --world     a compiled-in world (iarc-arena, gt-building, lobby, hallway, cluttered-lab)\n"
      "              or a world file (default iarc-arena)\n"
      "  --laser     utm30lx (1081 beams, 270 deg, 40 Hz, 30 m) or urg04lx (682 beams, 240 deg,\n"
      "              10 Hz, 4 m); default utm30lx\n"
      "  --duration  simulated seconds (default 60)\n"
      "  --seed      random seed: same world + config + seed = same outputs (default 1)\n"
      "  --out       output directory: metrics.json, trajectory_truth.tum, render.png, sim.log;\n"
      "              with the compact SLAM (urg04lx) also map.pgm, map.yaml and slam_map.png\n"
      "  --mission   what flies the vehicle:";
  for (const MissionInfo& m : mission_table()) u += std::string("\n                ") + m.name + ": " + m.summary;
  u +=
      "\n  --config    key = value file overriding vehicle.*, laser.*, imu.*, sim.* parameters\n"
      "  --record    also write the run as a CARMEN log (sim.log) with the true poses\n"
      "  --trace-scans  also write scan_trace.csv (hover, waypoints, explore): one row per scan\n"
      "              the autonomy stack processed, with the match, the filter after the update,\n"
      "              the true state and their errors; the header row names the columns, which\n"
      "              host_sim/flight/include/kestrel/flight/scan_trace.hpp documents; and, when\n"
      "              the compact SLAM runs, slam_trace.csv: one row per scan it processed, with\n"
      "              its outcome, the filter's pose, its best fit and the truth (slam_trace.hpp).\n"
      "              Off by default\n";
  return u;
}

ParseOutcome parse_sim_options(int argc, char** argv) {
  ParseOutcome r;
  SimOptions& o = r.options;
  cli::ArgReader args(argc, argv);
  while (args.next()) {
    std::string v;
    if (args.is("--help") || args.is("-h")) {
      o.help = true;
    } else if (args.is("--record")) {
      o.record = true;
    } else if (args.is("--trace-scans")) {
      o.trace_scans = true;
    } else if (args.is("--world")) {
      args.take(o.world);
    } else if (args.is("--laser")) {
      if (!args.take(v)) break;
      if (v != "utm30lx" && v != "urg04lx") args.fail("--laser: unknown laser '" + v + "' (utm30lx or urg04lx)");
      o.laser = v;
    } else if (args.is("--duration")) {
      if (!args.take(v)) break;
      if (!cli::to_double(v, o.duration_s) || o.duration_s <= 0 || o.duration_s > kMaxRunSeconds)
        args.fail("--duration: '" + v + "' is not a positive number of seconds");
    } else if (args.is("--seed")) {
      args.take_u64(o.seed);
    } else if (args.is("--out")) {
      args.take(o.out_dir);
    } else if (args.is("--mission")) {
      if (!args.take(v)) break;
      if (!find_mission(v)) {
        std::string known;
        for (const MissionInfo& m : mission_table()) known += std::string(known.empty() ? "" : ", ") + m.name;
        args.fail("--mission: unknown mission '" + v + "' (known: " + known + ")");
      }
      o.mission = v;
    } else if (args.is("--config")) {
      args.take(o.config_path);
    } else if (args.is("--script") || args.is("--waypoints") || args.is("--explorer")) {
      // Shorthands for --mission-arg script=, waypoints=, explorer=.
      if (args.take(v)) o.mission_options.values[args.option().substr(2)] = v;
    } else if (args.is("--mission-arg")) {
      if (!args.take(v)) break;
      const auto eq = v.find('=');
      if (eq == std::string::npos || eq == 0) {
        args.fail("--mission-arg: expected KEY=VALUE, got '" + v + "'");
      } else {
        o.mission_options.values[v.substr(0, eq)] = v.substr(eq + 1);
      }
    } else {
      args.unknown();
    }
  }
  if (args.ok() && !o.help && o.out_dir.empty()) args.fail("--out DIR is required");
  r.ok = args.ok();
  r.error = args.error();
  return r;
}

}  // namespace kestrel::sim::tools
