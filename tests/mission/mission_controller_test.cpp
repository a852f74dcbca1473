#include "kestrel/mission/mission_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <limits>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/core/angle.hpp"
#include "synthetic_world.hpp"

namespace kestrel::mission {
namespace {

// A vehicle that goes exactly where it is told, at most `speed` per second: enough to drive
// the state machine through its phases.
struct PointVehicle {
  NavState nav;
  float speed = 1.0f;
  // What stops it below, in the estimate's frame: the floor, a desk under it (0.75), or the
  // floor where the estimate's height is off by a desk's (-0.75).
  float surface_z = 0.0f;
  void follow(const GuidanceSetpoint& s, float dt) {
    Eigen::Vector3f target = s.position_m;
    if (s.mode == GuidanceSetpoint::Mode::kVelocity) {
      target = nav.position_m + s.velocity_mps * dt;
      target.z() = s.position_m.z();
    }
    Eigen::Vector3f d = target - nav.position_m;
    const float max_step = speed * dt;
    if (d.norm() > max_step) d *= max_step / d.norm();
    if (nav.position_m.z() + d.z() < surface_z) d.z() = surface_z - nav.position_m.z();  // it stops it
    nav.velocity_mps = d / dt;
    nav.position_m += d;
  }
};

// Whatever the estimate, no NaN or infinity reaches the controller.
bool finite(const GuidanceSetpoint& s) {
  return s.position_m.allFinite() && s.velocity_mps.allFinite() && std::isfinite(s.heading_rad);
}

struct MissionRun {
  MissionController mc;
  PointVehicle v;
  TimeUs t;
  static constexpr float kDt = 0.025f;

  MissionRun() {
    v.nav.valid = true;
    v.nav.position_m = {1, 2, 0};
  }
  // With `altimeter` on, every step reads the height over the surface under the vehicle, as a
  // laser's deflected beams do: nothing nearer than `altimeter_min_m`. Where its spot reads
  // down to something else than what holds the vehicle (a rim beside the spot), that is
  // `altimeter_floor_z`.
  bool altimeter = false;
  float altimeter_min_m = 0.0f;
  float altimeter_floor_z = std::numeric_limits<float>::quiet_NaN();
  GuidanceSetpoint step(const ExplorerOutput* e = nullptr) {
    t += Duration::from_s(kDt);
    v.nav.stamp = t;
    const float under = std::isnan(altimeter_floor_z) ? v.surface_z : altimeter_floor_z;
    const float height = v.nav.position_m.z() - under;
    if (altimeter && height >= altimeter_min_m) {
      newest = {t, height, 1e-4f};
      have_reading = true;
    }
    const GuidanceSetpoint s = mc.step(t, v.nav, e, nullptr, have_reading ? &newest : nullptr);
    v.follow(s, kDt);
    return s;
  }
  AltimeterSample newest;
  bool have_reading = false;
  // One step on an estimate other than the vehicle's (an invalid or NaN one), stamped with the
  // step's time so that only its content, not its age, is bad; the vehicle does not move.
  GuidanceSetpoint step_on(NavState nav, const ExplorerOutput* e = nullptr) {
    t += Duration::from_s(kDt);
    nav.stamp = t;
    return mc.step(t, nav, e);
  }
  bool run_until(Phase p, float max_s, const ExplorerOutput* e = nullptr) {
    for (float s = 0; s < max_s; s += kDt) {
      step(e);
      if (mc.phase() == p) return true;
    }
    return false;
  }
  // A hover mission, `hover_s` at the set-point and default parameters otherwise, flown until
  // it reaches phase p.
  bool hover_until(Phase p, float max_s, float hover_s = MissionParams{}.hover_duration_s) {
    MissionParams params;
    params.hover_duration_s = hover_s;
    return mc.configure(MissionKind::kHover, params) == Status::kOk && run_until(p, max_s);
  }
  struct Leg {
    Eigen::Vector3f velocity_mps;
    int steps;
  };
  // An explore mission that takes off, flies the explorer's legs at velocity set-points, and
  // is told exploring has finished. False unless it is then on its way home.
  bool explore_then_finish(const MissionParams& p, ExplorerOutput& e, std::initializer_list<Leg> legs) {
    if (mc.configure(MissionKind::kExplore, p) != Status::kOk) return false;
    e = ExplorerOutput{};
    e.setpoint.mode = GuidanceSetpoint::Mode::kVelocity;
    if (!run_until(Phase::kExplore, 10, &e)) return false;
    for (const Leg& leg : legs) {
      e.setpoint.velocity_mps = leg.velocity_mps;
      for (int i = 0; i < leg.steps; ++i) step(&e);
    }
    e.finished = true;
    step(&e);
    return mc.phase() == Phase::kReturn;
  }
};

TEST(MissionController, HoverMissionTakesOffHoversAndLands) {
  MissionRun r;
  MissionParams p;
  p.hover_duration_s = 5;
  ASSERT_EQ(r.mc.configure(MissionKind::kHover, p), Status::kOk);
  EXPECT_FALSE(r.mc.wants_armed());
  ASSERT_TRUE(r.run_until(Phase::kHover, 10));
  EXPECT_TRUE(r.mc.wants_armed());
  EXPECT_NEAR(r.v.nav.position_m.z(), 1.0f, 0.15f);
  EXPECT_NEAR(r.v.nav.position_m.x(), 1.0f, 1e-4f);
  const TimeUs hover_start = r.t;
  ASSERT_TRUE(r.run_until(Phase::kLand, 10));
  EXPECT_NEAR((r.t - hover_start).seconds(), 5.0, 0.1);
  ASSERT_TRUE(r.run_until(Phase::kLanded, 10));
  EXPECT_TRUE(r.mc.finished());
  EXPECT_FALSE(r.mc.wants_armed());
}

// GIVEN a valid estimate WHEN the mission starts THEN the vehicle rests on the ground for
// preflight_s (at rest, motors off: the filter's zero-velocity window) and only then takes off.
TEST(MissionController, RestsOnTheGroundForThePreflightTimeFirst) {
  MissionRun r;
  MissionParams p;
  p.preflight_s = 2.0f;
  ASSERT_EQ(r.mc.configure(MissionKind::kHover, p), Status::kOk);
  const TimeUs start = r.t + Duration::from_s(MissionRun::kDt);  // the first step's time
  while (r.mc.phase() == Phase::kIdle && (r.t - start).seconds() < 5.0) {
    EXPECT_TRUE(r.mc.at_rest());
    EXPECT_FALSE(r.mc.wants_armed());
    const GuidanceSetpoint s = r.step();
    if (r.mc.phase() == Phase::kIdle) {
      EXPECT_LT(s.position_m.z(), 0.01f);  // stays on the floor
    }
  }
  EXPECT_EQ(r.mc.phase(), Phase::kTakeoff);
  EXPECT_NEAR((r.t - start).seconds(), 2.0, 0.03);
  EXPECT_FALSE(r.mc.at_rest());
  EXPECT_TRUE(r.mc.wants_armed());
}

// GIVEN a rest on the ground WHEN the estimate goes stale part-way (a device fell silent: the
// stack tells the mission so, sensor_watchdog.hpp) THEN nothing takes off on it: the vehicle
// stays on the ground, and the rest starts again, preflight_s from when the estimate is back.
// Before, the rest counted from the first estimate only, so a laser gone quiet on the ground
// still let the vehicle take off when the time was up.
TEST(MissionController, AStaleEstimateOnTheGroundStartsThePreflightAgain) {
  MissionRun r;
  MissionParams p;
  p.preflight_s = 2.0f;
  ASSERT_EQ(r.mc.configure(MissionKind::kHover, p), Status::kOk);
  for (int i = 0; i < 60; ++i) r.step();  // 1.5 s of the rest
  r.v.nav.valid = false;
  for (int i = 0; i < 200; ++i) {  // 5 s stale, longer than the whole rest
    const GuidanceSetpoint s = r.step();
    EXPECT_EQ(r.mc.phase(), Phase::kIdle);
    EXPECT_FALSE(r.mc.wants_armed());
    EXPECT_TRUE(finite(s));
  }
  r.v.nav.valid = true;
  const TimeUs back = r.t + Duration::from_s(MissionRun::kDt);
  ASSERT_TRUE(r.run_until(Phase::kTakeoff, 5));
  EXPECT_NEAR((r.t - back).seconds(), 2.0, 0.03);
}

TEST(MissionController, WaypointsAreVisitedInOrderWithHolds) {
  MissionRun r;
  StaticVector<Waypoint, 4> wps;
  ASSERT_TRUE(wps.push_back({{3, 2, 1}, 0, 1.0f}));
  ASSERT_TRUE(wps.push_back({{3, 5, 1.5f}, 1.0f, 0}));
  ASSERT_EQ(r.mc.configure(MissionKind::kWaypoints, {}, &wps), Status::kOk);
  ASSERT_TRUE(r.run_until(Phase::kWaypoints, 10));
  bool saw_second = false;
  for (int i = 0; i < 2000 && r.mc.phase() == Phase::kWaypoints; ++i) {
    r.step();
    if (r.mc.waypoint_index() == 1) {
      saw_second = true;
      EXPECT_NEAR(r.v.nav.position_m.x(), 3.0f, 0.2f);  // left only after reaching the first
    }
  }
  EXPECT_TRUE(saw_second);
  EXPECT_EQ(r.mc.phase(), Phase::kLand);
  EXPECT_NEAR(r.v.nav.position_m.y(), 5.0f, 0.2f);
}

TEST(MissionController, ExploreThenReturnsAlongTheTrailAndLandsAtHome) {
  MissionRun r;
  MissionParams p;
  ExplorerOutput e;
  // Explore an L: +x for 4 s then +y for 3 s, at 0.5 m/s.
  ASSERT_TRUE(r.explore_then_finish(p, e, {{{0.5f, 0, 0}, 160}, {{0, 0.5f, 0}, 120}}));
  EXPECT_NEAR(r.v.nav.position_m.x(), 3.0f, 0.2f);
  EXPECT_NEAR(r.v.nav.position_m.y(), 3.5f, 0.2f);
  // On the way home it must pass the corner of the L, never cut across it.
  bool passed_corner = false;
  float heading = r.v.nav.heading_rad;
  float heading_on_first_leg = NAN;
  for (int i = 0; i < 4000 && r.mc.phase() == Phase::kReturn; ++i) {
    const GuidanceSetpoint s = r.step(&e);
    if ((r.v.nav.position_m.head<2>() - Eigen::Vector2f(3.0f, 2.0f)).norm() < 0.35f) passed_corner = true;
    // Velocity set-points (the composition bounds them against the scan) at the return speed.
    if (r.mc.phase() == Phase::kReturn) {
      EXPECT_EQ(s.mode, GuidanceSetpoint::Mode::kVelocity);
    }
    EXPECT_LE(s.velocity_mps.norm(), p.return_speed_mps + 1e-4f);
    // The heading turns towards the way home, never faster than the return yaw rate.
    EXPECT_LE(std::fabs(angle_diff(s.heading_rad, heading)), p.return_yaw_rate_radps * MissionRun::kDt + 1e-4f);
    heading = s.heading_rad;
    if (r.v.nav.position_m.y() > 2.6f && r.v.nav.position_m.y() < 2.9f) heading_on_first_leg = heading;
  }
  EXPECT_TRUE(passed_corner);
  EXPECT_TRUE(r.mc.returned_home());
  // Down the L's +y leg towards its corner the heading has turned from 0 (where exploring
  // ended) towards -y, the way home, without overshooting it.
  EXPECT_LT(heading_on_first_leg, -0.5f);
  EXPECT_GT(heading_on_first_leg, -M_PI / 2 - 0.05);
  EXPECT_EQ(r.mc.phase(), Phase::kLand);
  EXPECT_NEAR(r.v.nav.position_m.x(), 1.0f, 0.2f);
  EXPECT_NEAR(r.v.nav.position_m.y(), 2.0f, 0.2f);
}

// GIVEN an explore mission out along an L WHEN, at its end, the estimate is corrected 0.5 m
// east from the L's corner on (a SLAM correction, seconds late: the filter's state moves, and
// so does its path since the correction's stamp) THEN the flight home comes down the L's leg
// where the corrected estimate puts it, not where the estimate stood when it was drawn.
TEST(MissionController, TheTrailMovesWithALateCorrectionOfTheEstimate) {
  for (const bool told : {true, false}) {
    MissionRun r;
    MissionParams p;
    p.return_shortcut = false;
    ExplorerOutput e;
    ASSERT_TRUE(r.mc.configure(MissionKind::kExplore, p) == Status::kOk);
    e.setpoint.mode = GuidanceSetpoint::Mode::kVelocity;
    ASSERT_TRUE(r.run_until(Phase::kExplore, 10, &e));
    e.setpoint.velocity_mps = {0.5f, 0, 0};
    for (int i = 0; i < 160; ++i) r.step(&e);
    const TimeUs corner = r.t;
    e.setpoint.velocity_mps = {0, 0.5f, 0};
    for (int i = 0; i < 160; ++i) r.step(&e);
    const Pose2 delta{0.5f, 0, 0};
    r.v.nav.position_m.x() += 0.5f;
    if (told) r.mc.estimate_moved(corner, delta);
    e.finished = true;
    r.step(&e);
    ASSERT_EQ(r.mc.phase(), Phase::kReturn);
    float worst = 0;  // from the leg's corrected line, x = 3.5, on the way down it
    for (int i = 0; i < 4000 && r.mc.phase() == Phase::kReturn; ++i) {
      r.step(&e);
      if (r.v.nav.position_m.y() > 2.5f) worst = std::max(worst, std::fabs(r.v.nav.position_m.x() - 3.5f));
    }
    EXPECT_TRUE(r.mc.returned_home()) << told;
    if (told) {
      EXPECT_LT(worst, 0.1f);
    } else {
      EXPECT_GT(worst, 0.4f);  // the old trail, half a metre west
    }
  }
}

// GIVEN an explore mission home again WHEN it lands THEN the descent flies velocity set-points
// towards home, which the composition bounds against the scan (home is a point of the
// estimate's frame and may have drifted against a wall), and it settles there; a hover
// mission, with no drift to fear, still lands on a position set-point.
TEST(MissionController, LandingAfterExploringFliesBoundableVelocitySetPoints) {
  MissionRun r;
  MissionParams p;
  ExplorerOutput e;
  ASSERT_TRUE(r.explore_then_finish(p, e, {{{0.5f, 0, 0}, 160}}));
  ASSERT_TRUE(r.run_until(Phase::kLand, 60, &e));
  ASSERT_TRUE(r.mc.returned_home());
  // Offset the vehicle within the arrival radius, as a limiter holding it off a wall would.
  r.v.nav.position_m.x() += 0.12f;
  float last_z = r.v.nav.position_m.z() + 1.0f;
  int land_steps = 0;
  for (int i = 0; i < 2000 && r.mc.phase() == Phase::kLand; ++i, ++land_steps) {
    const Eigen::Vector2f to_home = r.mc.home().head<2>() - r.v.nav.position_m.head<2>();
    const GuidanceSetpoint s = r.step(&e);
    if (r.mc.phase() != Phase::kLand) break;
    ASSERT_EQ(s.mode, GuidanceSetpoint::Mode::kVelocity);
    EXPECT_LE(s.velocity_mps.head<2>().norm(), to_home.norm() + 1e-4f);  // 1/s towards home
    if (to_home.norm() > 1e-2f) {
      EXPECT_GT(s.velocity_mps.head<2>().dot(to_home), 0.0f);
    }
    EXPECT_LE(s.position_m.z(), last_z);  // the descent ramp never climbs
    last_z = s.position_m.z();
  }
  EXPECT_GT(land_steps, 10);
  EXPECT_EQ(r.mc.phase(), Phase::kLanded);
  EXPECT_NEAR(r.v.nav.position_m.x(), r.mc.home().x(), 0.02f);
  EXPECT_NEAR(r.v.nav.position_m.y(), r.mc.home().y(), 0.02f);

  MissionRun hover;
  p.hover_duration_s = 1;
  ASSERT_EQ(hover.mc.configure(MissionKind::kHover, p), Status::kOk);
  ASSERT_TRUE(hover.run_until(Phase::kLand, 20));
  EXPECT_EQ(hover.step().mode, GuidanceSetpoint::Mode::kPosition);
}

// GIVEN the way home along the trail WHEN the vehicle is home before the trail's end (an
// explorer that flew home itself: the frontier explorer's grid path) THEN it lands there and
// does not fly the rest of the trail out and back.
TEST(MissionController, HomeReachedAnywhereOnTheTrailLands) {
  MissionRun r;
  MissionParams p;
  ExplorerOutput e;
  ASSERT_TRUE(r.explore_then_finish(p, e, {{{0.5f, 0, 0}, 160}, {{0, 0.5f, 0}, 120}}));
  ASSERT_GT(r.mc.trail().size(), 3u);
  // Within 0.3 m of home, still moving (as the explorer's own flight home leaves it): the
  // last leg is to home, and there it lands, without going out along the trail.
  r.v.nav.position_m.head<2>() = r.mc.home().head<2>() + Eigen::Vector2f(0.25f, 0.0f);
  r.v.nav.velocity_mps = {0.3f, 0.0f, 0.0f};
  float farthest = 0;
  for (int i = 0; i < 400 && r.mc.phase() == Phase::kReturn; ++i) {
    r.step(&e);
    farthest = std::max(farthest, (r.v.nav.position_m.head<2>() - r.mc.home().head<2>()).norm());
  }
  EXPECT_EQ(r.mc.phase(), Phase::kLand);
  EXPECT_TRUE(r.mc.returned_home());
  EXPECT_LT(farthest, 0.35f);
}

TEST(MissionController, BlockedWayHomeLandsWhereItIs) {
  MissionRun r;
  MissionParams p;
  p.return_stall_s = 5.0f;
  ExplorerOutput e;
  ASSERT_TRUE(r.explore_then_finish(p, e, {{{0.5f, 0, 0}, 160}}));
  // A wall the trail now runs through (the estimate drifted): the vehicle cannot move.
  r.v.speed = 0.0f;
  const Eigen::Vector3f stuck = r.v.nav.position_m;
  ASSERT_FALSE(r.run_until(Phase::kLand, p.return_stall_s - 0.5f, &e));
  ASSERT_TRUE(r.run_until(Phase::kLand, 1.0f, &e));
  // It lands where it is, not at home, and says so.
  const GuidanceSetpoint s = r.step(&e);
  EXPECT_NEAR(s.position_m.x(), stuck.x(), 1e-4f);
  EXPECT_NEAR(s.position_m.y(), stuck.y(), 1e-4f);
  EXPECT_FALSE(r.mc.returned_home());
  // Slow progress is still progress: a vehicle creeping home is not landed short.
  MissionRun slow;
  ASSERT_TRUE(slow.explore_then_finish(p, e, {{{0.5f, 0, 0}, 400}}));
  slow.v.speed = 0.05f;
  ASSERT_TRUE(slow.run_until(Phase::kLand, 120, &e));
  EXPECT_TRUE(slow.mc.returned_home());
}

// GIVEN a trail home that now runs through a wall (drawn in a frame the estimate has since left:
// gt-building's corridor beside the north-west door) WHEN the newest scan shows home straight
// ahead and clear THEN the flight leaves the trail for it and lands at home; without the scan it
// is held at the wall until the stall lands it short.
struct WalledTrailFlight;
WalledTrailFlight fly_home_past_a_wall(bool give_scans, bool shortcut = true, const KeepOut* keep_out = nullptr);
struct WalledTrailFlight {
  bool home = false;
  bool crossed_the_wall = false;
  bool entered_the_keep_out = false;
  uint32_t shortcuts = 0;
};
WalledTrailFlight fly_home_past_a_wall(bool give_scans, bool shortcut, const KeepOut* keep_out) {
  MissionRun r;
  MissionParams p;
  p.return_stall_s = 10.0f;
  p.return_shortcut = shortcut;
  if (keep_out != nullptr) {
    p.keep_out[0] = *keep_out;
    p.keep_out_count = 1;
  }
  ExplorerOutput e;
  // Home (1, 2); east 2 m, north 2 m, west 1.5 m: the vehicle ends at (1.5, 4).
  EXPECT_TRUE(r.explore_then_finish(p, e, {{{0.5f, 0, 0}, 160}, {{0, 0.5f, 0}, 160}, {{-0.5f, 0, 0}, 120}}));
  // The wall the trail's first leg now crosses, x = 2.2 for y in [1, 3.5].
  test::SegmentWorld world;
  world.add(2.2, 1.0, 2.2, 3.5);
  const auto crosses = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
    if ((a.x() - 2.2f) * (b.x() - 2.2f) > 0.0f || a.x() == b.x()) return false;
    const float y = a.y() + (b.y() - a.y()) * (2.2f - a.x()) / (b.x() - a.x());
    return y >= 1.0f && y <= 3.5f;
  };
  r.v.nav.heading_rad = static_cast<float>(-M_PI / 2);  // facing south, home in the fan
  WalledTrailFlight out;
  for (int i = 0; i < 6000 && r.mc.phase() == Phase::kReturn; ++i) {
    r.t += Duration::from_s(MissionRun::kDt);
    r.v.nav.stamp = r.t;
    const LaserScan scan = world.scan(test::LaserModel::urg04lx(), r.v.nav.position_m.x(), r.v.nav.position_m.y(),
                                      r.v.nav.heading_rad, r.t);
    const GuidanceSetpoint s = r.mc.step(r.t, r.v.nav, &e, give_scans ? &scan : nullptr);
    const Eigen::Vector3f before = r.v.nav.position_m;
    r.v.follow(s, MissionRun::kDt);
    r.v.nav.heading_rad = s.heading_rad;
    if (keep_out != nullptr && keep_out->crossed_by({before.x(), before.y()},
                                                    {r.v.nav.position_m.x(), r.v.nav.position_m.y()}, 0.0f))
      out.entered_the_keep_out = true;
    if (crosses(before, r.v.nav.position_m)) {  // the wall stops it
      out.crossed_the_wall = true;
      r.v.nav.position_m = before;
      r.v.nav.velocity_mps.setZero();
    }
  }
  out.home = r.mc.returned_home();
  out.shortcuts = r.mc.shortcuts();
  return out;
}

TEST(MissionController, TheFlightHomeLeavesATrailThroughAWallWhereTheScanShowsTheWayClear) {
  const WalledTrailFlight scanned = fly_home_past_a_wall(true);
  EXPECT_TRUE(scanned.home);
  EXPECT_GE(scanned.shortcuts, 1u);
  EXPECT_FALSE(scanned.crossed_the_wall);  // never even tried to
  const WalledTrailFlight blind = fly_home_past_a_wall(false);
  EXPECT_FALSE(blind.home);
  EXPECT_EQ(blind.shortcuts, 0u);
  EXPECT_TRUE(blind.crossed_the_wall);  // held there, by the wall, until the stall
}

// GIVEN the same flight with an operator's keep-out box (glass) across the straight way home,
// which the laser sees through WHEN flying home THEN no shortcut enters the box grown by the
// clearance: the vehicle keeps to its trail, as it would without the scan.
TEST(MissionController, TheFlightHomesShortcutKeepsOutOfTheOperatorsBoxes) {
  const KeepOut glass{0.8f, 2.9f, 1.8f, 3.1f};  // across the way from (1.5, 4) to home (1, 2)
  const WalledTrailFlight kept = fly_home_past_a_wall(true, true, &glass);
  EXPECT_FALSE(kept.entered_the_keep_out);
  EXPECT_FALSE(kept.home);  // the trail through the wall was all that was left
  const WalledTrailFlight free = fly_home_past_a_wall(true);
  EXPECT_TRUE(free.home);
}

// The shortcut is an option (MissionParams::return_shortcut), its clearance must be positive, and
// its keep-out boxes valid and at most kMaxKeepOuts.
TEST(MissionController, TheShortcutIsOffWhenToldAndItsClearanceIsChecked) {
  const WalledTrailFlight off = fly_home_past_a_wall(true, false);
  EXPECT_FALSE(off.home);
  EXPECT_EQ(off.shortcuts, 0u);
  MissionController mc;
  MissionParams p;
  p.keep_out_count = 1;
  p.keep_out[0] = {2, 2, 1, 1};  // corners swapped
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
  p.keep_out_count = kMaxKeepOuts + 1;
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
  p.keep_out_count = 0;
  p.shortcut_clearance_m = 0.0f;
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
  p.shortcut_clearance_m = NAN;
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
}

// GIVEN a trail drawn south through a door (x 1.6..2.8 in a wall at y = 4) WHEN, on the way
// home, the estimate stands 0.6 m west of where it stood when the trail was drawn (its drift
// along a corridor: the trail now runs down the door's east jamb) and the vehicle is held 0.4 m
// off the walls (the approach limiter, sliding along them) THEN, stalled, the trail ahead is
// laid back onto the door the scan shows and the vehicle lands at home; with the alignment off,
// the stall lands it short of home, beside the jamb.
struct JambFlight {
  bool home = false;
  uint32_t realignments = 0;
};
JambFlight fly_home_beside_a_jamb(float realign_s) {
  MissionRun r;
  MissionParams p;
  p.return_stall_s = 20.0f;
  p.return_realign_s = realign_s;
  p.return_shortcut = false;  // the trail alone
  ExplorerOutput e;
  JambFlight out;
  // Home (1, 2); east 1.2 m to the door's middle, north 4 m through it to (2.2, 6).
  EXPECT_TRUE(r.explore_then_finish(p, e, {{{0.5f, 0, 0}, 96}, {{0, 0.5f, 0}, 320}}));
  test::SegmentWorld world;
  world.add(-5, 4, 1.6, 4);
  world.add(2.8, 4, 10, 4);
  const Eigen::Vector2f drift(0.6f, 0.0f);  // truth = estimate + drift, from now on
  const auto held_off = [&](const Eigen::Vector3f& est) {
    return world.clearance(est.x() + drift.x(), est.y() + drift.y()) < 0.4;
  };
  r.v.nav.heading_rad = static_cast<float>(-M_PI / 2);
  for (int i = 0; i < 8000 && r.mc.phase() == Phase::kReturn; ++i) {
    r.t += Duration::from_s(MissionRun::kDt);
    r.v.nav.stamp = r.t;
    const Eigen::Vector2f truth = r.v.nav.position_m.head<2>() + drift;
    const LaserScan scan = world.scan(test::LaserModel::urg04lx(), truth.x(), truth.y(), r.v.nav.heading_rad, r.t);
    const GuidanceSetpoint s = r.mc.step(r.t, r.v.nav, &e, &scan);
    const Eigen::Vector3f before = r.v.nav.position_m;
    r.v.follow(s, MissionRun::kDt);
    r.v.nav.heading_rad = s.heading_rad;
    // Held 0.4 m off the walls: the part of the step towards the nearest wall (against the
    // gradient of the clearance) is dropped, so the vehicle slides along walls and round a
    // jamb's end as the limiter lets it; what would still come nearer is not flown.
    if (held_off(r.v.nav.position_m)) {
      const Eigen::Vector2f at = before.head<2>() + drift;
      constexpr double kH = 1e-3;
      Eigen::Vector2f away(
          static_cast<float>(world.clearance(at.x() + kH, at.y()) - world.clearance(at.x() - kH, at.y())),
          static_cast<float>(world.clearance(at.x(), at.y() + kH) - world.clearance(at.x(), at.y() - kH)));
      away.normalize();  // never zero here (held 0.4 m off, 1 mm steps); Eigen leaves a zero as it is
      Eigen::Vector3f step = r.v.nav.position_m - before;
      const float towards = step.head<2>().dot(away);
      if (towards < 0.0f) step.head<2>() -= towards * away;
      r.v.nav.position_m = held_off(before + step) ? before : Eigen::Vector3f(before + step);
    }
  }
  out.home = r.mc.returned_home();
  out.realignments = r.mc.realignments();
  return out;
}

TEST(MissionController, StalledBesideAJambTheTrailIsLaidBackOntoTheDoor) {
  const JambFlight aligned = fly_home_beside_a_jamb(5.0f);
  EXPECT_TRUE(aligned.home);
  EXPECT_GE(aligned.realignments, 1u);
  const JambFlight as_drawn = fly_home_beside_a_jamb(0.0f);
  EXPECT_FALSE(as_drawn.home);
  EXPECT_EQ(as_drawn.realignments, 0u);
}

TEST(MissionController, StaleEstimateTriggersFailsafeLanding) {
  MissionRun r;
  ASSERT_TRUE(r.hover_until(Phase::kHover, 10));
  r.v.nav.valid = false;
  ASSERT_TRUE(r.run_until(Phase::kFailsafeLand, 1.0f));
  const GuidanceSetpoint s = r.step();
  EXPECT_EQ(s.mode, GuidanceSetpoint::Mode::kVelocity);
  EXPECT_TRUE(s.velocity_mps.isZero());
  ASSERT_TRUE(r.run_until(Phase::kLanded, 20));
  EXPECT_EQ(r.mc.touchdown_by(), TouchdownBy::kFailsafeTimer);  // no estimate, no altimeter
}

TEST(MissionController, NaNEstimateIsTreatedAsInvalid) {
  MissionRun r;
  ASSERT_TRUE(r.hover_until(Phase::kHover, 10));
  r.v.nav.position_m.x() = std::nanf("");
  r.v.nav.velocity_mps.setZero();
  for (int i = 0; i < 40; ++i) EXPECT_TRUE(finite(r.step_on(r.v.nav))) << "step " << i;
  EXPECT_EQ(r.mc.phase(), Phase::kFailsafeLand);
}

// Regression: the phase timers subtracted raw stamps. After the clock stepped back an hour,
// an invalid estimate never looked stale (now - last valid < 0), so the failsafe would not
// engage for an hour, and the hover's timer ran an hour long. Pinned: a step back advances
// the mission's clock by nothing, so the failsafe engages after estimate_timeout_s of
// (later) steps and the hover ends on time.
TEST(MissionController, ClockSteppingBackAnHourKeepsTheTimersAndTheFailsafe) {
  MissionRun r;
  ASSERT_TRUE(r.hover_until(Phase::kHover, 10, /*hover_s=*/2.0f));
  r.t = r.t - Duration::from_s(3600.0);
  EXPECT_TRUE(r.run_until(Phase::kLand, 2.5f));  // not an hour and two seconds
  MissionRun f;
  ASSERT_TRUE(f.hover_until(Phase::kHover, 10));
  f.t = f.t - Duration::from_s(3600.0);
  f.v.nav.valid = false;
  EXPECT_TRUE(f.run_until(Phase::kFailsafeLand, 1.0f));
}

// Regression: a clock leaping an hour ahead during the failsafe descent passed its time bound
// at once: kLanded, motors off, in the air. Pinned: a leap advances the mission's clock by at
// most 1 s (a stalled loop still trips the estimate timeout, as the first part shows), so the
// descent continues from the height it had and ends on its own time.
TEST(MissionController, ClockLeapingAnHourAheadDoesNotEndAPhaseAtOnce) {
  MissionRun r;
  ASSERT_TRUE(r.hover_until(Phase::kHover, 10));
  r.v.nav.valid = false;
  r.t = r.t + Duration::from_s(3600.0);
  GuidanceSetpoint s = r.step();
  EXPECT_EQ(r.mc.phase(), Phase::kFailsafeLand);  // a leap without an estimate: stale
  const float z = s.position_m.z();
  r.t = r.t + Duration::from_s(3600.0);
  s = r.step();
  EXPECT_EQ(r.mc.phase(), Phase::kFailsafeLand);
  EXPECT_TRUE(r.mc.wants_armed());
  EXPECT_NEAR(s.position_m.z(), z, 0.1f + 1e-4f);  // the ramp moved at most 0.1 s worth
  EXPECT_TRUE(r.run_until(Phase::kLanded, 10));
}

// A non-finite set-point from the explorer is not passed on: the mission holds where the
// vehicle is (velocity zero) at the flight altitude, with a finite heading.
TEST(MissionController, NonFiniteExplorerSetpointBecomesAHold) {
  MissionRun r;
  ExplorerOutput e;
  e.setpoint.mode = GuidanceSetpoint::Mode::kVelocity;
  ASSERT_EQ(r.mc.configure(MissionKind::kExplore, {}), Status::kOk);
  ASSERT_TRUE(r.run_until(Phase::kExplore, 10, &e));
  const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  for (int field = 0; field < 4; ++field) {
    ExplorerOutput bad = e;
    if (field == 0) bad.setpoint.velocity_mps.x() = nan;
    if (field == 1) bad.setpoint.velocity_mps.y() = -inf;
    if (field == 2) bad.setpoint.heading_rad = nan;
    if (field == 3) bad.setpoint.position_m.x() = inf;
    const GuidanceSetpoint s = r.step_on(r.v.nav, &bad);
    EXPECT_EQ(s.mode, GuidanceSetpoint::Mode::kVelocity) << field;
    EXPECT_TRUE(s.velocity_mps.isZero()) << field;
    EXPECT_TRUE(finite(s)) << field;
    EXPECT_FLOAT_EQ(s.position_m.z(), MissionParams{}.takeoff_altitude_m);
    EXPECT_EQ(r.mc.phase(), Phase::kExplore);
  }
}

// GIVEN an explore mission with a take-off survey turn WHEN it reaches altitude THEN it turns
// on the spot by that much, no faster than the return yaw rate, before it explores; a hover
// mission does not turn.
TEST(MissionController, TheTakeOffSurveyTurnsOnTheSpotBeforeExploring) {
  MissionRun r;
  MissionParams p;
  p.takeoff_survey_rad = 2.0f * kPi<float>;
  ASSERT_EQ(r.mc.configure(MissionKind::kExplore, p), Status::kOk);
  ExplorerOutput e;
  e.setpoint.mode = GuidanceSetpoint::Mode::kVelocity;
  e.setpoint.velocity_mps = {0.5f, 0, 0};
  float heading = 0, turned = 0;
  float explore_at = -1;
  for (int i = 0; i < 2000 && explore_at < 0; ++i) {
    const GuidanceSetpoint s = r.step(&e);
    if (r.mc.phase() == Phase::kExplore) {
      explore_at = static_cast<float>(i) * MissionRun::kDt;
      break;
    }
    const float d = angle_diff(s.heading_rad, heading);
    EXPECT_LE(std::fabs(d), p.return_yaw_rate_radps * MissionRun::kDt + 1e-4f);
    EXPECT_GE(d, -1e-5f);  // one way round
    turned += d;
    heading = s.heading_rad;
    if (r.mc.phase() == Phase::kTakeoff && turned > 0.01f) {
      // Turning at altitude, where it took off.
      EXPECT_NEAR(r.v.nav.position_m.x(), 1.0f, 0.16f);
      EXPECT_NEAR(r.v.nav.position_m.y(), 2.0f, 0.16f);
    }
  }
  EXPECT_NEAR(turned, 2.0f * kPi<float>, 1e-3f);
  // Preflight, climb, then 2 pi at 0.5 rad/s: 12.6 s of turning.
  EXPECT_GT(explore_at, 2.0f + 12.5f);
  EXPECT_LT(explore_at, 2.0f + 12.6f + 6.0f);

  MissionRun hover;
  ASSERT_EQ(hover.mc.configure(MissionKind::kHover, p), Status::kOk);
  for (int i = 0; i < 400; ++i) EXPECT_EQ(hover.step().heading_rad, 0.0f);
}

// GIVEN an explore mission with a home survey WHEN it is home by its estimate THEN it turns on
// the spot at altitude by that much (the home re-localisation looks meanwhile), then descends.
TEST(MissionController, HomeAgainItTurnsOnTheSpotBeforeDescending) {
  MissionRun r;
  MissionParams p;
  p.home_survey_rad = kPi<float>;
  ExplorerOutput e;
  ASSERT_TRUE(r.explore_then_finish(p, e, {{{0.5f, 0, 0}, 80}}));
  ASSERT_TRUE(r.run_until(Phase::kLand, 30, &e));
  ASSERT_TRUE(r.mc.returned_home());
  float heading = r.step(&e).heading_rad, turned = 0;
  int steps = 1;
  for (;; ++steps) {
    const GuidanceSetpoint s = r.step(&e);
    if (s.position_m.z() < p.takeoff_altitude_m) break;
    turned += angle_diff(s.heading_rad, heading);
    EXPECT_LE(std::fabs(angle_diff(s.heading_rad, heading)), p.return_yaw_rate_radps * MissionRun::kDt + 1e-4f);
    heading = s.heading_rad;
    ASSERT_LT(steps, 1000);
  }
  EXPECT_NEAR(turned, kPi<float>, 0.03f);
  // pi at 0.5 rad/s: 6.3 s at altitude.
  EXPECT_NEAR(static_cast<float>(steps) * MissionRun::kDt, kPi<float> / p.return_yaw_rate_radps, 0.1f);
  EXPECT_TRUE(r.run_until(Phase::kLanded, 10, &e));
}

// GIVEN an explore mission turning over home WHEN a fix of the estimate moves home 1.5 m off
// THEN it flies home again (the flight home: velocity set-points, facing the way) and lands
// there without a second turn.
TEST(MissionController, AFixThatMovesHomeAwayReopensTheFlightHome) {
  MissionRun r;
  MissionParams p;
  p.home_survey_rad = 2.0f * kPi<float>;
  ExplorerOutput e;
  ASSERT_TRUE(r.explore_then_finish(p, e, {{{0.5f, 0, 0}, 80}}));
  ASSERT_TRUE(r.run_until(Phase::kLand, 30, &e));
  for (int i = 0; i < 40; ++i) r.step(&e);  // a second into the turn
  ASSERT_EQ(r.mc.phase(), Phase::kLand);
  r.v.nav.position_m.x() += 1.5f;  // the fix: the vehicle is 1.5 m east of where it believed
  r.step(&e);
  EXPECT_EQ(r.mc.phase(), Phase::kReturn);
  ASSERT_TRUE(r.run_until(Phase::kLand, 20, &e));
  EXPECT_NEAR(r.v.nav.position_m.x(), 1.0f, 0.2f);  // home
  EXPECT_NEAR(r.v.nav.position_m.y(), 2.0f, 0.2f);
  // No second turn: it descends at once.
  float heading = r.step(&e).heading_rad;
  for (int i = 0; i < 20; ++i) {
    const GuidanceSetpoint s = r.step(&e);
    EXPECT_NEAR(angle_diff(s.heading_rad, heading), 0.0f, 1e-5f);
    heading = s.heading_rad;
  }
  EXPECT_LT(r.step(&e).position_m.z(), p.takeoff_altitude_m - 0.1f);
  EXPECT_TRUE(r.run_until(Phase::kLanded, 10, &e));
  EXPECT_TRUE(r.mc.returned_home());
}

// GIVEN an explore mission whose flight home stalls 2 m from home (the trail runs into a wall:
// the estimate has drifted), within stall_survey_radius_m WHEN it stalls THEN it turns on the
// spot at altitude (the home re-localisation gets its second view) before descending, and a
// fix that moves it 1.5 m re-opens the flight home, which lands at home. Beyond the radius, or
// stalled a second time, it lands where it is at once.
TEST(MissionController, StalledNearHomeItTurnsOnTheSpotAndAFixReopensTheWayHome) {
  MissionParams p;
  p.return_stall_s = 5.0f;
  p.home_survey_rad = 2.0f * kPi<float>;
  p.stall_survey_radius_m = 4.0f;
  ExplorerOutput e;
  const auto stall = [&](MissionRun& r, float east_m) {
    EXPECT_TRUE(r.explore_then_finish(p, e, {{{0.5f, 0, 0}, static_cast<int>(east_m / (0.5f * MissionRun::kDt))}}));
    r.v.speed = 0.0f;  // held by the wall
    EXPECT_TRUE(r.run_until(Phase::kLand, p.return_stall_s + 1.0f, &e));
    EXPECT_FALSE(r.mc.returned_home());
  };
  // The heading turned over n steps, and the lowest set-point meanwhile.
  struct Turn {
    float turned = 0, lowest = 1e9f;
  };
  const auto turn_of = [&](MissionRun& r, int n) {
    Turn out;
    float heading = r.step(&e).heading_rad;
    for (int i = 0; i < n; ++i) {
      const GuidanceSetpoint s = r.step(&e);
      out.lowest = std::min(out.lowest, s.position_m.z());
      out.turned += angle_diff(s.heading_rad, heading);
      heading = s.heading_rad;
    }
    return out;
  };

  MissionRun r;
  stall(r, 2.0f);
  const Turn turn = turn_of(r, 80);
  EXPECT_NEAR(turn.turned, 80 * p.return_yaw_rate_radps * MissionRun::kDt, 0.01f);
  EXPECT_GE(turn.lowest, p.takeoff_altitude_m - 1e-4f);
  ASSERT_EQ(r.mc.phase(), Phase::kLand);
  EXPECT_TRUE(r.mc.homing());  // the home re-localisation goes on searching
  r.v.nav.position_m.x() += 1.5f;  // the fix: 1.5 m further east than it believed
  r.v.speed = 1.0f;                // and the way home is the one the laser shows open
  r.step(&e);
  EXPECT_EQ(r.mc.phase(), Phase::kReturn);
  ASSERT_TRUE(r.run_until(Phase::kLanded, 60, &e));
  EXPECT_TRUE(r.mc.returned_home());
  EXPECT_NEAR(r.v.nav.position_m.x(), 1.0f, 0.2f);
  EXPECT_NEAR(r.v.nav.position_m.y(), 2.0f, 0.2f);

  // Stalled again after the fix: no second turn.
  MissionRun twice;
  stall(twice, 2.0f);
  for (int i = 0; i < 40; ++i) twice.step(&e);
  twice.v.nav.position_m.x() += 1.5f;
  twice.step(&e);
  ASSERT_EQ(twice.mc.phase(), Phase::kReturn);
  ASSERT_TRUE(twice.run_until(Phase::kLand, p.return_stall_s + 1.0f, &e));
  EXPECT_NEAR(turn_of(twice, 40).turned, 0.0f, 1e-5f);
  EXPECT_LT(twice.step(&e).position_m.z(), p.takeoff_altitude_m - 0.2f);  // descending

  // Stalled 5 m from home, beyond the radius: it descends at once.
  MissionRun far;
  stall(far, 5.0f);
  EXPECT_FALSE(far.mc.homing());
  EXPECT_NEAR(turn_of(far, 40).turned, 0.0f, 1e-5f);
  EXPECT_LT(far.step(&e).position_m.z(), p.takeoff_altitude_m - 0.2f);
}

TEST(MissionController, RejectsBadConfiguration) {
  MissionController mc;
  MissionParams p;
  p.takeoff_survey_rad = -1.0f;
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
  p.takeoff_survey_rad = std::nanf("");
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
  p.takeoff_survey_rad = 0;
  p.home_survey_rad = -1.0f;
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
  p.home_survey_rad = 0;
  p.stall_survey_radius_m = std::nanf("");
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
  p = MissionParams{};
  p.takeoff_altitude_m = std::nanf("");
  EXPECT_EQ(mc.configure(MissionKind::kHover, p), Status::kInvalidArgument);
  p = MissionParams{};
  p.preflight_s = -1.0f;
  EXPECT_EQ(mc.configure(MissionKind::kHover, p), Status::kInvalidArgument);
  p = MissionParams{};
  p.return_realign_s = -1.0f;
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
  p.return_realign_s = 5.0f;
  p.realign_max_offset_m = 1.5f;  // beyond what the scan's grid can weigh
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
  p.realign_max_offset_m = std::nanf("");
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kInvalidArgument);
  p.realign_max_offset_m = 0.8f;
  p.return_realign_s = 0.0f;  // off
  EXPECT_EQ(mc.configure(MissionKind::kExplore, p), Status::kOk);
  EXPECT_EQ(mc.configure(MissionKind::kWaypoints, {}, nullptr), Status::kInvalidArgument);
  StaticVector<Waypoint, 2> wps;
  ASSERT_TRUE(wps.push_back({{1, 1, -1}, 0, 0}));  // below the floor
  EXPECT_EQ(mc.configure(MissionKind::kWaypoints, {}, &wps), Status::kInvalidArgument);
  wps.clear();
  ASSERT_TRUE(wps.push_back({{1, 1, 1}, 0, std::numeric_limits<float>::infinity()}));  // a hold without end
  EXPECT_EQ(mc.configure(MissionKind::kWaypoints, {}, &wps), Status::kInvalidArgument);
}

// The flight's account (kestrel-sim's phase_start_s, kestrel-fw's closing report): when each
// phase was first entered, nothing for one never entered, and a new configure starts afresh.
TEST(MissionController, RecordsWhenEachPhaseWasFirstEntered) {
  MissionRun r;
  MissionParams p;
  p.hover_duration_s = 2;
  ASSERT_EQ(r.mc.configure(MissionKind::kHover, p), Status::kOk);
  TimeUs at;
  EXPECT_FALSE(r.mc.first_entered(Phase::kTakeoff, at));
  ASSERT_TRUE(r.run_until(Phase::kTakeoff, 10));
  const TimeUs takeoff = r.t;
  ASSERT_TRUE(r.run_until(Phase::kHover, 10));
  const TimeUs hover = r.t;
  ASSERT_TRUE(r.run_until(Phase::kLanded, 20));
  ASSERT_TRUE(r.mc.first_entered(Phase::kTakeoff, at));
  EXPECT_EQ(at, takeoff);
  ASSERT_TRUE(r.mc.first_entered(Phase::kHover, at));
  EXPECT_EQ(at, hover);
  EXPECT_TRUE(r.mc.first_entered(Phase::kLand, at));
  EXPECT_GT(at, hover + Duration::from_s(1.9));
  const TimeUs land = at;
  EXPECT_FALSE(r.mc.first_entered(Phase::kExplore, at));
  EXPECT_FALSE(r.mc.first_entered(Phase::kFailsafeLand, at));
  EXPECT_EQ(at, land);  // a phase never entered leaves `at` as it was
  ASSERT_EQ(r.mc.configure(MissionKind::kHover, p), Status::kOk);
  EXPECT_FALSE(r.mc.first_entered(Phase::kTakeoff, at));
}

// Regression (audit): the landing took the estimate's height without asking whether the
// estimate was valid, so one invalid state reading zeros (a filter not yet running) stopped
// the motors a metre up. Now only a believed estimate lands it; an invalid one that lasts
// hands the vehicle to the failsafe, which descends on its timer.
TEST(MissionController, AnInvalidEstimateWhileLandingDoesNotCountAsTouchdown) {
  MissionRun r;
  ASSERT_TRUE(r.hover_until(Phase::kLand, 20, /*hover_s=*/1));
  ASSERT_GT(r.v.nav.position_m.z(), 0.8f);
  NavState zeros;  // what NavFilter::state() gives before it is initialised: invalid, at 0
  (void)r.step_on(zeros);
  EXPECT_EQ(r.mc.phase(), Phase::kLand);
  EXPECT_TRUE(r.mc.wants_armed());
  for (int i = 0; i < 40 && r.mc.phase() == Phase::kLand; ++i) (void)r.step_on(zeros);
  EXPECT_EQ(r.mc.phase(), Phase::kFailsafeLand);
  EXPECT_TRUE(r.mc.wants_armed());
}

// A hover mission flown to touchdown over `surface_z` (the estimate's frame); the height over
// that surface when the mission called it landed, or NaN when it never did within 20 s; `by`,
// if given, what said so.
float touchdown_height(float surface_z, bool altimeter, float altimeter_min_m = 0.0f, TouchdownBy* by = nullptr) {
  MissionRun r;
  r.altimeter = altimeter;
  r.altimeter_min_m = altimeter_min_m;
  if (!r.hover_until(Phase::kLand, 20, /*hover_s=*/1)) {
    ADD_FAILURE() << "the hover mission never began to land";
    return std::numeric_limits<float>::infinity();
  }
  r.v.surface_z = surface_z;
  const bool landed = r.run_until(Phase::kLanded, 20);
  if (by != nullptr) *by = r.mc.touchdown_by();
  return landed ? r.v.nav.position_m.z() - surface_z : std::nanf("");
}

// The estimate's height 0.75 m low (a floor step taken wrongly, iarc-arena UTM-30LX seed 25):
// by the estimate the vehicle is down 0.55-0.87 m over the floor, where the motors were cut. The
// altimeter says it is not; the ramp goes on down to where the readings show the floor.
TEST(MissionController, AnEstimateLowByADeskLandsOnTheFloorByTheAltimeter) {
  TouchdownBy by = TouchdownBy::kNone;
  EXPECT_LT(touchdown_height(-0.75f, /*altimeter=*/true, 0.0f, &by), 0.12f);
  EXPECT_EQ(by, TouchdownBy::kAltimeter);
  // By the estimate alone: down when its ramp stops 0.2 m under the floor it believes in.
  EXPECT_NEAR(touchdown_height(-0.75f, /*altimeter=*/false, 0.0f, &by), 0.55f, 0.01f);
  EXPECT_EQ(by, TouchdownBy::kEstimate);
}

// Coming down on a desk, the estimate right: its height never goes under landed_altitude_m,
// but the altimeter reads the vehicle down on the desk. Without it (a UTM-30LX falls silent
// 0.02 m up), the set-point sinking under a height that stays still says the desk holds it.
TEST(MissionController, ComingDownOnADeskLandsOnIt) {
  TouchdownBy by = TouchdownBy::kNone;
  EXPECT_LT(touchdown_height(0.75f, /*altimeter=*/true, 0.0f, &by), 0.12f);
  EXPECT_EQ(by, TouchdownBy::kAltimeter);
  EXPECT_LT(touchdown_height(0.75f, /*altimeter=*/false, 0.0f, &by), 0.12f);
  EXPECT_EQ(by, TouchdownBy::kHeldUp);
  EXPECT_LT(touchdown_height(0.75f, /*altimeter=*/true, /*altimeter_min_m=*/0.02f, &by), 0.12f);
  EXPECT_EQ(by, TouchdownBy::kHeldUp);
}

// Resting on a 0.3 m step's rim with the altimeter's spot beside it, over the floor: the
// readings say 0.3 m up for as long as the motors run, and so does the estimate. Held up
// under a set-point sinking away from it, the vehicle is down: it lands within the time the
// ramp takes to open the gap and the wait after it, not never.
TEST(MissionController, RestingOnARimOverALowerFloorLands) {
  MissionRun r;
  r.altimeter = true;
  r.altimeter_floor_z = 0.0f;
  ASSERT_TRUE(r.hover_until(Phase::kLand, 20, /*hover_s=*/1));
  r.v.surface_z = 0.3f;
  for (int i = 0; i < 400 && r.v.nav.position_m.z() > r.v.surface_z; ++i) (void)r.step();
  ASSERT_EQ(r.v.nav.position_m.z(), r.v.surface_z);
  ASSERT_EQ(r.mc.phase(), Phase::kLand);
  const TimeUs rested = r.t;
  ASSERT_TRUE(r.run_until(Phase::kLanded, 10));
  EXPECT_EQ(r.mc.touchdown_by(), TouchdownBy::kHeldUp);
  EXPECT_FALSE(r.mc.wants_armed());
  const MissionParams p;
  // The ramp, level with the vehicle when it came to rest, takes kGapM / descent_rate_mps to
  // open the gap; then the wait.
  EXPECT_NEAR((r.t - rested).seconds(), HeldDescent::kGapM / p.descent_rate_mps + HeldDescent::kHeldS,
              2 * MissionRun::kDt);
}

// The vehicle stopped in the air (the point vehicle's speed set to zero) while the set-point
// sinks away: a second for the gap to open, and less than kHeldS still under it, is not down.
// Moving again, it lands on the floor by the estimate. Held there any longer it would be
// called down: only a snag or an estimate that no longer follows it holds a vehicle so
// (held_descent.hpp).
TEST(MissionController, AVehicleStoppedInTheAirForLessThanTheWaitIsNotDown) {
  MissionRun r;
  ASSERT_TRUE(r.hover_until(Phase::kLand, 20, /*hover_s=*/1));
  for (int i = 0; i < 8; ++i) (void)r.step();
  r.v.speed = 0.0f;
  const MissionParams p;
  const float stopped_s = HeldDescent::kGapM / p.descent_rate_mps + HeldDescent::kHeldS - 0.1f;
  EXPECT_FALSE(r.run_until(Phase::kLanded, stopped_s));
  EXPECT_TRUE(r.mc.wants_armed());
  EXPECT_GT(r.v.nav.position_m.z(), 0.5f);
  r.v.speed = 1.0f;
  ASSERT_TRUE(r.run_until(Phase::kLanded, 10));
  EXPECT_EQ(r.mc.touchdown_by(), TouchdownBy::kEstimate);
  EXPECT_LT(r.v.nav.position_m.z(), 0.12f);
}

// A UTM-30LX's deflected beams read nothing nearer than 0.1 m, 0.02 m over the floor from its
// 0.08 m mount: its low readings are still descending when they stop, which gives no verdict,
// and the estimate lands it as without an altimeter.
TEST(MissionController, AnAltimeterFallingSilentNearTheFloorStillLands) {
  EXPECT_LT(touchdown_height(0.0f, /*altimeter=*/true, /*altimeter_min_m=*/0.02f), 0.12f);
  EXPECT_LT(touchdown_height(0.0f, /*altimeter=*/true), 0.12f);
  EXPECT_LT(touchdown_height(0.0f, /*altimeter=*/false), 0.12f);
}

// Low readings held still for less than kStillS (something 0.05 m under the vehicle for 0.05 s)
// are not touchdown, though the estimate, off here, says the vehicle is down and still; the next
// reading, over the landed height again, says airborne.
TEST(MissionController, LowReadingsHeldStillBrieflyInTheAirAreNotTouchdown) {
  MissionRun r;
  r.altimeter = true;
  ASSERT_TRUE(r.hover_until(Phase::kLand, 20, /*hover_s=*/1));
  r.v.nav.position_m.z() = 0.1f;
  r.v.nav.velocity_mps.setZero();
  const auto step_reading = [&r](float height_m) {
    r.t += Duration::from_s(MissionRun::kDt);
    r.v.nav.stamp = r.t;
    const AltimeterSample reading{r.t, height_m, 1e-4f};
    (void)r.mc.step(r.t, r.v.nav, nullptr, nullptr, &reading);
  };
  for (int i = 0; i < 3; ++i) {  // 0.05 s from the first to the last
    step_reading(0.05f);
    ASSERT_EQ(r.mc.phase(), Phase::kLand) << "step " << i;
  }
  for (int i = 0; i < 10; ++i) {
    step_reading(0.85f);
    ASSERT_EQ(r.mc.phase(), Phase::kLand) << "step " << i;
  }
  step_reading(0.05f);  // and the same held long enough is touchdown
  step_reading(0.05f);
  step_reading(0.05f);
  step_reading(0.05f);
  step_reading(0.05f);
  EXPECT_EQ(r.mc.phase(), Phase::kLanded);
}

// The failsafe descends on a timer because the estimate may be what failed; the altimeter
// reading the vehicle down ends it at touchdown, not when the timer runs out.
TEST(MissionController, TheFailsafeLandsWhenTheAltimeterReadsTheGround) {
  MissionRun r;
  r.altimeter = true;
  ASSERT_TRUE(r.hover_until(Phase::kHover, 10));
  r.v.nav.valid = false;  // the vehicle still follows the set-points: its height is the truth
  ASSERT_TRUE(r.run_until(Phase::kFailsafeLand, 1.0f));
  const TimeUs failed = r.t;
  ASSERT_TRUE(r.run_until(Phase::kLanded, 20));
  EXPECT_LT(r.v.nav.position_m.z(), 0.12f);
  const MissionParams p;
  EXPECT_LT((r.t - failed).seconds(), p.takeoff_altitude_m / p.descent_rate_mps + 1.0);
}

// An estimate gone NaN on the way home: the set-point keeps the last position believed and
// holds still (velocity zero) until the failsafe takes over; no NaN reaches the controller.
TEST(MissionController, ANaNEstimateOnTheWayHomeGivesAFiniteSetpoint) {
  MissionRun r;
  MissionParams p;
  ExplorerOutput e;
  ASSERT_TRUE(r.explore_then_finish(p, e, {{{0.5f, 0, 0}, 160}}));
  const Eigen::Vector3f believed = r.v.nav.position_m;
  NavState nan_nav = r.v.nav;
  nan_nav.position_m.setConstant(std::nanf(""));
  for (int i = 0; i < 60; ++i) {
    const GuidanceSetpoint s = r.step_on(nan_nav, &e);
    ASSERT_TRUE(finite(s)) << "step " << i << " in " << to_string(r.mc.phase());
    EXPECT_NEAR(s.position_m.x(), believed.x(), 1e-5f);
    EXPECT_NEAR(s.position_m.y(), believed.y(), 1e-5f);
  }
  EXPECT_EQ(r.mc.phase(), Phase::kFailsafeLand);
}

// The same on the very step exploring ends (review): the return's first set-point and the
// heading it holds all the way home come from the estimate believed last, not a NaN one.
TEST(MissionController, ANaNEstimateAsExploringEndsLeavesNoNaNInTheFlightHome) {
  MissionRun r;
  ExplorerOutput e;
  ASSERT_EQ(r.mc.configure(MissionKind::kExplore, {}), Status::kOk);
  e.setpoint.mode = GuidanceSetpoint::Mode::kVelocity;
  ASSERT_TRUE(r.run_until(Phase::kExplore, 10, &e));
  e.setpoint.velocity_mps = {0.5f, 0, 0};
  for (int i = 0; i < 80; ++i) r.step(&e);
  const Eigen::Vector3f believed = r.v.nav.position_m;
  const float believed_heading = r.v.nav.heading_rad;
  e.finished = true;
  NavState nan_nav = r.v.nav;
  nan_nav.position_m.setConstant(std::nanf(""));
  nan_nav.heading_rad = std::nanf("");
  const GuidanceSetpoint first = r.step_on(nan_nav, &e);
  ASSERT_EQ(r.mc.phase(), Phase::kReturn);
  EXPECT_TRUE(finite(first));
  EXPECT_NEAR(first.position_m.x(), believed.x(), 0.02f);  // the last step's estimate, 25 ms before
  EXPECT_FLOAT_EQ(first.heading_rad, believed_heading);
  // The estimate back: the flight home's set-points stay finite all the way.
  for (int i = 0; i < 400; ++i) ASSERT_TRUE(finite(r.step(&e))) << i;
}

TEST(MissionController, StepsDoNotAllocate) {
  MissionRun r;
  ASSERT_EQ(r.mc.configure(MissionKind::kExplore, {}), Status::kOk);
  ExplorerOutput e;
  e.setpoint.mode = GuidanceSetpoint::Mode::kVelocity;
  e.setpoint.velocity_mps = {0.3f, 0.1f, 0};
  alloc_guard::Scope guard;
  for (int i = 0; i < 4000; ++i) r.step(&e);
  EXPECT_EQ(guard.allocations(), 0u);
}

}  // namespace
}  // namespace kestrel::mission
