// The compact SLAM's fit of a scan to its map and the Monte Carlo search for the best pose.
#include "kestrel/slam/scan_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "slam_scans.hpp"

namespace kestrel::slam {
namespace {

constexpr float kCell = 0.05f;

// A map of slam_room() drawn from a few poses near the origin, at the truth.
std::unique_ptr<SlamMap> room_map() {
  auto map = std::make_unique<SlamMap>();
  EXPECT_EQ(map->reset(kCell, 0, 0), Status::kOk);
  const test::SegmentWorld w = test::slam_room();
  MapScan s;
  for (const Pose2& p :
       {Pose2{0, 0, 0}, Pose2{-1.5f, 0.5f, 1.0f}, Pose2{1.0f, -2.0f, -2.0f}, Pose2{-2.5f, -1.5f, 2.5f}}) {
    thin_to_map_scan(test::scan_points(w, test::LaserModel::utm30lx(), p), kCell, 1081, s);
    const ScanPlacement at(*map, p);
    for (int k = 0; k < 6; ++k) {
      for (uint16_t i = 0; i < s.count; ++i)
        map->draw_return(at.sensor(), at.place(s.point[i]), 4 * kSub, 80 * kSub, 60);
    }
  }
  return map;
}

TEST(ScanFit, ThinningKeepsAtMostMaxPointsAndDropsWhatTheMapCannotHold) {
  scan_matching::ScanPoints in;
  in.count = 1000;
  for (uint16_t i = 0; i < in.count; ++i) {
    in.x[i] = 1.0f + 0.001f * i;
    in.y[i] = 0.0f;
  }
  in.x[0] = NAN;      // taken by the stride, dropped
  in.x[3] = 1000.0f;  // far beyond the map's span, dropped
  MapScan out;
  thin_to_map_scan(in, kCell, 300, out);
  EXPECT_LE(out.count, 300);
  EXPECT_GE(out.count, 240);
  for (uint16_t i = 0; i < out.count; ++i) EXPECT_LT(std::abs(out.point[i].x), kMapSide * kSub);
  thin_to_map_scan(in, kCell, 2000, out);
  EXPECT_EQ(out.count, 998);
  // 1 m in 5 cm cells: 20 cells.
  EXPECT_EQ(out.point[0].x, static_cast<int32_t>(std::lround((1.0f + 0.001f) / kCell * kSub)));
}

TEST(ScanFit, TheKnownShareCountsTheReturnsOnCellsTheMapHasTouched) {
  const auto map = room_map();
  MapScan s;
  thin_to_map_scan(test::scan_points(test::slam_room(), test::LaserModel::urg04lx(), {}), kCell, 300, s);
  EXPECT_GT(known_share(*map, s, Pose2{}), 0.95f);
  EXPECT_EQ(known_share(*map, s, Pose2{30.0f, 0, 0}), 0.0f);  // wholly beyond what was drawn
  EXPECT_EQ(known_share(*map, MapScan{}, Pose2{}), 0.0f);
}

TEST(ScanFit, TheTruePoseFitsBetterThanAnyPoseNearIt) {
  const auto map = room_map();
  const Pose2 truth{0.3f, -0.4f, 0.2f};
  MapScan s;
  thin_to_map_scan(test::scan_points(test::slam_room(), test::LaserModel::utm30lx(), truth), kCell, 400, s);
  const uint32_t at_truth = mean_level(*map, s, truth);
  EXPECT_LT(at_truth, 60u * kSub);
  for (const Pose2& d : {Pose2{0.06f, 0, 0}, Pose2{-0.06f, 0, 0}, Pose2{0, 0.06f, 0}, Pose2{0, -0.06f, 0},
                         Pose2{0, 0, 0.03f}, Pose2{0, 0, -0.03f}}) {
    const Pose2 off{truth.x + d.x, truth.y + d.y, truth.theta + d.theta};
    EXPECT_GT(mean_level(*map, s, off), at_truth + 10u * kSub) << d.x << " " << d.y << " " << d.theta;
  }
  // A scan placed far off the map samples only unknown cells.
  EXPECT_EQ(mean_level(*map, s, Pose2{500.0f, 0, 0}), uint32_t{kUnknown} * kSub);
}

TEST(ScanFit, TheSearchFindsTheTruePoseFromAnOffsetPrior) {
  const auto map = room_map();
  const test::SegmentWorld w = test::slam_room();
  MapScan s;
  int found = 0;
  for (int k = 0; k < 10; ++k) {
    const Pose2 truth{-1.0f + 0.2f * k, 0.5f - 0.1f * k, 0.3f * k};
    thin_to_map_scan(test::scan_points(w, test::LaserModel::utm30lx(), truth), kCell, 300, s);
    const Pose2 prior{truth.x + 0.12f, truth.y - 0.08f, truth.theta + 0.04f};
    Prng prng(static_cast<uint32_t>(k + 1));
    const FitResult r = monte_carlo_search(*map, s, prior, {0.08f, 0.03f}, {}, 300, prng);
    EXPECT_LT(r.level, r.prior_level);
    const float err = std::hypot(r.pose.x - truth.x, r.pose.y - truth.y);
    if (err < 0.03f && std::fabs(wrap_angle(r.pose.theta - truth.theta)) < 0.01f) ++found;
  }
  EXPECT_GE(found, 9);
}

TEST(ScanFit, TheSearchIsDeterministicForItsSeed) {
  const auto map = room_map();
  MapScan s;
  thin_to_map_scan(test::scan_points(test::slam_room(), test::LaserModel::urg04lx(), {0, 0, 0}), kCell, 300, s);
  Prng a(7), b(7);
  const FitResult ra = monte_carlo_search(*map, s, {0.1f, 0.1f, 0.02f}, {0.08f, 0.03f}, {}, 100, a);
  const FitResult rb = monte_carlo_search(*map, s, {0.1f, 0.1f, 0.02f}, {0.08f, 0.03f}, {}, 100, b);
  EXPECT_EQ(ra.pose.x, rb.pose.x);
  EXPECT_EQ(ra.pose.y, rb.pose.y);
  EXPECT_EQ(ra.pose.theta, rb.pose.theta);
  EXPECT_EQ(ra.level, rb.level);
}

}  // namespace
}  // namespace kestrel::slam
