// The scan matcher's prior from the filter's state (AutonomyStack::scan_task): the pose carried
// to the scan's stamp, the window's standard deviations, the motion the deskew holds over the
// sweep, and no prior from a filter that cannot give one.
#include "kestrel/autonomy/scan_prior.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace kestrel::autonomy {
namespace {

using scan_matching::PosePrior;

const TimeUs kScanStamp = TimeUs::from_s(20.0);

NavState moving_nav(double seconds_after_scan) {
  NavState nav;
  nav.valid = true;
  nav.stamp = TimeUs::from_s(20.0 + seconds_after_scan);
  nav.position_m = Eigen::Vector3f(4.0f, -2.0f, 1.0f);
  nav.velocity_mps = Eigen::Vector3f(0.8f, -0.5f, 0.1f);
  nav.yaw_rate_radps = 0.6f;
  nav.heading_rad = 1.0f;
  nav.position_std_m = Eigen::Vector3f(0.30f, 0.05f, 0.02f);
  nav.heading_std_rad = 0.01f;
  return nav;
}

TEST(ScanPriorTest, CarriesTheFilterBackToTheScanStamp) {
  PosePrior prior;
  ASSERT_TRUE(scan_prior_from_nav(moving_nav(0.15), kScanStamp, prior));
  EXPECT_NEAR(prior.pose.x, 4.0f - 0.8f * 0.15f, 1e-5f);
  EXPECT_NEAR(prior.pose.y, -2.0f + 0.5f * 0.15f, 1e-5f);
  EXPECT_NEAR(prior.pose.theta, 1.0f - 0.6f * 0.15f, 1e-5f);
}

TEST(ScanPriorTest, CarriesForwardToAScanStampedAfterTheFilter) {
  PosePrior prior;
  ASSERT_TRUE(scan_prior_from_nav(moving_nav(-0.1), kScanStamp, prior));
  EXPECT_NEAR(prior.pose.x, 4.0f + 0.8f * 0.1f, 1e-5f);
  EXPECT_NEAR(prior.pose.theta, 1.0f + 0.6f * 0.1f, 1e-5f);
}

TEST(ScanPriorTest, WrapsTheHeadingCarriedAcrossPi) {
  NavState nav = moving_nav(0.1);
  nav.heading_rad = -3.12f;  // 0.06 rad of turn back crosses -pi
  PosePrior prior;
  ASSERT_TRUE(scan_prior_from_nav(nav, kScanStamp, prior));
  EXPECT_NEAR(prior.pose.theta, -3.18f + 2.0f * kPi<float>, 1e-5f);
}

// The deskew needs the world-frame velocity and the yaw rate as the filter has them; the
// matcher rotates them into the sensor frame itself.
TEST(ScanPriorTest, HandsTheFiltersMotionToTheDeskew) {
  PosePrior prior;
  ASSERT_TRUE(scan_prior_from_nav(moving_nav(0.05), kScanStamp, prior));
  EXPECT_FLOAT_EQ(prior.vx_mps, 0.8f);
  EXPECT_FLOAT_EQ(prior.vy_mps, -0.5f);
  EXPECT_FLOAT_EQ(prior.yaw_rate_radps, 0.6f);
}

// Along a corridor one horizontal axis is unknown; the window follows the better-known one.
TEST(ScanPriorTest, WindowFollowsTheBetterKnownHorizontalAxis) {
  PosePrior prior;
  ASSERT_TRUE(scan_prior_from_nav(moving_nav(0.05), kScanStamp, prior));
  EXPECT_FLOAT_EQ(prior.position_std_m, 0.05f);
  EXPECT_FLOAT_EQ(prior.heading_std_rad, 0.01f);
}

TEST(ScanPriorTest, NoPriorBeforeTheFilterIsInitialised) {
  NavState nav = moving_nav(0.05);
  nav.valid = false;
  PosePrior prior;
  prior.position_std_m = 123.0f;
  EXPECT_FALSE(scan_prior_from_nav(nav, kScanStamp, prior));
  EXPECT_EQ(prior.position_std_m, 123.0f);  // untouched
}

TEST(ScanPriorTest, NoPriorAcrossATimeJump) {
  PosePrior prior;
  EXPECT_TRUE(scan_prior_from_nav(moving_nav(kMaxPriorExtrapolationS), kScanStamp, prior));
  EXPECT_FALSE(scan_prior_from_nav(moving_nav(kMaxPriorExtrapolationS + 0.01), kScanStamp, prior));
  EXPECT_FALSE(scan_prior_from_nav(moving_nav(-kMaxPriorExtrapolationS - 0.01), kScanStamp, prior));
  EXPECT_FALSE(scan_prior_from_nav(moving_nav(-3600.0), kScanStamp, prior));
}

TEST(ScanPriorTest, NoPriorFromANonFiniteState) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  PosePrior prior;
  NavState nav = moving_nav(0.05);
  nav.position_m.x() = nan;
  EXPECT_FALSE(scan_prior_from_nav(nav, kScanStamp, prior));
  nav = moving_nav(0.05);
  nav.velocity_mps.y() = inf;
  EXPECT_FALSE(scan_prior_from_nav(nav, kScanStamp, prior));
  nav = moving_nav(0.05);
  nav.yaw_rate_radps = nan;
  EXPECT_FALSE(scan_prior_from_nav(nav, kScanStamp, prior));
  nav = moving_nav(0.05);
  nav.heading_rad = inf;
  EXPECT_FALSE(scan_prior_from_nav(nav, kScanStamp, prior));
}

// After SLAM corrections the filter's frame is the matcher's moved by F (world = F * matcher):
// the prior handed to the matcher is the world prior taken back through F, pose and velocity,
// so that composing it with F again gives the world prior.
TEST(ScanPriorTest, TakenBackIntoTheMatchersFrameThroughTheSlamsCorrection) {
  PosePrior world;
  world.pose = {3.0f, -2.0f, 0.4f};
  world.vx_mps = 0.5f;
  world.vy_mps = -0.2f;
  world.yaw_rate_radps = 0.3f;
  world.position_std_m = 0.05f;
  world.heading_std_rad = 0.01f;
  const Pose2 f{0.7f, -0.4f, 0.2f};
  const PosePrior m = prior_in_matcher_frame(world, f);
  const Pose2 back = f.compose(m.pose);
  EXPECT_NEAR(back.x, world.pose.x, 1e-5f);
  EXPECT_NEAR(back.y, world.pose.y, 1e-5f);
  EXPECT_NEAR(back.theta, world.pose.theta, 1e-5f);
  // The velocity turns with the frame: rotated by F's angle it is the world velocity again.
  const float c = std::cos(f.theta), s = std::sin(f.theta);
  EXPECT_NEAR(c * m.vx_mps - s * m.vy_mps, world.vx_mps, 1e-5f);
  EXPECT_NEAR(s * m.vx_mps + c * m.vy_mps, world.vy_mps, 1e-5f);
  EXPECT_NEAR(std::hypot(m.vx_mps, m.vy_mps), std::hypot(world.vx_mps, world.vy_mps), 1e-5f);
  // What no frame changes: the yaw rate and the uncertainties.
  EXPECT_EQ(m.yaw_rate_radps, world.yaw_rate_radps);
  EXPECT_EQ(m.position_std_m, world.position_std_m);
  EXPECT_EQ(m.heading_std_rad, world.heading_std_rad);
  // No correction: the same prior.
  const PosePrior same = prior_in_matcher_frame(world, Pose2{});
  EXPECT_EQ(same.pose.x, world.pose.x);
  EXPECT_EQ(same.vx_mps, world.vx_mps);
}

}  // namespace
}  // namespace kestrel::autonomy
