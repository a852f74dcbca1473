// The four explorers behind one interface: Algorithm 1's blending (equations 1, 5, 6), the
// limits of section V, the defined hold on every bad input, and no heap in the guidance step.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/core/angle.hpp"
#include "kestrel/exploration/blend_explorer.hpp"
#include "kestrel/exploration/frontier_explorer.hpp"
#include "kestrel/exploration/srt_explorer.hpp"
#include "kestrel/exploration/wall_follow_explorer.hpp"
#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using test::LaserModel;
using test::SegmentWorld;
using test::uniform_scan;
using test::nav_at;

const LaserModel kUrg = LaserModel::urg04lx();

SegmentWorld hall() {
  SegmentWorld w;
  w.add_box(-3, -2, 9, 2);
  return w;
}

TEST(Explorer, KindsParseAndPrint) {
  EXPECT_EQ(parse_explorer_kind("blend").value(), ExplorerKind::kBlend);
  EXPECT_EQ(parse_explorer_kind("wallfollow").value(), ExplorerKind::kWallFollow);
  EXPECT_EQ(parse_explorer_kind("srt").value(), ExplorerKind::kSrt);
  EXPECT_EQ(parse_explorer_kind("frontier").value(), ExplorerKind::kFrontier);
  EXPECT_STREQ(to_string(ExplorerKind::kFrontier), "frontier");
  EXPECT_EQ(parse_explorer_kind("Blend").status(), Status::kInvalidArgument);
  EXPECT_EQ(parse_explorer_kind(nullptr).status(), Status::kInvalidArgument);
  EXPECT_STREQ(to_string(ExplorerKind::kWallFollow), "wallfollow");
  auto b = std::make_unique<BlendExplorer>();
  auto w = std::make_unique<WallFollowExplorer>();
  auto s = std::make_unique<SrtExplorer>();
  const Explorer* all[] = {b.get(), w.get(), s.get()};
  EXPECT_EQ(all[0]->kind(), ExplorerKind::kBlend);
  EXPECT_EQ(all[1]->planner(), nullptr);
  EXPECT_NE(all[2]->planner(), nullptr);
}

// The margins may be set below their defaults together: the limiter's stop distance is checked
// against the clearance the explorer is given, not against the planner's defaults.
TEST(Explorer, SmallerMarginsConfigureWhenConsistent) {
  const BeamGeometry g = BeamGeometry::of(uniform_scan(kUrg, 2000));
  Params p;
  p.srt.clearance_m = 0.35f;
  p.approach.stop_distance_m = 0.35f;
  p.wall.target_range_m = 0.95f;
  p.wall.safe_range_m = 0.6f;
  auto b = std::make_unique<BlendExplorer>();
  auto s = std::make_unique<SrtExplorer>();
  EXPECT_EQ(b->configure(p, g), Status::kOk);
  EXPECT_EQ(s->configure(p, g), Status::kOk);
  p.approach.stop_distance_m = 0.36f;  // the limiter would keep the vehicle off its waypoints
  EXPECT_EQ(b->configure(p, g), Status::kInvalidArgument);
  p.approach.enabled = false;          // ... unless there is no limiter
  EXPECT_EQ(b->configure(p, g), Status::kOk);
}

// srt.retrace = kGuarded: the blend, whose commands the approach limiter guards, retraces; SRT
// alone, and a blend without the limiter, do not (params.hpp, RetraceMode).
TEST(Explorer, AGuardedRetraceIsTheBlendsWithItsLimiterOnly) {
  const BeamGeometry g = BeamGeometry::of(uniform_scan(kUrg, 2000));
  Params p;
  p.srt.retrace = RetraceMode::kGuarded;
  auto b = std::make_unique<BlendExplorer>();
  auto s = std::make_unique<SrtExplorer>();
  ASSERT_EQ(b->configure(p, g), Status::kOk);
  ASSERT_EQ(s->configure(p, g), Status::kOk);
  EXPECT_TRUE(b->planner()->retraces_enabled());
  EXPECT_FALSE(s->planner()->retraces_enabled());
  p.approach.enabled = false;
  ASSERT_EQ(b->configure(p, g), Status::kOk);
  EXPECT_FALSE(b->planner()->retraces_enabled());
  p.srt.retrace = RetraceMode::kAlways;  // as told, guarded or not
  ASSERT_EQ(b->configure(p, g), Status::kOk);
  ASSERT_EQ(s->configure(p, g), Status::kOk);
  EXPECT_TRUE(b->planner()->retraces_enabled());
  EXPECT_TRUE(s->planner()->retraces_enabled());
}

TEST(BlendExplorer, CommandIsWallFollowingPlusFrontierVelocityTowardsTheWaypoint) {
  auto ex = std::make_unique<BlendExplorer>();
  Params p;
  p.guidance.speed_limit_mps = 100.0f;  // out of the way: check equations 1 and 5 exactly
  p.guidance.yaw_rate_limit_radps = 100.0f;
  p.srt.arrival_work_per_cycle = 0;  // the first waypoint in the first step
  p.approach.enabled = false;        // paper 002's blend alone (the limiter has its own tests)
  const SegmentWorld w = hall();
  LaserScan scan = w.scan(kUrg, 0, 0, 0.2);
  ASSERT_EQ(ex->configure(p, BeamGeometry::of(scan)), Status::kOk);
  GuidanceSetpoint out;
  ASSERT_EQ(ex->step(nav_at(0, 0, 0.2f), scan, out), Status::kOk);
  // Step again from a point off the waypoint, 0.1 s later.
  scan = w.scan(kUrg, 0.4, -0.3, 0.2, TimeUs{100000});
  ASSERT_EQ(ex->step(nav_at(0.4f, -0.3f, 0.2f), scan, out), Status::kOk);
  const ExplorerStatus& st = ex->status();
  ASSERT_TRUE(st.has_target);
  const Point2 wp = st.target;
  EXPECT_EQ(out.mode, GuidanceSetpoint::Mode::kVelocity);
  EXPECT_NEAR(st.v_fr.x(), p.guidance.gain_fr * (wp.x - 0.4f), 1e-5);  // equation 5
  EXPECT_NEAR(st.v_fr.y(), p.guidance.gain_fr * (wp.y + 0.3f), 1e-5);
  EXPECT_GT(st.field.in_range, 100);
  const Eigen::Vector2f v_wf = WallFollowField::to_inertial(st.field.body_mps, 0.2f);
  EXPECT_NEAR(out.velocity_mps.x(), v_wf.x() + st.v_fr.x(), 1e-5);  // equation 1
  EXPECT_NEAR(out.velocity_mps.y(), v_wf.y() + st.v_fr.y(), 1e-5);
  EXPECT_NEAR(out.heading_rad, std::atan2(wp.y + 0.3f, wp.x - 0.4f), 1e-5);  // equation 6
  EXPECT_FLOAT_EQ(out.position_m.z(), p.guidance.altitude_m);
  EXPECT_EQ(out.stamp, TimeUs{100000});
}

TEST(BlendExplorer, SpeedLimitCapsTheSum) {
  auto ex = std::make_unique<BlendExplorer>();
  Params p;
  p.guidance.gain_fr = 50.0f;  // a far waypoint would command tens of m/s
  p.srt.arrival_work_per_cycle = 0;  // the first waypoint in the first step
  p.approach.enabled = false;        // the section V limit alone
  const SegmentWorld w = hall();
  const LaserScan scan = w.scan(kUrg, 0, 0, 0);
  ASSERT_EQ(ex->configure(p, BeamGeometry::of(scan)), Status::kOk);
  GuidanceSetpoint out;
  ASSERT_EQ(ex->step(nav_at(0, 0, 0), scan, out), Status::kOk);
  EXPECT_NEAR(out.velocity_mps.head<2>().norm(), p.guidance.speed_limit_mps, 1e-5);
  EXPECT_GT((ex->status().v_wf + ex->status().v_fr).norm(), 10.0f);
  // Direction kept.
  const Eigen::Vector2f sum = (ex->status().v_wf + ex->status().v_fr).normalized();
  EXPECT_NEAR(out.velocity_mps.head<2>().normalized().dot(sum), 1.0f, 1e-5);
}

TEST(BlendExplorer, YawRateLimitSlewsTheHeadingCommand) {
  auto ex = std::make_unique<BlendExplorer>();
  Params p;
  p.guidance.yaw_rate_limit_radps = 0.5f;
  p.srt.arrival_work_per_cycle = 0;  // the first waypoint in the first step
  // Facing north across the 4 m hall: the only frontiers are east, 90 degrees off the nose.
  const SegmentWorld w = hall();
  const float heading = static_cast<float>(M_PI / 2);
  LaserScan scan = w.scan(kUrg, 0, 0, heading);
  ASSERT_EQ(ex->configure(p, BeamGeometry::of(scan)), Status::kOk);
  GuidanceSetpoint out;
  ASSERT_EQ(ex->step(nav_at(0, 0, heading), scan, out), Status::kOk);
  ASSERT_TRUE(ex->status().has_target);
  float prev = out.heading_rad;
  EXPECT_FLOAT_EQ(prev, heading);  // first step: no time has passed
  const float target = ex->status().heading_target_rad;
  ASSERT_GT(std::fabs(angle_diff(target, heading)), 0.3f);
  for (int k = 1; k <= 10; ++k) {
    scan.stamp = TimeUs{k * 100000};
    ASSERT_EQ(ex->step(nav_at(0, 0, heading), scan, out), Status::kOk);
    const float turn = std::fabs(angle_diff(out.heading_rad, prev));
    EXPECT_LE(turn, 0.5f * 0.1f + 1e-5f);
    prev = out.heading_rad;
  }
  EXPECT_NEAR(std::fabs(angle_diff(out.heading_rad, heading)), std::min(0.5f, std::fabs(angle_diff(target, heading))),
              1e-4);
}

TEST(BlendExplorer, WaypointTimeLimitRestartsExploration) {
  auto ex = std::make_unique<BlendExplorer>();
  Params p;
  p.guidance.waypoint_time_limit_s = 5.0f;
  const SegmentWorld w = hall();
  LaserScan scan = w.scan(kUrg, 0, 0, 0);
  ASSERT_EQ(ex->configure(p, BeamGeometry::of(scan)), Status::kOk);
  GuidanceSetpoint out;
  for (int k = 0; k <= 60; ++k) {  // hovering in place for 6 s: never reaches the waypoint
    scan.stamp = TimeUs{k * 100000};
    ASSERT_EQ(ex->step(nav_at(0, 0, 0), scan, out), Status::kOk);
  }
  EXPECT_EQ(ex->planner()->restarts(), 1u);
  EXPECT_EQ(ex->planner()->last_restart_reason(), RestartReason::kTimeout);
  EXPECT_EQ(ex->planner()->tree().nodes().size(), 1u);
}

TEST(BlendExplorer, HoldsOnTheArrivalPointWhileTheArrivalStepIsSliced) {
  auto ex = std::make_unique<BlendExplorer>();
  Params p;  // default budget: the arrival step takes several guidance cycles
  const SegmentWorld w = hall();
  LaserScan scan = w.scan(kUrg, 0, 0, 0);
  ASSERT_EQ(ex->configure(p, BeamGeometry::of(scan)), Status::kOk);
  GuidanceSetpoint out;
  ASSERT_EQ(ex->step(nav_at(0, 0, 0), scan, out), Status::kOk);
  ASSERT_TRUE(ex->planner()->busy());
  int cycles = 1;
  // Drifting off meanwhile: v_fr pulls back to where the step began, on top of the field.
  while (ex->planner()->busy() && cycles < 100) {
    scan = w.scan(kUrg, 0.1, 0.05, 0, TimeUs{cycles * 100000});
    ASSERT_EQ(ex->step(nav_at(0.1f, 0.05f, 0), scan, out), Status::kOk);
    ++cycles;
    if (!ex->planner()->busy()) break;
    EXPECT_TRUE(ex->status().has_target);
    EXPECT_FLOAT_EQ(ex->status().target.x, 0.0f);
    EXPECT_FLOAT_EQ(ex->status().target.y, 0.0f);
    EXPECT_NEAR(ex->status().v_fr.x(), -0.1f * p.guidance.gain_fr, 1e-6);
    EXPECT_NEAR(ex->status().v_fr.y(), -0.05f * p.guidance.gain_fr, 1e-6);
    EXPECT_EQ(out.mode, GuidanceSetpoint::Mode::kVelocity);
  }
  EXPECT_GE(cycles, 2);
  EXPECT_FALSE(ex->planner()->busy());
  EXPECT_EQ(ex->planner()->mode(), PlannerMode::kForward);
  EXPECT_GT(std::hypot(ex->status().target.x, ex->status().target.y), 2.0f * p.guidance.arrival_distance_m - 1e-4f);
}

TEST(SrtExplorer, SendsTheWaypointAsAPositionSetpoint) {
  auto ex = std::make_unique<SrtExplorer>();
  const SegmentWorld w = hall();
  const LaserScan scan = w.scan(kUrg, 0, 0, 0);
  ASSERT_EQ(ex->configure(Params{}, BeamGeometry::of(scan)), Status::kOk);
  GuidanceSetpoint out;
  ASSERT_EQ(ex->step(nav_at(0, 0, 0), scan, out), Status::kOk);
  EXPECT_EQ(out.mode, GuidanceSetpoint::Mode::kPosition);
  EXPECT_FLOAT_EQ(out.position_m.x(), ex->planner()->waypoint().x);
  EXPECT_FLOAT_EQ(out.position_m.y(), ex->planner()->waypoint().y);
  EXPECT_FLOAT_EQ(out.position_m.z(), Params{}.guidance.altitude_m);
  EXPECT_EQ(out.velocity_mps, Eigen::Vector3f::Zero());
  EXPECT_EQ(ex->status().field.in_range, 0);  // no wall-following contribution
}

TEST(WallFollowExplorer, CruisesAlongTheNearestWallKeepingItOnTheRight) {
  auto ex = std::make_unique<WallFollowExplorer>();
  SegmentWorld w;
  w.add(-50, -1.0, 50, -1.0);  // a wall 1 m to the south (r_t away): the field is small
  const LaserScan scan = w.scan(kUrg, 0, 0, 0);
  Params p;
  ASSERT_EQ(ex->configure(p, BeamGeometry::of(scan)), Status::kOk);
  GuidanceSetpoint out;
  ASSERT_EQ(ex->step(nav_at(0, 0, 0), scan, out), Status::kOk);
  EXPECT_EQ(out.mode, GuidanceSetpoint::Mode::kVelocity);
  EXPECT_FALSE(ex->finished());
  // Wall south -> travel east (the nearest beam is found to the mm: a few beams of slack).
  EXPECT_NEAR(ex->status().heading_target_rad, 0.0f, 0.05f);
  EXPECT_GT(out.velocity_mps.x(), 0.2f);
  // Pure field when the cruise and the hold are off: the heading is held.
  p.guidance.cruise_speed_mps = 0.0f;
  p.guidance.wall_hold_gain = 0.0f;
  ASSERT_EQ(ex->configure(p, BeamGeometry::of(scan)), Status::kOk);
  ASSERT_EQ(ex->step(nav_at(0, 0, 0.3f), scan, out), Status::kOk);
  EXPECT_FLOAT_EQ(out.heading_rad, 0.3f);
}

// Every explorer answers bad input with a hold and keeps its exploration state. (Plain
// functions called per explorer: GCC 12 for ARM misreads a parameterised fixture's destructor.)
void expect_hold(const GuidanceSetpoint& out, float x, float y, float heading) {
  EXPECT_EQ(out.mode, GuidanceSetpoint::Mode::kVelocity);
  EXPECT_EQ(out.velocity_mps, Eigen::Vector3f::Zero());
  EXPECT_FLOAT_EQ(out.position_m.x(), x);
  EXPECT_FLOAT_EQ(out.position_m.y(), y);
  EXPECT_FLOAT_EQ(out.heading_rad, heading);
}

void holds_on_bad_input(Explorer* ex) {
  SCOPED_TRACE(to_string(ex->kind()));
  const SegmentWorld w = hall();
  LaserScan scan = w.scan(kUrg, 1, 0.5, 0.1, TimeUs{1000000});
  GuidanceSetpoint out;
  EXPECT_EQ(ex->step(nav_at(1, 0.5f, 0.1f), scan, out), Status::kNotFound);  // unconfigured
  expect_hold(out, 1, 0.5f, 0.1f);
  ASSERT_EQ(ex->configure(Params{}, BeamGeometry::of(scan)), Status::kOk);
  ASSERT_EQ(ex->step(nav_at(1, 0.5f, 0.1f), scan, out), Status::kOk);
  const float heading_cmd = out.heading_rad;
  const std::size_t nodes = ex->planner() ? ex->planner()->tree().nodes().size() : 0;
  const uint32_t issued = ex->planner() ? ex->planner()->waypoints_issued() : 0;

  scan.stamp = TimeUs{1100000};
  NavState nan_nav = nav_at(NAN, 0.5f, 0.1f);
  EXPECT_EQ(ex->step(nan_nav, scan, out), Status::kNotFinite);
  expect_hold(out, 1, 0.5f, heading_cmd);
  NavState nan_heading = nav_at(5, 5, NAN);
  EXPECT_EQ(ex->step(nan_heading, scan, out), Status::kNotFinite);
  expect_hold(out, 1, 0.5f, heading_cmd);
  NavState invalid = nav_at(5, 5, 0);
  invalid.valid = false;
  EXPECT_EQ(ex->step(invalid, scan, out), Status::kNotFinite);
  LaserScan empty = scan;
  empty.beam_count = 0;
  EXPECT_EQ(ex->step(nav_at(5, 5, 0), empty, out), Status::kNoData);
  expect_hold(out, 1, 0.5f, heading_cmd);
  const LaserScan other = uniform_scan(LaserModel::utm30lx(), 2000);
  EXPECT_EQ(ex->step(nav_at(5, 5, 0), other, out), Status::kInvalidArgument);
  LaserScan old = scan;
  old.stamp = TimeUs{500000};
  EXPECT_EQ(ex->step(nav_at(5, 5, 0), old, out), Status::kTimeJump);
  expect_hold(out, 1, 0.5f, heading_cmd);
  EXPECT_EQ(ex->status().rejected, 6u);  // configure() reset the count of the first
  EXPECT_EQ(ex->status().last, Status::kTimeJump);
  if (ex->planner()) {
    EXPECT_EQ(ex->planner()->tree().nodes().size(), nodes);
    EXPECT_EQ(ex->planner()->waypoints_issued(), issued);
  }
  // Good input again works; a bad configuration leaves the explorer holding.
  EXPECT_EQ(ex->step(nav_at(1, 0.5f, 0.1f), scan, out), Status::kOk);
  Params bad;
  bad.guidance.speed_limit_mps = -1.0f;
  EXPECT_EQ(ex->configure(bad, BeamGeometry::of(scan)), Status::kInvalidArgument);
  EXPECT_EQ(ex->step(nav_at(1, 0.5f, 0.1f), scan, out), Status::kNotFound);
}

// Odd but finite inputs the hold checks do not catch: a scan stamped an hour after the last
// one, a heading of 1e30 rad, positions at 1e30 m or the float maximum, beam_count above the
// array's capacity, a scan of nothing but maximum ranges or of nothing but error codes.
// Pinned, for every explorer: step() returns, the set-point is finite, a velocity set-point
// stays within the speed limit, a huge position is refused as a hold (kOutOfRange) and the
// explorer keeps working on good input afterwards. Under host-asan this also checks that no
// float-to-int conversion of a huge coordinate is undefined.
void odd_finite_inputs_give_finite_bounded_setpoints(Explorer* ex) {
  SCOPED_TRACE(to_string(ex->kind()));
  const SegmentWorld w = hall();
  LaserScan scan = w.scan(kUrg, 1, 0.5, 0.1, TimeUs{1000000});
  ASSERT_EQ(ex->configure(Params{}, BeamGeometry::of(scan)), Status::kOk);
  const float speed = Params{}.guidance.speed_limit_mps;
  GuidanceSetpoint out;
  auto expect_sane = [&](const char* what) {
    SCOPED_TRACE(what);
    EXPECT_TRUE(out.position_m.allFinite() && out.velocity_mps.allFinite() && std::isfinite(out.heading_rad));
    if (out.mode == GuidanceSetpoint::Mode::kVelocity) {
      EXPECT_LE(out.velocity_mps.head<2>().norm(), speed * 1.0001f);
    }
  };
  ASSERT_EQ(ex->step(nav_at(1, 0.5f, 0.1f), scan, out), Status::kOk);
  scan.stamp = scan.stamp + Duration::from_s(3600.0);  // an hour later: a good step
  EXPECT_EQ(ex->step(nav_at(1, 0.5f, 0.1f), scan, out), Status::kOk);
  expect_sane("hour");
  EXPECT_LE(std::abs(angle_diff(out.heading_rad, 0.1f)), static_cast<float>(M_PI));
  scan.stamp = scan.stamp + Duration::from_ms(100);
  EXPECT_EQ(ex->step(nav_at(1, 0.5f, 1e30f), scan, out), Status::kOk);
  expect_sane("heading 1e30");
  for (float big : {1e30f, -1e30f, std::numeric_limits<float>::max(), 2e5f}) {
    scan.stamp = scan.stamp + Duration::from_ms(100);
    EXPECT_EQ(ex->step(nav_at(big, -big, 0.1f), scan, out), Status::kOutOfRange) << big;
    expect_sane("huge position");
    EXPECT_EQ(out.velocity_mps, Eigen::Vector3f::Zero());
    EXPECT_FLOAT_EQ(out.position_m.x(), 1.0f);  // the hold is at the last good position
  }
  LaserScan over = scan;
  over.beam_count = static_cast<uint16_t>(kMaxBeams + 1);
  EXPECT_EQ(ex->step(nav_at(1, 0.5f, 0.1f), over, out), Status::kInvalidArgument);
  expect_sane("beam_count above capacity");
  LaserScan far = scan, codes = scan;
  for (std::size_t i = 0; i < far.beam_count; ++i) {
    far.range_mm[i] = far.max_range_mm;
    codes.range_mm[i] = 1;  // an error code below kMinValidRangeMm
  }
  far.stamp = scan.stamp + Duration::from_ms(100);
  codes.stamp = far.stamp + Duration::from_ms(100);
  (void)ex->step(nav_at(1, 0.5f, 0.1f), far, out);
  expect_sane("all max range");
  (void)ex->step(nav_at(1, 0.5f, 0.1f), codes, out);
  expect_sane("all error codes");
  scan.stamp = codes.stamp + Duration::from_ms(100);
  EXPECT_EQ(ex->step(nav_at(1.05f, 0.5f, 0.1f), scan, out), Status::kOk);
  expect_sane("good again");
}

void never_allocates(Explorer* ex) {
  SCOPED_TRACE(to_string(ex->kind()));
  const SegmentWorld w = hall();
  const LaserScan first = w.scan(kUrg, 0, 0, 0);
  Params p;
  p.guidance.waypoint_time_limit_s = 2.0f;  // include restarts
  ASSERT_EQ(ex->configure(p, BeamGeometry::of(first)), Status::kOk);
  // Scans made before arming: the step itself is what is measured.
  std::vector<LaserScan> scans;
  std::vector<NavState> navs;
  for (int k = 0; k < 200; ++k) {
    const float x = 3.0f * std::sin(0.05f * k), y = 1.0f * std::sin(0.031f * k);
    scans.push_back(w.scan(kUrg, x, y, 0.02 * k, TimeUs{k * 100000}));
    navs.push_back(nav_at(x, y, 0.02f * k));
  }
  navs[50].position_m.x() = NAN;
  scans[60].beam_count = 0;
  GuidanceSetpoint out;
  uint64_t allocations = 0;
  {
    alloc_guard::Scope guard;
    for (std::size_t k = 0; k < scans.size(); ++k) {
      (void)ex->step(navs[k], scans[k], out);
      ex->background_step();  // level 3 (the frontier explorer's), in lockstep
    }
    allocations = guard.allocations();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_TRUE(alloc_guard::active());
  if (ex->planner()) {
    EXPECT_GE(ex->planner()->waypoints_issued(), 2u);  // arrivals or restarts did happen
  }
}

// The flight home borrows the explorer's approach limiter (AutonomyStack, Phase::kReturn).
void bounds_a_velocity_setpoint_from_elsewhere(Explorer* ex) {
  SegmentWorld w;
  w.add_box(-5, -5, 0.8, 5);  // a wall 0.8 m ahead of the vehicle at the origin, heading 0
  const LaserScan scan = w.scan(kUrg, 0, 0, 0);
  GuidanceSetpoint sp;
  sp.mode = GuidanceSetpoint::Mode::kVelocity;
  sp.velocity_mps = {0.6f, 0.0f, 0.0f};
  // Unconfigured: nothing can be trusted, the horizontal velocity is zeroed.
  EXPECT_EQ(ex->bound_velocity(nav_at(0, 0, 0), scan, sp), Status::kInvalidArgument);
  EXPECT_FLOAT_EQ(sp.velocity_mps.head<2>().norm(), 0.0f);
  ASSERT_EQ(ex->configure(Params{}, BeamGeometry::of(scan)), Status::kOk);
  sp.velocity_mps = {0.6f, 0.0f, 0.0f};
  EXPECT_EQ(ex->bound_velocity(nav_at(0, 0, 0), scan, sp), Status::kOk);
  EXPECT_NEAR(sp.velocity_mps.x(), 0.4f, 0.01f);  // gain * (0.8 - 0.4)
  // The same command with the vehicle turned round: the wall is behind, in the blind arc.
  const LaserScan turned = w.scan(kUrg, 0, 0, M_PI);
  sp.velocity_mps = {0.6f, 0.0f, 0.0f};
  EXPECT_EQ(ex->bound_velocity(nav_at(0, 0, static_cast<float>(M_PI)), turned, sp), Status::kOk);
  EXPECT_NEAR(sp.velocity_mps.x(), Params{}.approach.blind_speed_mps, 0.02f);
  // A position set-point is the controller's to fly: left as it is.
  GuidanceSetpoint pos;
  pos.mode = GuidanceSetpoint::Mode::kPosition;
  pos.velocity_mps = {0.6f, 0.0f, 0.0f};
  EXPECT_EQ(ex->bound_velocity(nav_at(0, 0, 0), scan, pos), Status::kOk);
  EXPECT_FLOAT_EQ(pos.velocity_mps.x(), 0.6f);
  // A scan of another laser, or a non-finite heading: zeroed.
  const LaserScan other = w.scan(LaserModel::utm30lx(), 0, 0, 0);
  EXPECT_EQ(ex->bound_velocity(nav_at(0, 0, 0), other, sp), Status::kInvalidArgument);
  EXPECT_FLOAT_EQ(sp.velocity_mps.head<2>().norm(), 0.0f);
  sp.velocity_mps = {0.6f, 0.0f, 0.0f};
  EXPECT_EQ(ex->bound_velocity(nav_at(0, 0, NAN), scan, sp), Status::kInvalidArgument);
  EXPECT_FLOAT_EQ(sp.velocity_mps.head<2>().norm(), 0.0f);
}

TEST(BlendExplorer, KeepsOutOfAKeepOutBoxTheLaserCannotSee) {
  // A glass window: no return, but the operator's box 0.8 m ahead bounds the command as a
  // wall there would; inside the box, the vehicle backs out by the nearest side.
  auto ex = std::make_unique<BlendExplorer>();
  SegmentWorld far;
  far.add_box(-10, -10, 10, 10);
  const LaserScan scan = far.scan(kUrg, 0, 0, 0);
  Params p;
  p.srt.keep_out[0] = {0.8f, -1.0f, 1.0f, 1.0f};
  p.srt.keep_out_count = 1;
  ASSERT_EQ(ex->configure(p, BeamGeometry::of(scan)), Status::kOk);
  GuidanceSetpoint sp;
  sp.mode = GuidanceSetpoint::Mode::kVelocity;
  sp.velocity_mps = {0.6f, 0.0f, 0.0f};
  ASSERT_EQ(ex->bound_velocity(nav_at(0, 0, 0), scan, sp), Status::kOk);
  EXPECT_NEAR(sp.velocity_mps.x(), 1.0f * (0.8f - 0.4f), 0.01f);
  // Heading turned: the box is now to the left of the body, the bound the same in the world.
  sp.velocity_mps = {0.6f, 0.0f, 0.0f};
  ASSERT_EQ(ex->bound_velocity(nav_at(0, 0, -1.2f), far.scan(kUrg, 0, 0, -1.2), sp), Status::kOk);
  EXPECT_NEAR(sp.velocity_mps.x(), 0.4f, 0.01f);
  // Inside, 0.05 m from its near side, facing out of it: pushed back out through that side.
  sp.velocity_mps = {0.0f, 0.0f, 0.0f};
  const float out = static_cast<float>(M_PI);
  ASSERT_EQ(ex->bound_velocity(nav_at(0.85f, 0, out), far.scan(kUrg, 0.85, 0, out), sp), Status::kOk);
  EXPECT_LT(sp.velocity_mps.x(), -0.3f);
  EXPECT_NEAR(sp.velocity_mps.y(), 0.0f, 0.01f);
}

TEST(BlendExplorer, BoundsAVelocitySetpointFromElsewhere) {
  bounds_a_velocity_setpoint_from_elsewhere(std::make_unique<BlendExplorer>().get());
}
TEST(SrtExplorer, BoundsAVelocitySetpointFromElsewhere) {
  bounds_a_velocity_setpoint_from_elsewhere(std::make_unique<SrtExplorer>().get());
}

TEST(BlendExplorer, HoldsOnBadInput) {
  holds_on_bad_input(std::make_unique<BlendExplorer>().get());
}
TEST(WallFollowExplorer, HoldsOnBadInput) {
  holds_on_bad_input(std::make_unique<WallFollowExplorer>().get());
}
TEST(SrtExplorer, HoldsOnBadInput) {
  holds_on_bad_input(std::make_unique<SrtExplorer>().get());
}
TEST(BlendExplorer, OddFiniteInputsGiveFiniteBoundedSetpoints) {
  odd_finite_inputs_give_finite_bounded_setpoints(std::make_unique<BlendExplorer>().get());
}
TEST(WallFollowExplorer, OddFiniteInputsGiveFiniteBoundedSetpoints) {
  odd_finite_inputs_give_finite_bounded_setpoints(std::make_unique<WallFollowExplorer>().get());
}
TEST(SrtExplorer, OddFiniteInputsGiveFiniteBoundedSetpoints) {
  odd_finite_inputs_give_finite_bounded_setpoints(std::make_unique<SrtExplorer>().get());
}
TEST(BlendExplorer, GuidanceStepNeverAllocates) {
  never_allocates(std::make_unique<BlendExplorer>().get());
}
TEST(WallFollowExplorer, GuidanceStepNeverAllocates) {
  never_allocates(std::make_unique<WallFollowExplorer>().get());
}
TEST(SrtExplorer, GuidanceStepNeverAllocates) {
  never_allocates(std::make_unique<SrtExplorer>().get());
}
TEST(FrontierExplorer, BoundsAVelocitySetpointFromElsewhere) {
  bounds_a_velocity_setpoint_from_elsewhere(std::make_unique<FrontierExplorer>().get());
}
TEST(FrontierExplorer, HoldsOnBadInput) {
  holds_on_bad_input(std::make_unique<FrontierExplorer>().get());
}
TEST(FrontierExplorer, OddFiniteInputsGiveFiniteBoundedSetpoints) {
  odd_finite_inputs_give_finite_bounded_setpoints(std::make_unique<FrontierExplorer>().get());
}
TEST(FrontierExplorer, GuidanceStepNeverAllocates) {
  never_allocates(std::make_unique<FrontierExplorer>().get());
}

}  // namespace
}  // namespace kestrel::exploration
