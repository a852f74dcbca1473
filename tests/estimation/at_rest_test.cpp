// Zero-velocity updates while the vehicle rests on the ground: with no pose information along
// an axis (a corridor), they are what makes its accelerometer bias observable before take-off.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "kestrel/estimation/nav_filter.hpp"

namespace kestrel::estimation {
namespace {

constexpr float kBiasX = 0.12f;  // m/s^2: a MEMS bias of 1.5 sigma

// A level vehicle at rest at the origin, heading 0, with an accelerometer bias along x, for
// `seconds` at 200 Hz; after the first pose, only at-rest updates at 40 Hz (when asked).
std::unique_ptr<NavFilter> rest(float seconds, bool at_rest) {
  auto f = std::make_unique<NavFilter>();
  PoseMeasurement2 pm;
  pm.pose = Pose2{0, 0, 0};
  pm.covariance = Eigen::Matrix3f::Identity() * 1e-4f;
  EXPECT_EQ(f->update_pose(pm), Status::kOk);
  const int steps = static_cast<int>(seconds * 200);
  for (int i = 1; i <= steps; ++i) {
    ImuSample imu;
    imu.stamp = TimeUs::from_us(5000LL * i);
    imu.accel_mps2 = Eigen::Vector3f(kBiasX, 0, 9.80665f);
    EXPECT_EQ(f->predict(imu), Status::kOk);
    if (at_rest && i % 5 == 0) {
      EXPECT_EQ(f->update_at_rest(imu.stamp, 1e-4f), Status::kOk);
    }
  }
  return f;
}

// GIVEN a vehicle resting for 2 s with a bias along x and no pose after the first, WHEN the
// filter gets zero-velocity updates, THEN it learns the bias and the velocity stays zero;
// without them the same bias runs the estimate away.
TEST(AtRest, ZeroVelocityUpdatesLearnTheAccelerometerBias) {
  const auto with = rest(2.0f, true);
  EXPECT_NEAR(with->axis(0).x(2), kBiasX, 0.02f);
  EXPECT_NEAR(with->state().velocity_mps.x(), 0.0f, 0.01f);
  EXPECT_NEAR(with->state().position_m.x(), 0.0f, 0.02f);
  EXPECT_EQ(with->counters().at_rest_updates, 80u);

  const auto without = rest(2.0f, false);
  EXPECT_GT(std::fabs(without->state().velocity_mps.x()), 0.15f);
  EXPECT_NEAR(without->axis(0).x(2), 0.0f, 0.01f);  // nothing told it otherwise
}

TEST(AtRest, BadInputsHaveDefinedBehaviour) {
  auto f = std::make_unique<NavFilter>();
  EXPECT_EQ(f->update_at_rest(TimeUs{}, 1e-4f), Status::kNoData);  // not initialised
  const auto g = rest(0.1f, false);
  EXPECT_EQ(g->update_at_rest(TimeUs::from_us(100000), std::numeric_limits<float>::quiet_NaN()), Status::kNotFinite);
  EXPECT_EQ(g->update_at_rest(TimeUs::from_us(100000), 0.0f), Status::kInvalidArgument);
  EXPECT_EQ(g->update_at_rest(TimeUs::from_us(100000), -1.0f), Status::kInvalidArgument);
  EXPECT_EQ(g->update_at_rest(TimeUs::from_s(100), 1e-4f), Status::kTimeJump);  // far future
  EXPECT_EQ(g->counters().at_rest_updates, 0u);
  EXPECT_TRUE(g->state().velocity_mps.allFinite());
}

}  // namespace
}  // namespace kestrel::estimation
