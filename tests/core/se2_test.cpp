#include "kestrel/core/se2.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace kestrel {
namespace {

constexpr double kTol = 1e-12;

TEST(Angle, WrapIntoHalfOpenInterval) {
  EXPECT_NEAR(wrap_angle(3 * kPi<double>), -kPi<double>, kTol);
  EXPECT_NEAR(wrap_angle(-3 * kPi<double>), -kPi<double>, kTol);
  EXPECT_NEAR(wrap_angle(kPi<double>), -kPi<double>, kTol);
  EXPECT_NEAR(wrap_angle(2 * kPi<double> + 0.1), 0.1, kTol);
  EXPECT_NEAR(wrap_angle(-0.1), -0.1, kTol);
  EXPECT_NEAR(wrap_angle(1e6), std::remainder(1e6, 2 * kPi<double>), 1e-9);
  EXPECT_TRUE(std::isnan(wrap_angle(std::numeric_limits<double>::quiet_NaN())));
  for (double a = -50; a < 50; a += 0.37) {
    const double w = wrap_angle(a);
    EXPECT_GE(w, -kPi<double>);
    EXPECT_LT(w, kPi<double>);
    EXPECT_NEAR(std::cos(w), std::cos(a), 1e-9);
    EXPECT_NEAR(std::sin(w), std::sin(a), 1e-9);
  }
}

TEST(Angle, DiffTakesShortWay) {
  EXPECT_NEAR(angle_diff(deg_to_rad(179.0), deg_to_rad(-179.0)), deg_to_rad(-2.0), 1e-12);
  EXPECT_NEAR(angle_diff(deg_to_rad(-179.0), deg_to_rad(179.0)), deg_to_rad(2.0), 1e-12);
}

TEST(Pose2, ComposeKnownValues) {
  const Pose2d a{1, 2, kPi<double> / 2};
  const Pose2d b{1, 0, 0};
  const Pose2d c = a.compose(b);
  EXPECT_NEAR(c.x, 1, kTol);
  EXPECT_NEAR(c.y, 3, kTol);
  EXPECT_NEAR(c.theta, kPi<double> / 2, kTol);
}

TEST(Pose2, InverseAndBetweenAreConsistent) {
  uint32_t seed = 3;
  auto rnd = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<double>(seed >> 8) / static_cast<double>(1u << 24) * 20.0 - 10.0;
  };
  for (int i = 0; i < 200; ++i) {
    const Pose2d a{rnd(), rnd(), wrap_angle(rnd())};
    const Pose2d b{rnd(), rnd(), wrap_angle(rnd())};
    const Pose2d id = a.compose(a.inverse());
    EXPECT_NEAR(id.x, 0, 1e-9);
    EXPECT_NEAR(id.y, 0, 1e-9);
    EXPECT_NEAR(id.theta, 0, 1e-12);
    const Pose2d back = a.compose(a.between(b));
    EXPECT_NEAR(back.x, b.x, 1e-9);
    EXPECT_NEAR(back.y, b.y, 1e-9);
    EXPECT_NEAR(angle_diff(back.theta, b.theta), 0, 1e-12);
    // associativity
    const Pose2d c{rnd(), rnd(), wrap_angle(rnd())};
    const Pose2d l = a.compose(b).compose(c), r = a.compose(b.compose(c));
    EXPECT_NEAR(l.x, r.x, 1e-9);
    EXPECT_NEAR(l.y, r.y, 1e-9);
    EXPECT_NEAR(angle_diff(l.theta, r.theta), 0, 1e-12);
  }
}

TEST(Pose2, TransformPoint) {
  const Pose2d p{1, 1, kPi<double>};
  const Point2d q = p.transform({1, 0});
  EXPECT_NEAR(q.x, 0, kTol);
  EXPECT_NEAR(q.y, 1, kTol);
}

TEST(Point2, DistanceIsSymmetricAndPlanar) {
  const Point2d a{1, 2}, b{4, 6};
  EXPECT_NEAR(distance(a, b), 5, kTol);
  EXPECT_NEAR(distance(b, a), 5, kTol);
  EXPECT_EQ(distance(a, a), 0);
  EXPECT_NEAR(squared_distance(a, b), 25, kTol);
  EXPECT_NEAR(squared_distance(b, a), 25, kTol);
  EXPECT_EQ(squared_distance(a, a), 0);
}

TEST(Point2, DistanceToSegmentIsPerpendicularInsideAndToTheNearerEndOutside) {
  const Point2d a{0, 0}, b{4, 0};
  EXPECT_NEAR(distance_to_segment(a, b, {2, 3}), 3, kTol);   // over the middle
  EXPECT_NEAR(distance_to_segment(a, b, {-3, 4}), 5, kTol);  // beyond a: from a
  EXPECT_NEAR(distance_to_segment(a, b, {7, -4}), 5, kTol);  // beyond b: from b
  EXPECT_NEAR(distance_to_segment(a, b, {1, 0}), 0, kTol);   // on it
  // A segment of no length is its one point.
  EXPECT_NEAR(distance_to_segment(a, a, {3, 4}), 5, kTol);
}

}  // namespace
}  // namespace kestrel
