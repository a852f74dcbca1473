// Home re-localisation at its two boundaries: what the loop hands over (the reference scans of
// the first minute, then one scan a period on the way home, near home only) and what comes
// back (a fix only when two searches in a row agree), with level 3 run in between as the
// stack runs it.
#include "kestrel/autonomy/home_fix.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "glass_window_world.hpp"
#include "synthetic_points.hpp"

namespace kestrel::autonomy {
namespace {

using test::LaserModel;
using test::scan_points;

// Rooms around home: every direction constrained for a 4 m laser.
test::SegmentWorld rooms() {
  test::SegmentWorld w;
  w.add(-3, -2.5, 5, -2.5);
  w.add(5, -2.5, 5, 3);
  w.add(5, 3, 1, 3);
  w.add(1, 3, 1, 2);
  w.add(1, 2, -1, 2);
  w.add(-1, 2, -1, 3);
  w.add(-1, 3, -3, 3);
  w.add(-3, 3, -3, -2.5);
  w.add_box(2.2, -1.4, 2.8, -0.8);
  w.add_box(-2.0, 0.5, -1.6, 0.9);
  return w;
}

struct Harness {
  Harness() {
    scan_matching::Params m;
    m.max_range_m = 3.99f;
    config.enabled = true;
    EXPECT_EQ(fix->configure(config, m), Status::kOk);
  }
  // One matched scan from `truth`, the filter believing `believed`; level 3 runs after it.
  void scan(const Pose2& truth, const Pose2& believed, bool flying_home, bool at_altitude = true) {
    t = t + Duration::from_ms(100);
    LaserScan raw = world.scan(LaserModel::urg04lx(), truth.x, truth.y, truth.theta, t);
    fix->offer(scan_points(world, LaserModel::urg04lx(), truth), raw, believed, flying_home, at_altitude);
    fix->background_step();
  }
  HomeFixConfig config;
  std::unique_ptr<HomeFix> fix = std::make_unique<HomeFix>();  // 1 MiB: not on the stack
  test::SegmentWorld world = rooms();
  TimeUs t = TimeUs::from_s(10.0);
};

// The first minute: on the ground, then at altitude it turns round and moves off. `frame`: the
// estimate's frame (believed = frame * truth), home at its origin unless given.
void first_minute(Harness& h, const Pose2& frame = {}) {
  for (int i = 0; i < 20; ++i) h.scan({0, 0, 0}, frame, false, /*at_altitude=*/false);
  EXPECT_EQ(h.fix->counters().references, 0u);  // on the ground the laser sees what it flies over
  h.scan({0, 0, 0}, frame, false);
  for (int i = 1; i <= 10; ++i) {
    const Pose2 p{0.25f * static_cast<float>(i), 0.1f * static_cast<float>(i), 0.35f * static_cast<float>(i)};
    h.scan(p, frame.compose(p), false);
  }
}

TEST(HomeFix, DrawsTheTakeOffScanAndThoseOfTheFirstMinuteOnlyWhenTheyShowSomethingNew) {
  Harness h;
  first_minute(h);
  // 2.5 m and 3.5 rad in steps of 0.25 m and 0.35 rad: every third scan or so has moved
  // 1 m or turned 0.8 rad from the last one drawn.
  EXPECT_GE(h.fix->counters().references, 4u);
  EXPECT_LE(h.fix->counters().references, 6u);
  const uint32_t drawn = h.fix->counters().references;
  // After the window nothing more is drawn, however far the vehicle goes.
  h.t = h.t + Duration::from_s(h.config.reference_window_s);
  h.scan({3, -1, 1}, {3, -1, 1}, false);
  EXPECT_EQ(h.fix->counters().references, drawn);
  EXPECT_EQ(h.fix->counters().searches, 0u);  // exploring: never searched
}

TEST(HomeFix, SetsRightAnEstimateOneAndAHalfMetresOffOnceTwoSearchesAgree) {
  Harness h;
  first_minute(h);
  h.t = h.t + Duration::from_s(h.config.reference_window_s);
  const Pose2 drift{1.2f, -0.9f, 0.08f};  // believed = drift * truth
  PoseMeasurement2 out;
  Pose2 truth{1.6f, 0.4f, 2.6f};
  for (int i = 0; i < 30 && !h.fix->take(out); ++i) {
    truth.x -= 0.04f;  // flying home: 0.4 m between searches, another view
    h.scan(truth, drift.compose(truth), true);
  }
  ASSERT_EQ(h.fix->counters().confirmed, 1u);
  EXPECT_GE(h.fix->counters().searches, 2u);
  // One search per period: 10 scans a second, one searched.
  EXPECT_LE(h.fix->counters().searches, 3u);
  EXPECT_NEAR(out.pose.x, truth.x, 0.06f);
  EXPECT_NEAR(out.pose.y, truth.y, 0.06f);
  EXPECT_NEAR(wrap_angle(out.pose.theta - truth.theta), 0.0f, 0.02f);
  EXPECT_EQ(out.stamp, h.t);
}

TEST(HomeFix, SearchesOnlyOnTheWayHomeAndNearHome) {
  Harness h;
  first_minute(h);
  h.t = h.t + Duration::from_s(h.config.reference_window_s);
  for (int i = 0; i < 20; ++i) h.scan({0.5f, 0, 0}, {0.5f, 0, 0}, false);  // exploring
  EXPECT_EQ(h.fix->counters().searches, 0u);
  for (int i = 0; i < 20; ++i) h.scan({0.5f, 0, 0}, {4.8f, 0, 0}, true);  // believed 4.8 m from home
  EXPECT_EQ(h.fix->counters().searches, 0u);
  for (int i = 0; i < 20; ++i) h.scan({0.5f, 0, 0}, {0.5f, 0, 0}, true);
  EXPECT_EQ(h.fix->counters().searches, 2u);  // two seconds, one a second
  EXPECT_EQ(h.fix->counters().found, 0u);     // the estimate was right: nothing to gain
  PoseMeasurement2 out;
  EXPECT_FALSE(h.fix->take(out));
}

// With explore_radius_m, scans are searched while exploring too, within that of home (by the
// estimate), one a period (at 0, the default, only flying home: the test above); the same fix
// rules hold.
TEST(HomeFix, SearchesWhileExploringWithinItsOwnRadiusWhenAsked) {
  Harness h;
  h.config.explore_radius_m = 4.0f;
  scan_matching::Params m;
  m.max_range_m = 3.99f;
  ASSERT_EQ(h.fix->configure(h.config, m), Status::kOk);
  first_minute(h);
  h.t = h.t + Duration::from_s(h.config.reference_window_s);
  Pose2 truth{1.6f, 0.4f, 2.6f};
  for (int i = 0; i < 20; ++i) h.scan(truth, {truth.x + 4.5f, truth.y, truth.theta}, false);  // 6 m out
  EXPECT_EQ(h.fix->counters().searches, 0u);
  // Landed or coming down (not at flight altitude): the laser sees what it flies over.
  for (int i = 0; i < 20; ++i) h.scan(truth, truth, false, /*at_altitude=*/false);
  EXPECT_EQ(h.fix->counters().searches, 0u);
  const Pose2 drift{1.2f, -0.9f, 0.08f};  // believed = drift * truth: about 2.5 m from home
  PoseMeasurement2 out;
  for (int i = 0; i < 30 && !h.fix->take(out); ++i) {
    truth.x -= 0.04f;  // exploring: 0.4 m between searches, another view
    h.scan(truth, drift.compose(truth), false);
  }
  ASSERT_EQ(h.fix->counters().confirmed, 1u);
  EXPECT_LE(h.fix->counters().searches, 3u);
  EXPECT_NEAR(out.pose.x, truth.x, 0.06f);
  EXPECT_NEAR(out.pose.y, truth.y, 0.06f);

  h.config.explore_radius_m = -0.5f;
  EXPECT_EQ(h.fix->configure(h.config, m), Status::kInvalidArgument);
  h.config.explore_radius_m = std::nanf("");
  EXPECT_EQ(h.fix->configure(h.config, m), Status::kInvalidArgument);
}

// The same fix found twice from the same view confirms nothing: a view like another place's
// is like it every time it is asked. Another view confirms it.
TEST(HomeFix, TheSameViewAskedTwiceConfirmsNothing) {
  Harness h;
  first_minute(h);
  h.t = h.t + Duration::from_s(h.config.reference_window_s);
  const Pose2 drift{1.2f, -0.9f, 0.08f};
  const Pose2 truth{1.4f, 0.4f, 2.6f};
  PoseMeasurement2 out;
  for (int i = 0; i < 40; ++i) h.scan(truth, drift.compose(truth), true);  // hovering: 4 searches
  EXPECT_EQ(h.fix->counters().searches, 4u);
  EXPECT_EQ(h.fix->counters().found, 4u);
  EXPECT_EQ(h.fix->counters().confirmed, 0u);
  EXPECT_FALSE(h.fix->take(out));
  const Pose2 turned{truth.x, truth.y, truth.theta + 0.4f};  // the survey turn
  for (int i = 0; i < 10; ++i) h.scan(turned, drift.compose(turned), true);
  EXPECT_EQ(h.fix->counters().confirmed, 1u);
  ASSERT_TRUE(h.fix->take(out));
  EXPECT_NEAR(out.pose.x, turned.x, 0.06f);
  EXPECT_NEAR(out.pose.y, turned.y, 0.06f);
}

// Two fixes agree when they put the vehicle at the same pose, wherever the frame's origin is.
// Home 9 m from it, the estimate's heading turned 0.03 rad between the two searches (about the
// vehicle, as the filter's heading drifts): both fixes are right, but as transforms of the
// frame they differ by 0.03 rad about a point 9 m from the origin, a quarter of a metre there.
TEST(HomeFix, FixesAgreeOnTheVehiclesPoseNotOnTheFramesOrigin) {
  Harness h;
  const Pose2 frame{8.0f, -3.0f, 0.4f};
  first_minute(h, frame);
  h.t = h.t + Duration::from_s(h.config.reference_window_s);
  const Pose2 drift{1.2f, -0.9f, 0.08f};
  const Pose2 heading_drift{0.0f, 0.0f, 0.03f};
  PoseMeasurement2 out;
  Pose2 truth{1.6f, 0.4f, 2.6f};
  for (int i = 0; i < 30 && !h.fix->take(out); ++i) {
    truth.x -= 0.04f;
    const Pose2 believed = frame.compose(drift).compose(truth);
    h.scan(truth, h.fix->counters().searches == 0 ? believed : believed.compose(heading_drift), true);
  }
  ASSERT_EQ(h.fix->counters().confirmed, 1u);
  EXPECT_EQ(h.fix->counters().searches, 2u);  // the second search confirms the first
  const Pose2 right = frame.compose(truth);
  EXPECT_NEAR(out.pose.x, right.x, 0.06f);
  EXPECT_NEAR(out.pose.y, right.y, 0.06f);
  EXPECT_NEAR(wrap_angle(out.pose.theta - right.theta), 0.0f, 0.02f);
}

// Two searches that each find a fix, but not the same one, confirm nothing.
TEST(HomeFix, TwoFixesThatDisagreeConfirmNothing) {
  Harness h;
  first_minute(h);
  h.t = h.t + Duration::from_s(h.config.reference_window_s);
  const Pose2 truth{0.6f, 0.3f, 2.6f};
  h.scan(truth, Pose2{1.0f, -0.8f, 0.0f}.compose(truth), true);
  h.t = h.t + Duration::from_s(1.0);
  h.scan(truth, Pose2{-0.7f, 0.9f, 0.0f}.compose(truth), true);  // the estimate jumped (as if)
  EXPECT_EQ(h.fix->counters().found, 2u);
  EXPECT_EQ(h.fix->counters().confirmed, 0u);
  PoseMeasurement2 out;
  EXPECT_FALSE(h.fix->take(out));
}

// The take-off turn beside a glass window, then, flying home, room A's west end facing the
// hallway (glass_window_world.hpp): its scan fits the hallway's end 3 m north, save that it puts
// a wall where the turn's beams passed through the window. The references carry their raw
// scans, so that test sees it; without them (beams to returns only) a fix is confirmed.
TEST(HomeFix, ConfirmsNoFixThatPutsWallsWhereTheTakeOffTurnSawThrough) {
  Harness h;
  h.world = test::glass_window_world();
  const Pose2 home{2.0f, 7.5f, 0.0f};
  for (int i = 0; i <= 20; ++i) {
    const Pose2 turning{home.x, home.y, 0.35f * static_cast<float>(i)};
    h.scan(turning, turning, false);
  }
  ASSERT_EQ(h.fix->counters().references, 6u);
  h.t = h.t + Duration::from_s(h.config.reference_window_s);
  Pose2 truth{1.34f, 4.3f, 1.5f};
  for (int i = 0; i < 60; ++i) {
    truth.y += 0.01f;  // slowly north, turning: new views
    truth.theta += 0.006f;
    h.scan(truth, {truth.x + 0.3f, truth.y + 0.03f, truth.theta}, true);
  }
  EXPECT_GE(h.fix->counters().searches, 5u);
  EXPECT_GE(h.fix->counters().returns_in_free, 2u);
  EXPECT_EQ(h.fix->counters().confirmed, 0u);
  PoseMeasurement2 out;
  EXPECT_FALSE(h.fix->take(out));
}

TEST(HomeFix, OffDoesNothingAndBadConfigurationIsRefused) {
  auto fix = std::make_unique<HomeFix>();
  HomeFixConfig c;
  scan_matching::Params m;
  m.max_range_m = 3.99f;
  c.enabled = false;
  ASSERT_EQ(fix->configure(c, m), Status::kOk);
  const scan_matching::ScanPoints pts = scan_points(rooms(), LaserModel::urg04lx(), {});
  const LaserScan raw = rooms().scan(LaserModel::urg04lx(), 0, 0, 0, TimeUs::from_s(1.0));
  fix->offer(pts, raw, {}, false, true);
  fix->background_step();
  EXPECT_EQ(fix->counters().references, 0u);

  c.enabled = true;
  c.radius_m = -1.0f;
  EXPECT_EQ(fix->configure(c, m), Status::kInvalidArgument);
  c = {};
  c.period_s = std::nanf("");
  EXPECT_EQ(fix->configure(c, m), Status::kInvalidArgument);
  c = {};
  c.search.window_m = 50.0f;
  EXPECT_EQ(fix->configure(c, m), Status::kInvalidArgument);
  // A pose that is not finite is never handed over.
  c = {};
  c.enabled = true;
  ASSERT_EQ(fix->configure(c, m), Status::kOk);
  fix->offer(pts, raw, {NAN, 0.0f, 0.0f}, false, true);
  fix->background_step();
  EXPECT_EQ(fix->counters().references, 0u);
}

}  // namespace
}  // namespace kestrel::autonomy
