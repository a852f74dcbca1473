// A kinematic closed loop for the four explorers: a point vehicle that does exactly what it is
// told (velocity commands integrated, position set-points tracked by a saturated proportional
// law, heading commands obeyed at once) flies through a synthetic building ray-cast in this
// file, with a URG-04LX at 10 Hz and perfect navigation. Paper 002's claims, checked:
//   - the blend (Algorithm 1) passes the narrow gap and explores the inner room (Fig. 5);
//   - wall following alone tracks the outer walls and leaves the inner room unexplored
//     (section I-B);
//   - SRT-Star alone explores too (it is a complete frontier method), with waypoints sent
//     straight as position set-points;
//   - paper 003's grid frontier explorer explores all of it and says when it is done.
// The full closed loop with vehicle dynamics, EKF and controller in the simulator comes with
// kestrel-sim --mission explore; this test isolates the guidance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/exploration/blend_explorer.hpp"
#include "kestrel/exploration/frontier_explorer.hpp"
#include "kestrel/exploration/srt_explorer.hpp"
#include "kestrel/exploration/wall_follow_explorer.hpp"
#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using test::LaserModel;
using test::SegmentWorld;

// 14 m x 10 m. A partition at x = 5 closes the start room but for a 1.2 m gap at its north end;
// the east hall holds an inner room [7.5, 12.5] x [2.5, 7.5] whose only door (1.2 m) is in its
// west wall. The inner room's far half is more than the laser's 4 m from anywhere outside it:
// it can only be explored from inside.
struct Building {
  SegmentWorld world;
  static constexpr double kW = 14, kH = 10;
  Building() {
    world.add_box(0, 0, kW, kH);
    world.add(5, 0, 5, 8.8);         // partition, gap y in [8.8, 10]
    world.add(7.5, 2.5, 12.5, 2.5);  // inner room
    world.add(12.5, 2.5, 12.5, 7.5);
    world.add(12.5, 7.5, 7.5, 7.5);
    world.add(7.5, 7.5, 7.5, 5.6);  // door y in [4.4, 5.6]
    world.add(7.5, 4.4, 7.5, 2.5);
  }
  static bool in_east(double x, double) { return x > 5.3; }
  static bool in_inner(double x, double y) { return x > 7.7 && x < 12.3 && y > 2.7 && y < 7.3; }
};

// Cells of 0.2 m seen by the laser (every stride-th beam, up to its return).
class CoverageGrid {
 public:
  static constexpr double kCell = 0.2;
  CoverageGrid()
      : nx_(static_cast<int>(Building::kW / kCell)),
        ny_(static_cast<int>(Building::kH / kCell)),
        seen_(static_cast<std::size_t>(nx_ * ny_), false) {}
  void mark(const LaserScan& s, double x, double y, double heading, int stride) {
    for (int i = 0; i < s.beam_count; i += stride) {
      const uint16_t r = s.range_mm[i];
      const double range =
          r >= kMinValidRangeMm ? r * 1e-3 : (r == range_code::kNoReturn ? s.max_range_mm * 1e-3 : 0.0);
      const double a = heading + s.angle_of(static_cast<std::size_t>(i));
      const double c = std::cos(a), sn = std::sin(a);
      for (double t = 0; t < range; t += 0.5 * kCell) {
        const int cx = static_cast<int>((x + t * c) / kCell), cy = static_cast<int>((y + t * sn) / kCell);
        if (cx >= 0 && cy >= 0 && cx < nx_ && cy < ny_) {
          auto cell = seen_[static_cast<std::size_t>(cy * nx_ + cx)];
          if (!cell) {
            cell = true;
            ++count_;
          }
        }
      }
    }
  }
  double fraction() const { return static_cast<double>(count_) / static_cast<double>(seen_.size()); }
  // Seen fraction of the cells whose centres satisfy `inside`.
  template <class F>
  double fraction_where(F inside) const {
    int n = 0, s = 0;
    for (int cy = 0; cy < ny_; ++cy)
      for (int cx = 0; cx < nx_; ++cx)
        if (inside((cx + 0.5) * kCell, (cy + 0.5) * kCell)) {
          ++n;
          s += seen_[static_cast<std::size_t>(cy * nx_ + cx)] ? 1 : 0;
        }
    return n > 0 ? static_cast<double>(s) / n : 0.0;
  }

 private:
  int nx_, ny_;
  std::vector<bool> seen_;
  int count_ = 0;
};

struct FlightLog {
  double coverage = 0;
  double inner_coverage = 0;
  double t_east_s = -1, t_inner_s = -1, t_cov90_s = -1, t_finished_s = -1;
  double min_clearance_m = 1e9;
  double distance_m = 0;
  double finished_x = 0, finished_y = 0;  // where the explorer first said it was done
  int collisions = 0;
  uint32_t restarts = 0;
  uint32_t retraces = 0;
  std::size_t nodes = 0;
  uint64_t allocations = 0;
};

// `tune` changes the explorer's defaults before it is configured (nullptr: the defaults).
FlightLog fly(Explorer& ex, double duration_s, uint32_t seed, int stride, void (*tune)(Params&) = nullptr) {
  const Building b;
  const LaserModel urg = LaserModel::urg04lx();
  Params p;
  p.srt.seed = seed;
  if (tune != nullptr) tune(p);
  EXPECT_EQ(ex.configure(p, BeamGeometry::of(b.world.scan(urg, 1, 1, 0))), Status::kOk);
  CoverageGrid grid;
  FlightLog log;
  double x = 2.5, y = 3.0, heading = 0.3;
  const double dt = 0.1;
  constexpr double kVehicleRadius = 0.2;
  constexpr double kPositionGain = 1.0;  // 1/s, for kPosition set-points
  LaserScan scan;
  GuidanceSetpoint out;
  NavState nav;
  nav.valid = true;
  // KESTREL_EXPLORE_TRACE=DIR writes the flight (t x y heading mode target) for inspection.
  FILE* trace = nullptr;
  if (const char* dir = std::getenv("KESTREL_EXPLORE_TRACE")) {
    const std::string path = std::string(dir) + "/" + to_string(ex.kind()) + "_" + std::to_string(seed) + ".txt";
    trace = std::fopen(path.c_str(), "w");
  }
  for (int k = 0; k * dt < duration_s; ++k) {
    const double t = k * dt;
    scan = b.world.scan(urg, x, y, heading, TimeUs::from_s(t));
    grid.mark(scan, x, y, heading, stride);
    nav.stamp = scan.stamp;
    nav.position_m = {static_cast<float>(x), static_cast<float>(y), 1.0f};
    nav.heading_rad = static_cast<float>(heading);
    {
      alloc_guard::Scope guard;
      EXPECT_EQ(ex.step(nav, scan, out), Status::kOk);
      ex.background_step();  // level 3 in lockstep, as kestrel-sim runs it
      log.allocations += guard.allocations();
    }
    double vx = out.velocity_mps.x(), vy = out.velocity_mps.y();
    if (out.mode == GuidanceSetpoint::Mode::kPosition) {
      vx = kPositionGain * (out.position_m.x() - x);
      vy = kPositionGain * (out.position_m.y() - y);
      const double n = std::hypot(vx, vy), vmax = p.guidance.speed_limit_mps;
      if (n > vmax) vx *= vmax / n, vy *= vmax / n;
    }
    x += vx * dt;
    y += vy * dt;
    log.distance_m += std::hypot(vx, vy) * dt;
    heading = out.heading_rad;
    if (trace) {
      const SrtStarPlanner* pl = ex.planner();
      std::fprintf(trace, "%.1f %.3f %.3f %.3f %s %.3f %.3f %.3f %.3f %zu\n", t, x, y, heading,
                   pl ? to_string(pl->mode()) : "-", ex.status().target.x, ex.status().target.y, out.velocity_mps.x(),
                   out.velocity_mps.y(), pl ? pl->tree().nodes().size() : 0);
    }
    const double clearance = b.world.clearance(x, y);
    log.min_clearance_m = std::min(log.min_clearance_m, clearance);
    if (clearance < kVehicleRadius) ++log.collisions;
    if (log.t_east_s < 0 && Building::in_east(x, y)) log.t_east_s = t;
    if (log.t_inner_s < 0 && Building::in_inner(x, y)) log.t_inner_s = t;
    if (log.t_cov90_s < 0 && grid.fraction() >= 0.9) log.t_cov90_s = t;
    if (log.t_finished_s < 0 && ex.finished()) {
      log.t_finished_s = t;
      log.finished_x = x;
      log.finished_y = y;
    }
  }
  if (trace) std::fclose(trace);
  log.coverage = grid.fraction();
  log.inner_coverage = grid.fraction_where(Building::in_inner);
  if (const SrtStarPlanner* pl = ex.planner()) {
    log.restarts = pl->restarts();
    log.retraces = pl->retraces();
    log.nodes = pl->tree().nodes().size();
  }
  std::printf(
      "[ kinematic ] %-10s seed %u: coverage %.3f (90%% at %.0f s), inner room %.3f, east at %.0f s, inner at %.0f s, "
      "finished at %.0f s, distance %.0f m, min clearance %.2f m, collisions %d, restarts %u, retraces %u, nodes %zu\n",
      to_string(ex.kind()), seed, log.coverage, log.t_cov90_s, log.inner_coverage, log.t_east_s, log.t_inner_s,
      log.t_finished_s, log.distance_m, log.min_clearance_m, log.collisions, log.restarts, log.retraces, log.nodes);
  return log;
}

// Under qemu-arm (10-50x slower, and the Verdex emulates its floating point) one seed per
// explorer and a shorter flight (Overo 400 s, Verdex 240 s) keep the test within minutes; the host runs ten
// seeds for 15 minutes of flight each. KESTREL_KINEMATIC_SHORT=1 runs the short version on the
// host (KESTREL_KINEMATIC_SHORT=240 with the Verdex's flight time), to check that its
// assertions hold.
//
// SRT-Star draws its waypoints at random, so whether a flight gets through a door depends on
// where the nodes happen to fall (a node that lands beside a jamb may have no clear ray
// within ray_search_sectors of the door's frontier, drops it, and exploration can end in the
// start room; a tree that runs out is not trusted at once, see srt_star_planner.hpp).
// Collisions, clearance and allocations are checked on every flight; exploring the inner room
// is asked of a share of the flights: measured on seeds 1-10 with the defaults (a
// discontinuity frontier needs a jump between neighbouring beams, the trees grown after a
// restart are steered), blend 9 and SRT 9 (before the beam jumps, 9 and 7; drawn as paper 002
// draws, 8 and 10; earlier, while a first tree that ran out ended exploration, 7 and 5); the
// short runs fly seeds 1 and 2 and ask for one.
struct Scale {
  double flight_s;
  std::vector<uint32_t> seeds;
  int coverage_beam_stride;
  // At least `tenths` of the flights, and one.
  std::size_t successes_needed(std::size_t tenths) const {
    return std::max<std::size_t>(1, seeds.size() >= 10 ? seeds.size() * tenths / 10 : 1);
  }
};
Scale scale() {
  const char* forced = std::getenv("KESTREL_KINEMATIC_SHORT");  // "1", or the flight in seconds
  const bool short_run = !KESTREL_TEST_ON_HOST || forced != nullptr;
  if (!short_run) return {900, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, 2};
  double flight_s = KESTREL_TEST_ON_VERDEX ? 240.0 : 400.0;
  if (forced != nullptr && std::atof(forced) > 1.0) flight_s = std::atof(forced);
  return {flight_s, {1, 2}, 6};
}

TEST(KinematicClosedLoop, BlendPassesTheGapAndExploresTheInnerRoom) {
  const Scale sc = scale();
  std::size_t explored = 0;
  for (uint32_t seed : sc.seeds) {
    auto ex = std::make_unique<BlendExplorer>();
    const FlightLog log = fly(*ex, sc.flight_s, seed, sc.coverage_beam_stride);
    EXPECT_EQ(log.collisions, 0) << "seed " << seed;
    EXPECT_GE(log.min_clearance_m, 0.3) << "seed " << seed;  // wall following keeps clear
    EXPECT_EQ(log.allocations, 0u);
    // Through the 1.2 m gap, into the inner room, and most of the building seen.
    explored += log.t_east_s >= 0 && log.t_inner_s >= 0 && log.inner_coverage >= 0.95 && log.coverage >= 0.95;
  }
  EXPECT_GE(explored, sc.successes_needed(7));
}

TEST(KinematicClosedLoop, WallFollowingAloneLeavesRoomsUnexplored) {
  const Scale sc = scale();
  auto ex = std::make_unique<WallFollowExplorer>();
  const FlightLog log = fly(*ex, sc.flight_s, 1, sc.coverage_beam_stride);
  EXPECT_EQ(log.collisions, 0);
  // It circles the start room at about r_t from its walls: a gap narrower than 2 r_t is never
  // taken, and the inner room is never seen.
  EXPECT_LT(log.t_inner_s, 0);
  EXPECT_LT(log.inner_coverage, 0.2);
  EXPECT_LT(log.coverage, 0.6);
  EXPECT_EQ(log.allocations, 0u);
}

// SRT alone has nothing between its straight lines and the walls but the clearance it checked
// when it drew them: a backtrack from within d / 2 of a node flies the tree edge back to the
// parent unchecked, and the edge was flown forward from up to d beside the parent. Before the
// planner closed in on a node to choose again (close_in_to_choose), seed 1 grazed the
// partition's end so at 336 s, 0.13 m from the vehicle's centre; since, no flight of seeds 1-10
// comes nearer than 0.21 m, but the unchecked edge remains. So one flight may touch (not the
// blend's, which the approach limiter guards), and none by more than half the vehicle's 0.2 m
// radius.
TEST(KinematicClosedLoop, SrtAloneExploresWithPositionSetpoints) {
  const Scale sc = scale();
  std::size_t explored = 0, touched = 0;
  for (uint32_t seed : sc.seeds) {
    auto ex = std::make_unique<SrtExplorer>();
    const FlightLog log = fly(*ex, sc.flight_s, seed, sc.coverage_beam_stride);
    touched += log.collisions > 0 ? 1 : 0;
    EXPECT_GE(log.min_clearance_m, 0.1) << "seed " << seed;
    EXPECT_EQ(log.allocations, 0u);
    explored += log.t_inner_s >= 0 && log.inner_coverage >= 0.95;
  }
  EXPECT_LE(touched, 1u);
  EXPECT_GE(explored, sc.successes_needed(7));
}

// srt.retrace counting the coarse grid's frontier (RetraceTarget::kFrontier): a flight ends
// once what the laser has shown holds no frontier in reach of the path flown. Seeds 1-10 over
// 900 s on the host: every flight through the inner room with all of the building seen, and
// every one finished (at 374-889 s; two retraced once); counting unflown cells instead, 6 of
// the 10 finished. The short runs under qemu are too short to finish: explored and clear only.
TEST(KinematicClosedLoop, BlendRetracingToTheFrontierFinishesOnceTheBuildingIsSeen) {
  const Scale sc = scale();
  std::size_t explored = 0, finished = 0;
  for (uint32_t seed : sc.seeds) {
    auto ex = std::make_unique<BlendExplorer>();
    const FlightLog log = fly(*ex, sc.flight_s, seed, sc.coverage_beam_stride, [](Params& p) {
      p.srt.retrace = RetraceMode::kAlways;
      p.srt.retrace_target = RetraceTarget::kFrontier;
    });
    EXPECT_EQ(log.collisions, 0) << "seed " << seed;
    EXPECT_GE(log.min_clearance_m, 0.3) << "seed " << seed;
    EXPECT_EQ(log.allocations, 0u);
    const bool all_seen = log.t_inner_s >= 0 && log.inner_coverage >= 0.95 && log.coverage >= 0.95;
    explored += all_seen ? 1 : 0;
    finished += all_seen && log.t_finished_s >= 0 ? 1 : 0;
  }
  EXPECT_GE(explored, sc.successes_needed(9));
  if (sc.flight_s >= 900) {
    EXPECT_GE(finished, sc.successes_needed(9));
  }
}

// The grid frontier explorer draws nothing at random: one flight says what it does. It flies
// to the nearest frontier by path cost until none is left, through the 1.2 m gap and the inner
// room's door (all of it seen by 77 s on the host; 157 s before a scan counted once per grid
// cell, when rays grazing the far side of a wall's cells wore them away), flies home on its
// grid and then reports finished (111 s on every target: the flights agree), so every target
// flies 180 s.
TEST(KinematicClosedLoop, FrontierExplorerExploresEverythingAndFinishes) {
  const Scale sc = scale();
  auto ex = std::make_unique<FrontierExplorer>();
  const FlightLog log = fly(*ex, 180.0, 1, sc.coverage_beam_stride);
  EXPECT_EQ(log.collisions, 0);
  EXPECT_GE(log.min_clearance_m, 0.3);
  EXPECT_EQ(log.allocations, 0u);
  EXPECT_GE(log.t_inner_s, 0);
  EXPECT_GE(log.inner_coverage, 0.95);
  EXPECT_GE(log.coverage, 0.95);
  EXPECT_GE(log.t_finished_s, 0);
  EXPECT_GT(ex->counters().goals, 3u);
  EXPECT_EQ(ex->counters().homed, 1u);
  // Home, the take-off point, within the arrival distance and half a cell's diagonal.
  EXPECT_LT(std::hypot(log.finished_x - 2.5, log.finished_y - 3.0), 0.39);
}

}  // namespace
}  // namespace kestrel::exploration
