// The whole real-time loop per laser scan (scan matching + EKF + guidance + control), the
// figure DESIGN.md budgets: 12.5 ms / ~9 M cycles per scan on the Overo with the UTM-30LX,
// 50 ms / ~20 M cycles on the Verdex with the URG-04LX.
//
// Set-up (not timed): the closed-loop hover mission flies the simulator for a few seconds and
// its sensor stream (scans, IMU samples, autopilot status) is recorded. Each iteration then
// replays one scan period of that stream into a fresh-looking loop through in-memory HAL
// devices on a manual clock: every IMU sample, the scan, and every task release of the
// period. The recording is a hover, so wrapping around from its end to its start is a jump of
// a few centimetres, as between two scans.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "kestrel/autonomy/autonomy_stack.hpp"
#include "kestrel/sim/builtin_worlds.hpp"
#include "kestrel/sim/mission_registry.hpp"
#include "kestrel/sim/mission_runner.hpp"
#include "kestrel/sim/simulation.hpp"

namespace {

using namespace kestrel;

struct Recording {
  std::vector<LaserScan> scans;
  std::vector<ImuSample> imu;
  hal::LaserGeometry geometry;
  Duration imu_period;
};

class Recorder final : public sim::SimObserver {
 public:
  explicit Recorder(Recording& r) : r_(r) {}
  void on_scan(const LaserScan& scan, const sim::VehicleState& truth) override {
    if (truth.position_m.z() > 0.9) r_.scans.push_back(scan);  // hovering at 1 m
  }
  void on_imu(const ImuSample& s) override { imu_.push_back(s); }
  std::vector<ImuSample> imu_;

 private:
  Recording& r_;
};

Recording record(const sim::LaserParams& laser) {
  Recording r;
  const sim::WorldParseResult world = sim::load_builtin_world("iarc-arena");
  sim::SimConfig cfg;
  cfg.laser = laser;
  sim::Simulation s(world.world, cfg);
  Recorder rec(r);
  s.set_observer(&rec);
  std::string err;
  sim::MissionOptions opt;
  opt.values.emplace(std::string("hover_s"), std::string("4"));
  auto mission = sim::find_mission("hover")->create(opt, err);
  (void)sim::run_mission(s, *mission, Duration::from_s(8.0));
  // Keep the IMU samples of the hover part, from the first recorded scan on.
  if (!r.scans.empty())
    for (const ImuSample& i : rec.imu_)
      if (i.stamp >= r.scans.front().stamp && i.stamp <= r.scans.back().stamp) r.imu.push_back(i);
  r.geometry = s.laser().geometry();
  r.imu_period = s.imu().sample_period();
  return r;
}

// In-memory devices the driver loads with one scan period of data at a time.
struct ReplayLaser final : hal::LaserScanner {
  hal::LaserGeometry g;
  const LaserScan* pending = nullptr;
  hal::LaserGeometry geometry() const override { return g; }
  Status poll(LaserScan& out) override {
    if (pending == nullptr) return Status::kNoData;
    out = *pending;
    pending = nullptr;
    return Status::kOk;
  }
};
struct ReplayImu final : hal::Imu {
  Duration period;
  const ImuSample* next = nullptr;
  const ImuSample* end = nullptr;
  Duration shift;
  Duration sample_period() const override { return period; }
  Status poll(ImuSample& out) override {
    if (next == end) return Status::kNoData;
    out = *next++;
    out.stamp += shift;
    return Status::kOk;
  }
};
struct NullAutopilot final : hal::FlightController {
  Status arm(bool) override { return Status::kOk; }
  Status send(const AttitudeSetpoint&) override { return Status::kOk; }
  Status poll_status(FlightStatus&) override { return Status::kNoData; }
};
struct ManualClock final : hal::Clock {
  TimeUs t;
  TimeUs now() const override { return t; }
  Status sleep_until(TimeUs until) override {
    if (until > t) t = until;
    return Status::kOk;
  }
};

void run_loop(benchmark::State& state, const sim::LaserParams& laser, bool slam = false) {
  static Recording rec;
  rec = record(laser);
  if (rec.scans.size() < 10) {
    state.SkipWithError("the hover recording has too few scans");
    return;
  }
  ManualClock clock;
  ReplayLaser dev_laser;
  dev_laser.g = rec.geometry;
  ReplayImu dev_imu;
  dev_imu.period = rec.imu_period;
  NullAutopilot autopilot;
  const autonomy::Devices devices{clock, dev_laser, dev_imu, nullptr, autopilot};
  auto stack = std::make_unique<autonomy::AutonomyStack>(devices, clock);
  autonomy::StackConfig cfg;
  cfg.mission.hover_duration_s = 1e6f;
  // The real-time loop alone by default; with the compact SLAM, its level-3 search and drawing
  // (which background_step runs in lockstep here) and the scan task's side of the mailboxes.
  cfg.slam_enabled = slam;
  if (stack->configure(cfg) != Status::kOk || stack->start() != Status::kOk) {
    state.SkipWithError("stack configuration failed");
    return;
  }
  const Duration period = rec.geometry.scan_period;
  std::size_t k = 0, imu_i = 0;
  Duration lap_shift;  // each replay lap is shifted forward so time never goes backwards
  const Duration lap = rec.scans.back().stamp - rec.scans.front().stamp + period;
  for (auto _ : state) {
    const LaserScan& src = rec.scans[k];
    static LaserScan scan;
    scan = src;
    scan.stamp += lap_shift;
    const TimeUs t0 = scan.stamp;
    // IMU samples of this scan period.
    std::size_t j = imu_i;
    while (j < rec.imu.size() && rec.imu[j].stamp < src.stamp + period) ++j;
    dev_imu.next = rec.imu.data() + imu_i;
    dev_imu.end = rec.imu.data() + j;
    dev_imu.shift = lap_shift;
    imu_i = j;
    dev_laser.pending = &scan;
    // Every release of the period, in order.
    clock.t = t0;
    while (clock.t < t0 + period) {
      stack->poll();
      stack->background_step();
      clock.t = std::min(stack->next_release(), t0 + period);
      if (stack->next_release() >= t0 + period) break;
    }
    if (++k == rec.scans.size()) {
      k = 0;
      imu_i = 0;
      lap_shift = lap_shift + lap;
    }
  }
  state.counters["matched"] = stack->counters().scans_matched;
}

void BM_LoopUtm(benchmark::State& s) { run_loop(s, sim::LaserParams::utm30lx()); }
void BM_LoopUrg(benchmark::State& s) { run_loop(s, sim::LaserParams::urg04lx()); }
BENCHMARK(BM_LoopUtm)->Name("autonomy/loop_per_scan_utm30lx")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LoopUrg)->Name("autonomy/loop_per_scan_urg04lx")->Unit(benchmark::kMicrosecond);
void BM_LoopSlamUrg(benchmark::State& s) { run_loop(s, sim::LaserParams::urg04lx(), true); }
BENCHMARK(BM_LoopSlamUrg)->Name("autonomy/loop_and_slam_per_scan_urg04lx")->Unit(benchmark::kMicrosecond);

}  // namespace
