// kestrel-sim: runs one simulated flight and writes its outputs. Exit status 0 on success
// (a collision is an outcome, not an error: it is in metrics.json), 2 for a usage or input
// error (bad option, unknown world, bad world/config/script file), 1 when outputs cannot be
// written.
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <cstdio>
#include <string>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/output/png_writer.hpp"
#include "kestrel/sim/builtin_worlds.hpp"
#include "kestrel/sim/carmen_recorder.hpp"
#include "kestrel/sim/flight_recorder.hpp"
#include "kestrel/sim/mission_runner.hpp"
#include "kestrel/sim/sim_observer_list.hpp"
#include "kestrel/sim/simulation.hpp"
#include "run_outputs.hpp"
#include "sim_options.hpp"
#include "world_render.hpp"

using namespace kestrel;
using namespace kestrel::sim;

namespace {

int usage_error(const std::string& msg) {
  std::fprintf(stderr, "kestrel-sim: %s\n", msg.c_str());
  return 2;
}

// Drawn while the allocation guard is armed: a fixed buffer, no std::string.
void progress_bar(double f) {
  constexpr int kWidth = 40;
  char bar[kWidth + 1];
  const int n = static_cast<int>(f * kWidth + 0.5);
  for (int i = 0; i < kWidth; ++i) bar[i] = i < n ? '#' : '.';
  bar[kWidth] = '\0';
  std::fprintf(stderr, "\r[%s] %3d%%", bar, static_cast<int>(f * 100 + 0.5));
  if (f >= 1.0) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace

int main(int argc, char** argv) {
  const tools::ParseOutcome parsed = tools::parse_sim_options(argc, argv);
  if (!parsed.ok) return usage_error(parsed.error + "\n" + tools::sim_usage());
  const tools::SimOptions& opt = parsed.options;
  if (opt.help) {
    std::fputs(tools::sim_usage().c_str(), stdout);
    return 0;
  }
  WorldParseResult world = load_world(opt.world);
  if (!world.ok) return usage_error(world.error);

  SimConfig cfg;
  cfg.laser = opt.laser == "urg04lx" ? LaserParams::urg04lx() : LaserParams::utm30lx();
  cfg.seed = opt.seed;
  if (!opt.config_path.empty()) {
    ConfigFile file;
    if (std::string e = file.load(opt.config_path); !e.empty()) return usage_error(e);
    if (std::string e = cfg.apply(file); !e.empty()) return usage_error(e);
  } else if (std::string e = cfg.validate(); !e.empty()) {
    return usage_error(e);
  }
  const MissionInfo* info = find_mission(opt.mission);
  std::string mission_error;
  std::unique_ptr<Mission> mission = info->create(opt.mission_options, mission_error);
  if (!mission) return usage_error(mission_error);

  std::error_code ec;
  std::filesystem::create_directories(opt.out_dir, ec);
  if (ec || !std::filesystem::is_directory(opt.out_dir)) {
    std::fprintf(stderr, "kestrel-sim: cannot create the output directory '%s'\n", opt.out_dir.c_str());
    return 1;
  }

  if (opt.trace_scans) {
    const std::string trace_path = opt.out_dir + "/scan_trace.csv";
    const Status ts = mission->open_traces(opt.out_dir);
    if (ts == Status::kUnsupported)
      return usage_error("--trace-scans: mission '" + opt.mission + "' runs no scan matcher");
    if (ts != Status::kOk) {
      std::fprintf(stderr, "kestrel-sim: cannot write the scan trace '%s'\n", trace_path.c_str());
      return 1;
    }
  }
  Simulation sim(std::move(world.world), cfg);
  FlightRecorder rec(sim.world(), sim.free_space(), Duration::from_s(opt.duration_s));
  SimObserverList observers;
  observers.add(&rec);
  mission->set_recorder(&rec);
  CarmenRecorder carmen;
  const std::string log_path = opt.out_dir + "/sim.log";
  if (opt.record) {
    if (carmen.open(log_path.c_str(), sim.imu().sample_period()) != Status::kOk) {
      std::fprintf(stderr, "kestrel-sim: cannot write the log '%s'\n", log_path.c_str());
      return 1;
    }
    observers.add(&carmen);
  }
  sim.set_observer(&observers);
  const bool tty = ::isatty(2) != 0;
  const auto wall0 = std::chrono::steady_clock::now();
  RunHooks hooks;
  if (tty) hooks.progress = progress_bar;
  uint64_t heap_allocs_after_arm = 0;
  hooks.loop_begins = [] {
    alloc_guard::reset();
    alloc_guard::arm();
  };
  hooks.loop_ends = [&heap_allocs_after_arm] {
    alloc_guard::disarm();
    heap_allocs_after_arm = alloc_guard::count();
  };
  const RunResult run = run_mission(sim, *mission, Duration::from_s(opt.duration_s), hooks);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  if (run.status == Status::kIoError) {  // e.g. the SLAM trace, opened as the mission starts
    std::fprintf(stderr, "kestrel-sim: %s\n", run.message.c_str());
    return 1;
  }
  if (run.status != Status::kOk) return usage_error(run.message);

  const std::string dir = opt.out_dir + "/";
  int rc = 0;
  if (opt.record && carmen.close() != Status::kOk) {
    std::fprintf(stderr, "kestrel-sim: writing the log '%s' failed: %s\n", log_path.c_str(),
                 to_string(carmen.status()));
    rc = 1;
  }
  if (tools::write_metrics(dir + "metrics.json", opt, sim, rec, run, *mission, heap_allocs_after_arm) != Status::kOk)
    rc = 1;
  if (tools::write_truth_tum(dir + "trajectory_truth.tum", rec) != Status::kOk) rc = 1;
  char title[256], sub[256];
  std::snprintf(title, sizeof(title), "KESTREL-SIM  %s  (%s)", sim.world().name.c_str(), opt.mission.c_str());
  std::snprintf(sub, sizeof(sub), "LASER %s  SEED %llu  %.1f S  FLOWN %.1f M  COVERAGE %.0f%%  COLLISIONS %zu",
                opt.laser.c_str(), static_cast<unsigned long long>(opt.seed), run.end.seconds(), rec.distance_m(),
                rec.coverage() * 100, sim.contacts().size());
  if (mission->write_outputs(opt.out_dir) != Status::kOk) rc = 1;
  const output::Canvas canvas = tools::render_run(sim.world(), rec, sim.contacts(), {title, sub}, mission.get());
  if (output::write_png(dir + "render.png", canvas) != Status::kOk) rc = 1;
  if (rc != 0) std::fprintf(stderr, "kestrel-sim: could not write every output into '%s'\n", opt.out_dir.c_str());
  std::fprintf(stderr, "kestrel-sim: %s after %.2f s simulated (%.1fx real time); outputs in %s\n",
               run.message.c_str(), run.end.seconds(), wall_s > 0 ? run.end.seconds() / wall_s : 0.0,
               opt.out_dir.c_str());
  return rc;
}
