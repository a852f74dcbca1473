#include "kestrel/metrics/horizontal_drift.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace kestrel::metrics {
namespace {

// A corridor flight: out 10 m along x and back, the estimate lagging along x by 1 % of the
// distance flown (what an unobserved axis looks like), 2 cm off across, on the ground at both
// ends.
TEST(HorizontalDrift, CorridorOutAndBack) {
  HorizontalDriftAccumulator acc;
  double flown = 0, prev_x = 0;
  for (int k = 0; k <= 200; ++k) {
    const double x = k <= 100 ? 0.1 * k : 0.1 * (200 - k);
    flown += std::fabs(x - prev_x);
    prev_x = x;
    const Eigen::Vector2d truth(x, 5.0);
    const Eigen::Vector2d est(x - 0.01 * flown, 5.02);
    ASSERT_EQ(acc.add(est, truth, k > 0 && k < 200), Status::kOk);
  }
  const HorizontalDrift d = acc.result();
  EXPECT_EQ(d.samples, 201u);
  EXPECT_EQ(d.airborne_m.count, 199u);
  EXPECT_NEAR(d.far_from_start_m, 10.0, 1e-9);
  EXPECT_NEAR(d.far_error_m, std::hypot(0.10, 0.02), 1e-9);  // 10 m flown at the far end
  EXPECT_NEAR(d.final_error_m, std::hypot(0.20, 0.02), 1e-9);  // 20 m flown, on the ground
  // The worst airborne sample is the last one before landing: 19.9 m flown.
  EXPECT_NEAR(d.airborne_m.max, std::hypot(0.199, 0.02), 1e-9);
}

TEST(HorizontalDrift, HeightPlaysNoPartAndTheStartIsTheFirstSample) {
  HorizontalDriftAccumulator acc;
  ASSERT_EQ(acc.add({3.3, 4.4}, {3, 4}, false), Status::kOk);
  ASSERT_EQ(acc.add({0, 0}, {0, 0}, true), Status::kOk);  // 5 m from the start, no error
  const HorizontalDrift d = acc.result();
  EXPECT_NEAR(d.far_from_start_m, 5.0, 1e-12);
  EXPECT_NEAR(d.far_error_m, 0.0, 1e-12);
  EXPECT_NEAR(d.final_error_m, 0.0, 1e-12);
  EXPECT_NEAR(d.airborne_m.max, 0.0, 1e-12);
}

TEST(HorizontalDrift, NonFiniteSamplesAreRefusedAndEmptyIsZero) {
  HorizontalDriftAccumulator acc;
  EXPECT_EQ(acc.result().samples, 0u);
  EXPECT_EQ(acc.result().airborne_m.count, 0u);
  EXPECT_EQ(acc.add({std::nan(""), 0}, {0, 0}, true), Status::kNotFinite);
  EXPECT_EQ(acc.add({0, 0}, {0, INFINITY}, true), Status::kNotFinite);
  EXPECT_EQ(acc.result().samples, 0u);
  // A refused sample does not become the start.
  ASSERT_EQ(acc.add({1, 0}, {1, 0}, true), Status::kOk);
  ASSERT_EQ(acc.add({4, 0.1}, {4, 0}, true), Status::kOk);
  EXPECT_NEAR(acc.result().far_from_start_m, 3.0, 1e-12);
  EXPECT_NEAR(acc.result().far_error_m, 0.1, 1e-12);
}

}  // namespace
}  // namespace kestrel::metrics
