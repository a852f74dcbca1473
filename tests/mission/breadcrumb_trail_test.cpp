#include "kestrel/mission/breadcrumb_trail.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace kestrel::mission {
namespace {

TEST(BreadcrumbTrail, KeepsPointsAtLeastTheSpacingApart) {
  BreadcrumbTrail t(0.5f);
  for (int i = 0; i <= 100; ++i) t.record({0.05f * static_cast<float>(i), 0, 1});
  ASSERT_EQ(t.size(), 11u);  // 0, 0.5, ..., 5.0 m
  EXPECT_NEAR(t.point(10).x(), 5.0f, 1e-5f);
  t.record({std::nanf(""), 0, 1});
  EXPECT_EQ(t.size(), 11u);
}

TEST(BreadcrumbTrail, CutsALoopWhenThePathCrossesItself) {
  BreadcrumbTrail t(0.5f);
  // Out along x, round a square, and back through the point at x = 2.
  for (float x = 0; x <= 4.0f; x += 0.1f) t.record({x, 0, 1});
  for (float y = 0; y <= 2.0f; y += 0.1f) t.record({4, y, 1});
  for (float x = 4; x >= 2.0f; x -= 0.1f) t.record({x, 2, 1});
  for (float y = 2; y >= 0.05f; y -= 0.1f) t.record({2, y, 1});
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
      t.record({x, y, 1});
    }
    x += 1.0f;
    t.record({x, y, 1});
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

}  // namespace
}  // namespace kestrel::mission
