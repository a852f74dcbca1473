#include "kestrel/mission/breadcrumb_trail.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace kestrel::mission {
namespace {

TEST(BreadcrumbTrail, KeepsPointsAtLeastTheSpacingApart) {
  BreadcrumbTrail t(0.5f);
  for (int i = 0; i <= 100; ++i) t.record({0.05f * static_cast<float>(i), 0, 1}, TimeUs{});
  ASSERT_EQ(t.size(), 11u);  // 0, 0.5, ..., 5.0 m
  EXPECT_NEAR(t.point(10).x(), 5.0f, 1e-5f);
  t.record({std::nanf(""), 0, 1}, TimeUs{});
  EXPECT_EQ(t.size(), 11u);
}

TEST(BreadcrumbTrail, CutsALoopWhenThePathCrossesItself) {
  BreadcrumbTrail t(0.5f);
  // Out along x, round a square, and back through the point at x = 2.
  for (float x = 0; x <= 4.0f; x += 0.1f) t.record({x, 0, 1}, TimeUs{});
  for (float y = 0; y <= 2.0f; y += 0.1f) t.record({4, y, 1}, TimeUs{});
  for (float x = 4; x >= 2.0f; x -= 0.1f) t.record({x, 2, 1}, TimeUs{});
  for (float y = 2; y >= 0.05f; y -= 0.1f) t.record({2, y, 1}, TimeUs{});
  // The way home is the short one: everything after the visit near (2, 0) was cut.
  const Eigen::Vector3f last = t.point(t.size() - 1);
  EXPECT_NEAR(last.x(), 2.0f, 0.3f);
  EXPECT_NEAR(last.y(), 0.0f, 0.3f);
  EXPECT_LE(t.size(), 6u);
}

TEST(BreadcrumbTrail, WhenFullDropsStraightStretchesFirstAndKeepsCorners) {
  BreadcrumbTrail t(0.1f);
  // A long zig-zag: straight legs of 20 points joined by corners, never crossing itself.
  float x = 0, y = 0;
  int dir = 1;
  for (int leg = 0; leg < 80; ++leg) {
    for (int k = 0; k < 20; ++k) {
      y += 0.1f * static_cast<float>(dir);
      t.record({x, y, 1}, TimeUs{});
    }
    x += 1.0f;
    t.record({x, y, 1}, TimeUs{});
    dir = -dir;
  }
  EXPECT_LT(t.size(), BreadcrumbTrail::kCapacity);
  // Every corner is still there: the leg ends at y = 0 or y = 2.
  int corners = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (std::fabs(t.point(i).y()) < 0.05f || std::fabs(t.point(i).y() - 2.0f) < 0.05f) ++corners;
  EXPECT_GE(corners, 80);
  EXPECT_NEAR(t.point(t.size() - 1).x(), 80.0f, 1e-3f);
}

// GIVEN a trail drawn over 10 s WHEN the estimate is corrected from t = 5 s on (rotated a
// quarter turn about the origin, then moved) THEN exactly the points recorded since move, by
// that pose; a non-finite correction moves nothing.
TEST(BreadcrumbTrail, LateCorrectionMovesThePointsRecordedSinceItsStamp) {
  BreadcrumbTrail t(0.5f);
  for (int i = 0; i <= 20; ++i) t.record({0.5f * static_cast<float>(i), 1, 1}, TimeUs::from_s(0.5 * i));
  ASSERT_EQ(t.size(), 21u);
  const Pose2 delta{0.2f, -0.1f, 1.5707963f};
  t.shift_since(TimeUs::from_s(5.0), delta);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const float x = 0.5f * static_cast<float>(i);
    if (i < 10) {
      EXPECT_EQ(t.point(i).x(), x);
      EXPECT_EQ(t.point(i).y(), 1.0f);
    } else {
      EXPECT_NEAR(t.point(i).x(), 0.2f - 1.0f, 1e-5f) << i;  // (x, 1) turned to (-1, x), moved
      EXPECT_NEAR(t.point(i).y(), -0.1f + x, 1e-5f) << i;
    }
    EXPECT_EQ(t.point(i).z(), 1.0f);
  }
  const Eigen::Vector3f last = t.point(20);
  t.shift_since(TimeUs{}, Pose2{std::nanf(""), 0, 0});
  EXPECT_EQ(t.point(20), last);
  EXPECT_EQ(t.point(0).x(), 0.0f);
}

// GIVEN a trail thinned when full WHEN a correction comes THEN each point left still moves by
// its own stamp (the stamps went with the points they were recorded with).
TEST(BreadcrumbTrail, ThinnedTrailKeepsEachPointsStamp) {
  BreadcrumbTrail t(0.1f);
  float x = 0, y = 0;
  int dir = 1, n = 0;
  for (int leg = 0; leg < 80; ++leg) {
    for (int k = 0; k < 20; ++k) {
      y += 0.1f * static_cast<float>(dir);
      t.record({x, y, 1}, TimeUs::from_s(x));  // the stamp says which leg
      ++n;
    }
    x += 1.0f;
    t.record({x, y, 1}, TimeUs::from_s(x));
    dir = -dir;
  }
  ASSERT_LT(t.size(), BreadcrumbTrail::kCapacity);  // 1,680 points 0.1 m apart: thinned
  ASSERT_GT(n, static_cast<int>(BreadcrumbTrail::kCapacity));
  for (std::size_t i = 0; i < t.size(); ++i) ASSERT_NEAR(t.stamp(i).seconds(), t.point(i).x(), 1e-4) << i;
  t.shift_since(TimeUs::from_s(40.0), Pose2{0, 5, 0});
  for (std::size_t i = 0; i < t.size(); ++i) {
    const bool moved = t.point(i).x() >= 40.0f - 1e-3f;
    EXPECT_TRUE(moved ? t.point(i).y() >= 5.0f - 1e-4f : t.point(i).y() <= 2.0f + 1e-4f) << i;
  }
}

}  // namespace
}  // namespace kestrel::mission
