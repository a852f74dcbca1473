// Guidance cycle of paper 002's explorer (wall-following field + SRT-Star + blending) with the
// two lasers of the design: the URG-04LX (682 beams over 240 degrees, Verdex at 10 Hz) and the
// UTM-30LX (1081 beams over 270 degrees, Overo at 40 Hz). The vehicle hovers in a 6 m x 4 m room
// off its waypoint, so each iteration is one steady-state cycle; the arrival case (sectors,
// new node, frontier pruning, new waypoint) is measured apart.
// Heap use here is set-up before each benchmark's timed loop (large objects that would not fit
// on the stack); the timed code itself never allocates (see the alloc_guard tests).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "kestrel/core/messages.hpp"
#include "kestrel/exploration/approach_limiter.hpp"
#include "kestrel/exploration/blend_explorer.hpp"
#include "kestrel/exploration/flown_history.hpp"
#include "kestrel/exploration/frontier_explorer.hpp"
#include "kestrel/exploration/srt_star_planner.hpp"
#include "kestrel/exploration/unflown_bearings.hpp"
#include "kestrel/exploration/visited_grid.hpp"
#include "retrace_flight_out.hpp"
#include "synthetic_world.hpp"

namespace {

using namespace kestrel;
using namespace kestrel::exploration;

// Ranges from (x, y, heading) to the walls of the room [0, w] x [0, h], in mm.
LaserScan room_scan(uint16_t beams, double fov_deg, double x, double y, double heading, double w, double h) {
  LaserScan s;
  s.beam_count = beams;
  const double fov = fov_deg * M_PI / 180.0;
  s.first_angle_rad = static_cast<float>(-fov / 2);
  s.angle_step_rad = static_cast<float>(fov / beams);
  s.max_range_mm = 30000;
  for (uint16_t i = 0; i < beams; ++i) {
    const double a = heading + s.first_angle_rad + s.angle_step_rad * i;
    const double c = std::cos(a), sn = std::sin(a);
    double t = 1e9;
    if (c > 1e-9) t = std::min(t, (w - x) / c);
    if (c < -1e-9) t = std::min(t, -x / c);
    if (sn > 1e-9) t = std::min(t, (h - y) / sn);
    if (sn < -1e-9) t = std::min(t, -y / sn);
    s.range_mm[i] = static_cast<uint16_t>(std::lround(std::min(t, 29.0) * 1000.0));
  }
  return s;
}

// frontier_marks: srt.retrace counting the coarse grid's frontier, whose planner marks a slice
// of every scan's beams on its laser layers (srt_star_planner.hpp, mark_seen).
void guidance_step(benchmark::State& state, uint16_t beams, double fov_deg, bool frontier_marks = false) {
  auto explorer = std::make_unique<BlendExplorer>();
  LaserScan scan = room_scan(beams, fov_deg, 2.0, 1.5, 0.3, 6.0, 4.0);
  Params params;
  params.guidance.waypoint_time_limit_s = 1e6f;  // steady state: no restart inside the loop
  if (frontier_marks) {
    params.srt.retrace = RetraceMode::kAlways;
    params.srt.retrace_target = RetraceTarget::kFrontier;
  }
  if (explorer->configure(params, BeamGeometry::of(scan)) != Status::kOk) {
    state.SkipWithError("configure failed");
    return;
  }
  NavState nav;
  nav.valid = true;
  nav.position_m = {2.0f, 1.5f, 1.0f};
  nav.heading_rad = 0.3f;
  GuidanceSetpoint out;
  (void)explorer->step(nav, scan, out);  // starts the tree: later steps are off the waypoint
  for (auto _ : state) {
    scan.stamp += Duration::from_ms(25);
    benchmark::DoNotOptimize(explorer->step(nav, scan, out));
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations() * beams);
}

// The approach limiter's worst case: 0.45 m from two walls of a corner, the command at full
// speed into it, so every return near the corner is within reach and several cuts are made.
void approach_limit_corner(benchmark::State& state, uint16_t beams, double fov_deg) {
  const LaserScan scan = room_scan(beams, fov_deg, 5.55, 3.55, 0.6, 6.0, 4.0);
  auto directions = std::make_unique<BeamDirections>();
  directions->build(BeamGeometry::of(scan));
  ApproachLimiter limiter;
  if (limiter.configure(ApproachParams{}, BeamGeometry::of(scan)) != Status::kOk) {
    state.SkipWithError("configure failed");
    return;
  }
  uint32_t cuts = 0;
  for (auto _ : state) {
    Eigen::Vector2f v{0.45f, 0.2f};
    cuts = limiter.limit(scan, *directions, v).cuts;
    benchmark::DoNotOptimize(v);
  }
  state.counters["cuts"] = cuts;
}

// The whole arrival step in one call (srt.arrival_work_per_cycle = 0), as before it was sliced.
// The direction tables are built once per laser geometry, outside the timed loop.
void srt_arrival(benchmark::State& state, uint16_t beams, double fov_deg) {
  auto planner = std::make_unique<SrtStarPlanner>();
  SrtParams whole;
  whole.arrival_work_per_cycle = 0;
  (void)planner->configure(whole, GuidanceParams{});
  LaserScan scan = room_scan(beams, fov_deg, 2.0, 1.5, 0.3, 6.0, 4.0);
  bool fresh = false;
  (void)planner->update({2.0f, 1.5f, 0.3f}, scan, TimeUs{}, fresh);
  for (auto _ : state) {
    state.PauseTiming();
    planner->reset();
    state.ResumeTiming();
    benchmark::DoNotOptimize(planner->update({2.0f, 1.5f, 0.3f}, scan, TimeUs{}, fresh));
  }
}

// The first state.range(0) guidance cycles of an arrival step in slices (default budget):
// the instructions of cycle n are those of n cycles minus those of n - 1, so each cycle's
// share is measured exactly under qemu-arm (`kestrel-budget insns`), not averaged.
void srt_arrival_cycles(benchmark::State& state, uint16_t beams, double fov_deg, bool corridor = false) {
  auto planner = std::make_unique<SrtStarPlanner>();
  (void)planner->configure(SrtParams{}, GuidanceParams{});
  LaserScan scan = corridor ? room_scan(beams, fov_deg, 2.0, 0.7, 0.3, 20.0, 1.4)
                            : room_scan(beams, fov_deg, 2.0, 1.5, 0.3, 6.0, 4.0);
  bool fresh = false;
  const Pose2 pose{2.0f, corridor ? 0.7f : 1.5f, 0.3f};
  do {  // tables built, as in flight after the first arrival
    (void)planner->update(pose, scan, TimeUs{}, fresh);
  } while (planner->busy());
  int64_t calls = 0;
  bool done = false;
  for (auto _ : state) {
    planner->reset();
    calls = 0;
    done = false;
    while (calls < state.range(0) && !done) {
      benchmark::DoNotOptimize(planner->update(pose, scan, TimeUs{}, fresh));
      ++calls;
      done = !planner->busy();
    }
  }
  state.counters["cycles"] = static_cast<double>(calls);
  state.counters["arrival_done"] = done ? 1.0 : 0.0;
}

// A retrace with a nearly full path flown, guidance cycle by guidance cycle (default budget,
// a guarded planner as the blend's): the flight out of retrace_flight_out.hpp (kLong, some 860
// trail points), then a late waypoint in an enclosed place. Cycle 1 restarts the tree; the
// fresh tree's arrival step, the trail's count (UnflownBearings at every kRetraceStride-th
// point) and the retrace's start (two searches along the whole trail, each an item that may
// begin just under the budget) run over the next cycles; once the planner is free, every cycle
// puts the vehicle on its waypoint, so each is an arrival on the way back (the leg after the
// next found along the trail). Each iteration starts from a copy of the planner before cycle 1,
// the same work for every n: cycle n = `.../n` minus `.../n-1` (`kestrel-budget insns`).
void srt_retrace_cycles(benchmark::State& state) {
  auto before = std::make_unique<SrtStarPlanner>();
  GuidanceParams g;
  g.waypoint_time_limit_s = 1000.0f;
  if (before->configure(SrtParams{}, g, /*guarded=*/true) != Status::kOk || !before->retraces_enabled()) {
    state.SkipWithError("configure");
    return;
  }
  bool fresh = false;
  const auto ignore = [](Status) {};
  test::retrace_take_start(*before, fresh, ignore);
  test::retrace_fly_out(*before, test::Outward::kLong, fresh, ignore);
  const Point2 last = test::retrace_flight_out(test::Outward::kLong).back();
  // The scenario the figures describe, as retrace_test.cpp's flight asserts it: no restart on
  // the way out, a history nearly full but never thinned.
  if (before->restarts() != 0 || before->mode() != PlannerMode::kForward || before->trail().size() < 800 ||
      before->trail().spacing_m() != FlownHistory::kSpacingM) {
    state.SkipWithError("the flight out is not the retrace tests' own");
    return;
  }
  const TimeUs late = TimeUs::from_s(1001);
  const LaserScan enclosed = test::retrace_enclosed_scan();
  auto planner = std::make_unique<SrtStarPlanner>();
  int64_t calls = 0;
  uint32_t most_work = 0;
  for (auto _ : state) {
    *planner = *before;
    Pose2 at{last.x, last.y, 0};
    for (calls = 0; calls < state.range(0); ++calls) {
      if (calls > 0 && !planner->busy()) at = {planner->waypoint().x, planner->waypoint().y, 0};
      benchmark::DoNotOptimize(planner->update(at, enclosed, late + Duration::from_ms(100 * calls), fresh));
      most_work = std::max(most_work, planner->last_work());
    }
  }
  state.counters["trail_points"] = static_cast<double>(before->trail().size());
  state.counters["retracing"] = planner->mode() == PlannerMode::kRetrace ? 1.0 : 0.0;
  state.counters["busy"] = planner->busy() ? 1.0 : 0.0;
  state.counters["most_work_units"] = static_cast<double>(most_work);
  state.counters["last_work_units"] = static_cast<double>(planner->last_work());
  state.counters["restarts"] = static_cast<double>(planner->restarts());
  state.counters["retraces"] = static_cast<double>(planner->retraces());
}

// The sectors and their erosion alone (SectorScan::build), direction tables kept; and with the
// tables rebuilt every time (two scans whose beam steps differ in the last bit, alternately):
// these calibrate the work units of work_units.hpp on the Verdex.
// The corridor case (1.4 m wide, walls 0.7 m away) makes every return block many rays.
void sector_scan(benchmark::State& state, uint16_t beams, double fov_deg, bool rebuild_tables, bool corridor = false) {
  auto sectors = std::make_unique<SectorScan>();
  LaserScan a = corridor ? room_scan(beams, fov_deg, 2.0, 0.7, 0.3, 20.0, 1.4)
                         : room_scan(beams, fov_deg, 2.0, 1.5, 0.3, 6.0, 4.0);
  LaserScan b = a;
  b.angle_step_rad = std::nextafter(a.angle_step_rad, 1.0f);
  const SrtParams params;
  (void)sectors->build(a, params);
  bool flip = false;
  for (auto _ : state) {
    flip = rebuild_tables && !flip;
    benchmark::DoNotOptimize(sectors->build(flip ? b : a, params));
  }
}

void BM_GuidanceStepUrg(benchmark::State& s) {
  guidance_step(s, 682, 240.0);
}
void BM_GuidanceStepUtm(benchmark::State& s) {
  guidance_step(s, 1081, 270.0);
}
void BM_GuidanceStepFrontierMarksUrg(benchmark::State& s) {
  guidance_step(s, 682, 240.0, true);
}
void BM_GuidanceStepFrontierMarksUtm(benchmark::State& s) {
  guidance_step(s, 1081, 270.0, true);
}
void BM_ApproachCornerUrg(benchmark::State& s) {
  approach_limit_corner(s, 682, 240.0);
}
void BM_ApproachCornerUtm(benchmark::State& s) {
  approach_limit_corner(s, 1081, 270.0);
}
void BM_SrtArrivalUrg(benchmark::State& s) {
  srt_arrival(s, 682, 240.0);
}
void BM_SrtArrivalUtm(benchmark::State& s) {
  srt_arrival(s, 1081, 270.0);
}
void BM_SrtArrivalCyclesUrg(benchmark::State& s) {
  srt_arrival_cycles(s, 682, 240.0);
}
void BM_SrtArrivalCyclesCorridorUrg(benchmark::State& s) {
  srt_arrival_cycles(s, 682, 240.0, true);
}
void BM_SrtArrivalCyclesUtm(benchmark::State& s) {
  srt_arrival_cycles(s, 1081, 270.0);
}
void BM_SrtRetraceCyclesUrg(benchmark::State& s) { srt_retrace_cycles(s); }
void BM_SectorScanUrg(benchmark::State& s) {
  sector_scan(s, 682, 240.0, false);
}
void BM_SectorScanCorridorUrg(benchmark::State& s) {
  sector_scan(s, 682, 240.0, false, true);
}
void BM_SectorScanTablesUrg(benchmark::State& s) {
  sector_scan(s, 682, 240.0, true);
}
// The work item a steered draw (srt.steer) adds to each choice: the unflown cells around a node in the
// middle of a gt-building-sized outline (24 x 16 m), with a corridor and two rooms flown.
void BM_UnflownCount(benchmark::State& s) {
  auto grid = std::make_unique<VisitedGrid>();
  for (float x = 0.5f; x <= 23.5f; x += 0.25f) grid->mark({x, 8.0f});
  for (float y = 1.0f; y <= 15.0f; y += 0.25f) {
    grid->mark({4.0f, y});
    grid->mark({14.0f, y});
  }
  grid->widen_extent({0.0f, 0.0f});
  grid->widen_extent({24.0f, 16.0f});
  auto bearings = std::make_unique<UnflownBearings>();
  for (auto _ : s) {
    benchmark::DoNotOptimize(bearings->count(*grid, {12.0f, 8.0f}));
    benchmark::DoNotOptimize(bearings->total());
  }
}
// Its worst case, which the work units must cover: every cell in reach inside the extent and
// never flown, so each one is weighted and added (the count near a long flight's start, far
// from where it ended: exploration/srt_retrace_cycles).
void BM_UnflownCountAllUnflown(benchmark::State& s) {
  auto grid = std::make_unique<VisitedGrid>();
  // The first mark centres the grid on (0, 0), cells -32..32 m; its flown cells lie 18 cells
  // from the count's, beyond its reach of 16.
  grid->mark({0.0f, 0.0f});
  grid->widen_extent({-2.5f, -2.5f});  // inside the grid, so the extent takes them
  grid->widen_extent({31.0f, 31.0f});
  auto bearings = std::make_unique<UnflownBearings>();
  for (auto _ : s) {
    benchmark::DoNotOptimize(bearings->count(*grid, {14.0f, 14.0f}));
    benchmark::DoNotOptimize(bearings->total());
  }
  s.counters["total"] = static_cast<double>(bearings->total());
}
// The same count of the coarse grid's frontier (RetraceTarget::kFrontier, work::kFrontierCells):
// the corridor and the rooms' first metres seen free, their walls marked, the rest unseen.
void BM_FrontierCount(benchmark::State& s) {
  auto grid = std::make_unique<VisitedGrid>();
  grid->mark({12.0f, 8.0f});
  for (float x = 0.5f; x <= 23.5f; x += 0.5f) {
    for (float y = 7.0f; y <= 9.0f; y += 0.5f) grid->mark_seen({x, y});
    for (float y = 4.0f; y <= 12.0f; y += 1.0f)
      if (static_cast<int>(x) % 6 == 2) grid->mark_seen({x, y});  // a door every 6 m
    grid->mark_wall({x, 6.5f});
    grid->mark_wall({x, 9.5f});
  }
  auto bearings = std::make_unique<UnflownBearings>();
  for (auto _ : s) {
    benchmark::DoNotOptimize(bearings->count(*grid, {12.0f, 8.0f}, RetraceTarget::kFrontier));
    benchmark::DoNotOptimize(bearings->total());
  }
}
// Its worst case: nothing seen in reach, so every cell tests its four neighbours (a cell walled
// all round tests eight bits, but its neighbours, seen, test two).
void BM_FrontierCountNothingSeen(benchmark::State& s) {
  auto grid = std::make_unique<VisitedGrid>();
  grid->mark({0.0f, 0.0f});  // centres the grid; its flown cells lie beyond the count's reach
  auto bearings = std::make_unique<UnflownBearings>();
  for (auto _ : s) {
    benchmark::DoNotOptimize(bearings->count(*grid, {14.0f, 14.0f}, RetraceTarget::kFrontier));
    benchmark::DoNotOptimize(bearings->total());
  }
}
// A retrace's search along the path flown (work::kTrailPoint): a full history, a lawn-mower of
// FlownHistory::kCapacity points, searched from its first point to its last for a place no
// point is near, so that every point is tested.
void BM_TrailSearch(benchmark::State& s) {
  auto history = std::make_unique<FlownHistory>();
  const float step = FlownHistory::kSpacingM;
  for (std::size_t i = 0; i < FlownHistory::kCapacity; ++i) {
    const std::size_t line = i / 64, along = i % 64;  // 32 m lines, 1 m apart
    const float y = step * static_cast<float>(line % 2 == 0 ? along : 63 - along);
    history->record({static_cast<float>(line), y});
  }
  const Point2 elsewhere{-10.0f, -10.0f};
  for (auto _ : s) benchmark::DoNotOptimize(history->earliest_near(0, history->size() - 1, elsewhere, 0.4f));
  s.counters["points"] = static_cast<double>(history->size());
}
// The grid frontier explorer (paper 003) in a 15 x 10 m hall split by a wall with a 1 m door,
// after a walk through its west half: one cycle of both levels, the scan drawn and a whole
// plan made (obstacle distance, search, frontiers, path) every iteration (replan_period_s
// shortened to force it; by default a plan is made once a second). `frontier_guidance` is
// level 2 alone, the guidance task's share.
struct FrontierHall {
  std::unique_ptr<FrontierExplorer> ex = std::make_unique<FrontierExplorer>();
  test::SegmentWorld world;
  test::LaserModel laser;
  double t = 0;
  GuidanceSetpoint out;
  explicit FrontierHall(const test::LaserModel& l) : laser(l) {
    world.add_box(0, 0, 15, 10);
    world.add(7, 0, 7, 4.5);
    world.add(7, 5.5, 7, 10);
    world.add_box(3, 3, 3.4, 3.4);
  }
  bool start(bool replan_every_cycle) {
    Params p;
    if (replan_every_cycle) p.frontier.replan_period_s = 1e-3f;
    p.frontier.draw_period_s = 0.0f;
    if (ex->configure(p, BeamGeometry::of(world.scan(laser, 1, 5, 0))) != Status::kOk) return false;
    for (int k = 0; k < 80; ++k)
      cycle(1.0f + 0.07f * static_cast<float>(k), 5.0f + std::sin(0.1f * static_cast<float>(k)),
            0.08f * static_cast<float>(k), true);
    return ex->plan_in_flight().has_goal;
  }
  void cycle(float x, float y, float heading, bool level3) {
    t += 0.1;
    const auto s = std::make_unique<LaserScan>(world.scan(laser, x, y, heading, TimeUs::from_s(t)));
    step_with(*s, x, y, heading, level3);
  }
  void step_with(LaserScan& s, float x, float y, float heading, bool level3) {
    NavState nav;
    nav.valid = true;
    nav.position_m = {x, y, 1.0f};
    nav.heading_rad = heading;
    (void)ex->step(nav, s, out);
    if (level3) ex->background_step();
  }
};

void frontier_cycle(benchmark::State& state, const test::LaserModel& laser, bool level3) {
  FrontierHall h(laser);
  if (!h.start(level3)) {
    state.SkipWithError("no plan after the walk");
    return;
  }
  auto scan = std::make_unique<LaserScan>(h.world.scan(laser, 6.5, 5.0, 0.2));
  for (auto _ : state) {
    h.t += 0.1;
    scan->stamp = TimeUs::from_s(h.t);
    h.step_with(*scan, 6.5f, 5.0f, 0.2f, level3);
    benchmark::DoNotOptimize(h.out.velocity_mps.x());
  }
  state.counters["frontiers"] = static_cast<double>(h.ex->frontiers().size());
  state.counters["peak_open"] = static_cast<double>(h.ex->counters().peak_open);
}
void BM_FrontierCycleUrg(benchmark::State& s) { frontier_cycle(s, test::LaserModel::urg04lx(), true); }
void BM_FrontierCycleUtm(benchmark::State& s) { frontier_cycle(s, test::LaserModel::utm30lx(), true); }
void BM_FrontierGuidanceUrg(benchmark::State& s) { frontier_cycle(s, test::LaserModel::urg04lx(), false); }
void BM_FrontierGuidanceUtm(benchmark::State& s) { frontier_cycle(s, test::LaserModel::utm30lx(), false); }

BENCHMARK(BM_GuidanceStepUrg)->Name("exploration/guidance_step/urg04lx_682");
BENCHMARK(BM_FrontierCycleUrg)->Name("exploration/frontier_plan_cycle/urg04lx_682_hall_15x10m");
BENCHMARK(BM_FrontierCycleUtm)->Name("exploration/frontier_plan_cycle/utm30lx_1081_hall_15x10m");
BENCHMARK(BM_FrontierGuidanceUrg)->Name("exploration/frontier_guidance/urg04lx_682");
BENCHMARK(BM_FrontierGuidanceUtm)->Name("exploration/frontier_guidance/utm30lx_1081");
BENCHMARK(BM_GuidanceStepUtm)->Name("exploration/guidance_step/utm30lx_1081");
BENCHMARK(BM_ApproachCornerUrg)->Name("exploration/approach_limit_corner/urg04lx_682");
BENCHMARK(BM_ApproachCornerUtm)->Name("exploration/approach_limit_corner/utm30lx_1081");
BENCHMARK(BM_SrtArrivalUrg)->Name("exploration/srt_arrival/urg04lx_682");
BENCHMARK(BM_SrtArrivalUtm)->Name("exploration/srt_arrival/utm30lx_1081");
BENCHMARK(BM_SectorScanUrg)->Name("exploration/sector_scan/urg04lx_682");
BENCHMARK(BM_SectorScanCorridorUrg)->Name("exploration/sector_scan/urg04lx_682_corridor");
BENCHMARK(BM_SectorScanTablesUrg)->Name("exploration/sector_scan_new_tables/urg04lx_682");
BENCHMARK(BM_SrtArrivalCyclesUrg)->Name("exploration/srt_arrival_cycles/urg04lx_682")->DenseRange(1, 8);
BENCHMARK(BM_SrtArrivalCyclesCorridorUrg)
    ->Name("exploration/srt_arrival_cycles/urg04lx_682_corridor")
    ->DenseRange(1, 16);
BENCHMARK(BM_SrtArrivalCyclesUtm)->Name("exploration/srt_arrival_cycles/utm30lx_1081")->DenseRange(1, 8);
BENCHMARK(BM_SrtRetraceCyclesUrg)->Name("exploration/srt_retrace_cycles/urg04lx_682")->DenseRange(0, 24);
BENCHMARK(BM_UnflownCount)->Name("exploration/unflown_count");
BENCHMARK(BM_UnflownCountAllUnflown)->Name("exploration/unflown_count_all_unflown");
BENCHMARK(BM_FrontierCountNothingSeen)->Name("exploration/frontier_count_nothing_seen");
BENCHMARK(BM_FrontierCount)->Name("exploration/frontier_count");
BENCHMARK(BM_GuidanceStepFrontierMarksUrg)->Name("exploration/guidance_step_frontier_marks/urg04lx_682");
BENCHMARK(BM_GuidanceStepFrontierMarksUtm)->Name("exploration/guidance_step_frontier_marks/utm30lx_1081");
BENCHMARK(BM_TrailSearch)->Name("exploration/trail_search/1024");

}  // namespace
