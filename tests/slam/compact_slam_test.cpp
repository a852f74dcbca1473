// The compact SLAM as the stack runs it: scans with the filter's (drifting) pose, corrections
// back, and its defined behaviour on bad inputs.
#include "kestrel/slam/compact_slam.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "kestrel/core/alloc_guard.hpp"
#include "slam_scans.hpp"

namespace kestrel::slam {
namespace {

struct Rig {
  std::unique_ptr<SlamMap> map = std::make_unique<SlamMap>();
  std::unique_ptr<CompactSlam> slam = std::make_unique<CompactSlam>(*map);
};

// A filter whose pose drifts by `drift` per scan and takes every correction: what is left of
// its error after `scans` scans along a loop through the world.
struct Flight {
  float final_error_m = 0;
  float worst_error_m = 0;
  uint32_t corrections = 0;
  float corrected_along_x_m = 0;  // sum of |x| shifts the corrections made
};

Flight fly(Rig& r, const test::SegmentWorld& w, const test::LaserModel& laser, int scans, Pose2 drift,
           float radius_x, float radius_y) {
  Flight f;
  Pose2 offset{};
  for (int k = 0; k < scans; ++k) {
    const float a = 0.02f * k;
    const Pose2 truth{radius_x * std::sin(a), radius_y * (1.0f - std::cos(a)) - 0.5f * radius_y, 0.5f * a};
    const Pose2 prior{truth.x + offset.x, truth.y + offset.y, wrap_angle(truth.theta + offset.theta)};
    const SlamResult res = r.slam->process(test::scan_points(w, laser, truth), prior);
    if (res.corrected()) {
      ++f.corrections;
      f.corrected_along_x_m += std::fabs(res.pose.x - prior.x);
      offset = {res.pose.x - truth.x, res.pose.y - truth.y, wrap_angle(res.pose.theta - truth.theta)};
    }
    const float err = std::hypot(offset.x, offset.y);
    f.worst_error_m = std::max(f.worst_error_m, err);
    f.final_error_m = err;
    // The filter holds still while the map warms up, as it does on the ground.
    if (k >= static_cast<int>(SlamParams{}.warmup_scans))
      offset = {offset.x + drift.x, offset.y + drift.y, offset.theta + drift.theta};
  }
  return f;
}

TEST(CompactSlam, ConfigureRefusesBadParameters) {
  Rig r;
  SlamParams p;
  EXPECT_EQ(r.slam->configure(p), Status::kOk);
  p.cell_m = 0;
  EXPECT_EQ(r.slam->configure(p), Status::kInvalidArgument);
  p = {};
  p.iterations = NAN;
  EXPECT_EQ(r.slam->configure(p), Status::kInvalidArgument);
  p = {};
  p.min_points = 500;
  p.max_points = 100;
  EXPECT_EQ(r.slam->configure(p), Status::kInvalidArgument);
}

TEST(CompactSlam, TheFirstScanStartsTheMapAndTheWarmUpDrawsAtThePrior) {
  Rig r;
  SlamParams p;
  p.warmup_scans = 3;
  ASSERT_EQ(r.slam->configure(p), Status::kOk);
  const test::SegmentWorld w = test::slam_room();
  const Pose2 at{0.5f, 0.2f, 0.1f};
  const scan_matching::ScanPoints pts = test::scan_points(w, test::LaserModel::urg04lx(), at);
  SlamResult res = r.slam->process(pts, at);
  EXPECT_EQ(res.flags, slam_flag::kStarted | slam_flag::kDrawn);
  EXPECT_TRUE(r.slam->started());
  EXPECT_GT(r.slam->map().known_cells(), 1000u);
  for (int i = 0; i < 2; ++i) {
    res = r.slam->process(pts, at);
    EXPECT_EQ(res.flags, slam_flag::kWarmingUp | slam_flag::kDrawn);
  }
  // Past the warm-up, the search runs; at the true pose there is nothing to gain.
  res = r.slam->process(pts, at);
  EXPECT_TRUE((res.flags & slam_flag::kMatched) != 0);
  EXPECT_FALSE(res.corrected());
  EXPECT_EQ(res.pose.x, at.x);
  EXPECT_LT(res.level, 100.0f);  // three draws: the walls are well below unknown (128)
}

// Past the warm-up, a scan is drawn only once the sensor has moved draw_every_m or turned
// draw_every_rad since the last scan drawn: a hover does not redraw its own error.
TEST(CompactSlam, AScanIsDrawnOnlyAfterTheSensorHasMovedOrTurned) {
  Rig r;
  SlamParams p;
  p.warmup_scans = 0;
  ASSERT_EQ(r.slam->configure(p), Status::kOk);
  const test::SegmentWorld w = test::slam_room();
  const auto drawn = [&](const Pose2& at) {
    return (r.slam->process(test::scan_points(w, test::LaserModel::urg04lx(), at), at).flags & slam_flag::kDrawn) != 0;
  };
  EXPECT_TRUE(drawn({0, 0, 0}));  // the first scan starts the map
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(drawn({0.01f * i, 0, 0.01f * i})) << i;
  EXPECT_TRUE(drawn({0.35f, 0, 0}));      // moved
  EXPECT_FALSE(drawn({0.40f, 0, 0.1f}));  // 5 cm and 0.1 rad on: not yet
  EXPECT_TRUE(drawn({0.35f, 0, 0.25f}));  // turned
}

TEST(CompactSlam, CorrectionsHoldADriftingFilterOnTheMap) {
  Rig r;
  ASSERT_EQ(r.slam->configure({}), Status::kOk);
  // 5.8 mm and 0.06 degrees of drift per scan (a filter running away at 6 cm/s): 1.7 m and 17
  // degrees over the flight without the SLAM. Where the walls in reach leave a direction free
  // the drift along it is drawn into the map (supported_move), hence the 15 cm.
  const Flight f = fly(r, test::slam_room(), test::LaserModel::urg04lx(), 300, {0.005f, -0.003f, 0.001f}, 2.0f, 1.2f);
  EXPECT_GT(f.corrections, 20u);
  EXPECT_LT(f.worst_error_m, 0.15f);
  EXPECT_LT(f.final_error_m, 0.12f);
  EXPECT_EQ(r.slam->counters().corrections, f.corrections);
}

TEST(CompactSlam, AlongACorridorItDoesNotCorrectWhatTheWallsCannotSay) {
  Rig r;
  ASSERT_EQ(r.slam->configure({}), Status::kOk);
  // Flying 6 m along the corridor with a filter that drifts across it: the walls pull the pose
  // back across, and the corrections, which the map cannot support along it, leave x alone.
  const Flight f = fly(r, test::slam_corridor(), test::LaserModel::urg04lx(), 160, {0.0f, 0.005f, 0.0f}, 3.0f, 0.4f);
  EXPECT_GT(f.corrections, 5u);
  EXPECT_LT(f.worst_error_m, 0.1f);
  EXPECT_LT(f.corrected_along_x_m, 0.1f);
}

// With draw_min_curvature a scan due to be drawn is drawn only where the map pins the fit both
// ways: in a room's corner, yes; along a corridor whose ends are out of reach, where a drifted
// pose would draw the corridor's walls shifted along themselves, no.
TEST(CompactSlam, ADrawMinimumCurvatureDrawsOnlyWhereTheMapPinsThePose) {
  const auto drawn_after_move = [](const test::SegmentWorld& w, float min_curvature) {
    Rig r;
    SlamParams p;
    p.warmup_scans = 2;
    p.draw_min_curvature = min_curvature;
    EXPECT_EQ(r.slam->configure(p), Status::kOk);
    const Pose2 start{0, 0, 0};
    for (int i = 0; i <= 2; ++i) (void)r.slam->process(test::scan_points(w, test::LaserModel::urg04lx(), start), start);
    const Pose2 moved{0.4f, 0, 0};  // past draw_every_m
    const uint32_t flags = r.slam->process(test::scan_points(w, test::LaserModel::urg04lx(), moved), moved).flags;
    // The counts agree with the flags: two scans drawn before (the first, the warm-up's; the
    // third, matched where the second was drawn, was not due), and this one drawn or kept out.
    const SlamCounters& c = r.slam->counters();
    EXPECT_EQ(c.drawn, (flags & slam_flag::kDrawn) != 0 ? 3u : 2u);
    EXPECT_EQ(c.unpinned, (flags & slam_flag::kUnpinned) != 0 ? 1u : 0u);
    return flags;
  };
  using namespace slam_flag;
  // The room's least curvature there is about 2000 levels/m^2 (its end walls at the reach's
  // edge), the corridor's about 300.
  EXPECT_TRUE((drawn_after_move(test::slam_room(), 1000.0f) & kDrawn) != 0);
  const uint32_t corridor = drawn_after_move(test::slam_corridor(), 1000.0f);
  EXPECT_EQ(corridor & kDrawn, 0u);
  EXPECT_TRUE((corridor & kUnpinned) != 0);
  // Off (0, the default), it is drawn wherever due, as CoreSLAM draws.
  EXPECT_TRUE((drawn_after_move(test::slam_corridor(), 0.0f) & kDrawn) != 0);
}

// The curvature is judged over the returns the map knows: a scan turned half onto ground the
// map has not drawn is pinned by the half it knows, though the unknown half, flat at kUnknown,
// dilutes the curvature of the mean over all its returns.
TEST(CompactSlam, APartlyNewScanIsJudgedPinnedByTheReturnsTheMapKnows) {
  const test::SegmentWorld w = test::slam_room();
  const test::LaserModel laser = test::LaserModel::urg04lx();
  const Pose2 drawn_at{0, 0, 0};
  const Pose2 turned{0, 0, 2.2f};  // the 240-degree fan turned well onto the side not drawn
  // What the gate will see at the turned pose, on a map drawn at drawn_at only.
  Rig probe;
  SlamParams p;
  p.warmup_scans = 2;
  ASSERT_EQ(probe.slam->configure(p), Status::kOk);
  for (int i = 0; i <= 2; ++i) (void)probe.slam->process(test::scan_points(w, laser, drawn_at), drawn_at);
  MapScan scan;
  thin_to_map_scan(test::scan_points(w, laser, turned), probe.slam->map().cell_m(), 300, scan);
  const float least = fit_curvature(probe.slam->map(), scan, turned, probe.slam->map().cell_m()).least();
  const float share = known_share(probe.slam->map(), scan, turned);
  ASSERT_GT(share, 0.2f);
  ASSERT_LT(share, 0.8f);
  // A threshold the diluted curvature misses and the known returns' curvature reaches.
  const float threshold = least / std::sqrt(share);
  ASSERT_GT(least / share, threshold);

  Rig r;
  p.draw_min_curvature = threshold;
  ASSERT_EQ(r.slam->configure(p), Status::kOk);
  for (int i = 0; i <= 2; ++i) (void)r.slam->process(test::scan_points(w, laser, drawn_at), drawn_at);
  const uint32_t flags = r.slam->process(test::scan_points(w, laser, turned), turned).flags;
  EXPECT_TRUE((flags & slam_flag::kDrawn) != 0) << flags;
}

// The search's best pose is reported whether the correction is handed back or refused: what
// kestrel-sim's SLAM trace compares with the truth to tell a map that could have corrected the
// filter from one that had followed it.
TEST(CompactSlam, TheBestFitIsReportedWhetherHandedBackOrRefused) {
  const test::SegmentWorld w = test::slam_room();
  const Pose2 truth{0.3f, -0.2f, 0.1f};
  const Pose2 prior{truth.x + 0.1f, truth.y - 0.08f, truth.theta};
  const scan_matching::ScanPoints pts = test::scan_points(w, test::LaserModel::urg04lx(), truth);
  const auto after_warmup = [&](const SlamParams& p) {
    Rig r;
    EXPECT_EQ(r.slam->configure(p), Status::kOk);
    for (int i = 0; i <= static_cast<int>(p.warmup_scans); ++i) (void)r.slam->process(pts, truth);
    return r.slam->process(pts, prior);
  };
  SlamParams p;
  const SlamResult handed_back = after_warmup(p);
  ASSERT_TRUE(handed_back.corrected());
  EXPECT_EQ(handed_back.fit.x, handed_back.pose.x);
  EXPECT_EQ(handed_back.fit.y, handed_back.pose.y);
  EXPECT_LT(std::hypot(handed_back.fit.x - truth.x, handed_back.fit.y - truth.y), 0.04f);

  p.max_correction_m = 0.05f;  // the 13 cm move is now beyond the limit
  const SlamResult refused = after_warmup(p);
  ASSERT_TRUE((refused.flags & slam_flag::kTooFar) != 0) << refused.flags;
  EXPECT_EQ(refused.pose.x, prior.x);
  EXPECT_EQ(refused.pose.y, prior.y);
  EXPECT_LT(std::hypot(refused.fit.x - truth.x, refused.fit.y - truth.y), 0.04f);

  Rig r;  // nothing searched: the fit is the prior
  ASSERT_EQ(r.slam->configure({}), Status::kOk);
  const SlamResult started = r.slam->process(pts, prior);
  EXPECT_EQ(started.fit.x, prior.x);
  EXPECT_EQ(started.fit.y, prior.y);
}

TEST(CompactSlam, BadInputsAreIgnoredWithAReason) {
  Rig r;
  ASSERT_EQ(r.slam->configure({}), Status::kOk);
  const scan_matching::ScanPoints pts = test::scan_points(test::slam_room(), test::LaserModel::urg04lx(), {});
  SlamResult res = r.slam->process(pts, Pose2{NAN, 0, 0});
  EXPECT_EQ(res.flags, slam_flag::kNotFinite);
  EXPECT_FALSE(r.slam->started());
  scan_matching::ScanPoints few = pts;
  few.count = 5;
  res = r.slam->process(few, Pose2{});
  EXPECT_EQ(res.flags, slam_flag::kTooFewPoints);
  EXPECT_FALSE(r.slam->started());
  EXPECT_EQ(r.slam->counters().too_few_points, 1u);
  // Points that are not finite are dropped, not drawn.
  scan_matching::ScanPoints bad = pts;
  for (uint16_t i = 0; i < bad.count; i += 3) bad.x[i] = NAN;
  res = r.slam->process(bad, Pose2{});
  EXPECT_TRUE((res.flags & slam_flag::kStarted) != 0);
  MapScan all;
  thin_to_map_scan(pts, r.slam->map().cell_m(), static_cast<uint16_t>(SlamParams{}.max_points), all);
  EXPECT_LT(res.points, all.count);
  EXPECT_GT(res.points, all.count / 2);
}

TEST(CompactSlam, ProcessingAllocatesNothing) {
  Rig r;
  ASSERT_EQ(r.slam->configure({}), Status::kOk);
  const test::SegmentWorld w = test::slam_room();
  const auto pts = std::make_unique<scan_matching::ScanPoints>(test::scan_points(w, test::LaserModel::utm30lx(), {}));
  alloc_guard::Scope guard;
  for (int i = 0; i < 20; ++i) (void)r.slam->process(*pts, Pose2{0.01f * i, 0, 0});
  EXPECT_EQ(guard.allocations(), 0u);
}

}  // namespace
}  // namespace kestrel::slam
