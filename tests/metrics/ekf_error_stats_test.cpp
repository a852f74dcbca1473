#include "kestrel/metrics/ekf_error_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace kestrel::metrics {
namespace {

TEST(EkfErrorStats, KnownOffsets) {
  std::vector<StateSample> est, truth;
  for (int k = 0; k < 10; ++k) {
    StateSample t;
    t.stamp = TimeUs::from_us(1000 * k);
    t.position_m = Eigen::Vector3d(k, 2 * k, 1);
    t.velocity_mps = Eigen::Vector3d(1, 2, 0);
    StateSample e = t;
    e.position_m += Eigen::Vector3d(0.3, 0.4, 0);                     // 0.5 m off
    e.velocity_mps += Eigen::Vector3d(0, k % 2 == 0 ? 0.1 : 0.3, 0);  // 0.1, 0.3 alternately
    truth.push_back(t);
    est.push_back(e);
  }
  const auto r = ekf_error_stats(est, truth);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().position_m.mean, 0.5, 1e-12);
  EXPECT_NEAR(r.value().position_m.std, 0, 1e-12);
  EXPECT_NEAR(r.value().velocity_mps.mean, 0.2, 1e-12);
  EXPECT_NEAR(r.value().velocity_mps.std, 0.1, 1e-12);
  EXPECT_EQ(r.value().velocity_mps.count, 10u);
}

TEST(EkfErrorStats, HorizontalOnlyIgnoresHeight) {
  EkfErrorAccumulator acc(true);
  StateSample t, e;
  e.position_m = Eigen::Vector3d(0.3, 0.4, 5.0);
  e.velocity_mps = Eigen::Vector3d(0, 0, 2.0);
  ASSERT_EQ(acc.add(e, t), Status::kOk);
  EXPECT_NEAR(acc.stats().position_m.mean, 0.5, 1e-12);
  EXPECT_NEAR(acc.stats().velocity_mps.mean, 0, 1e-12);
}

TEST(EkfErrorStats, FromNavStateAndBadInputs) {
  NavState s;
  s.stamp = TimeUs::from_us(7);
  s.position_m = Eigen::Vector3f(1, 2, 3);
  s.velocity_mps = Eigen::Vector3f(4, 5, 6);
  const StateSample x = StateSample::from(s);
  EXPECT_EQ(x.stamp.us, 7);
  EXPECT_EQ(x.velocity_mps.z(), 6.0);

  std::vector<StateSample> a(3), b(3);
  b[1].stamp = TimeUs::from_us(10);
  EXPECT_EQ(ekf_error_stats(a, b).status(), Status::kInvalidArgument);  // stamps differ
  EXPECT_TRUE(ekf_error_stats(a, b, Duration::from_us(10)).ok());
  EXPECT_EQ(ekf_error_stats(a, std::span<const StateSample>(b).first(2)).status(), Status::kInvalidArgument);
  EXPECT_EQ(ekf_error_stats({}, {}).status(), Status::kNoData);
  a[2].velocity_mps.x() = std::nan("");
  b[1].stamp = TimeUs{};
  EXPECT_EQ(ekf_error_stats(a, b).status(), Status::kNotFinite);
  EkfErrorAccumulator acc;
  EXPECT_EQ(acc.add(a[2], b[2]), Status::kNotFinite);
  EXPECT_EQ(acc.stats().position_m.count, 0u);
}

}  // namespace
}  // namespace kestrel::metrics
