#include "kestrel/metrics/absolute_trajectory_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace kestrel::metrics {
namespace {

std::vector<Pose2d> random_path(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-5, 5);
  std::vector<Pose2d> p;
  for (int k = 0; k < n; ++k) p.push_back({u(rng), u(rng), wrap_angle(u(rng))});
  return p;
}

TEST(AbsoluteTrajectoryError, RigidlyMovedEstimateAlignsToZero) {
  const auto ref = random_path(40, 1);
  const Pose2d motion{3.0, -7.0, deg_to_rad(130.0)};
  std::vector<Pose2d> est;
  for (const Pose2d& p : ref) est.push_back(motion.compose(p));
  const auto r = absolute_trajectory_error(est, ref);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().trans_m.rmse, 0, 1e-9);
  // The alignment undoes the motion.
  const Pose2d inv = motion.inverse();
  EXPECT_NEAR(r.value().alignment.x, inv.x, 1e-9);
  EXPECT_NEAR(r.value().alignment.y, inv.y, 1e-9);
  EXPECT_NEAR(r.value().alignment.theta, inv.theta, 1e-12);
}

TEST(AbsoluteTrajectoryError, PureTranslationOffset) {
  const auto ref = random_path(10, 2);
  std::vector<Pose2d> est;
  for (const Pose2d& p : ref) est.push_back({p.x + 0.3, p.y - 0.4, p.theta});
  const auto r = absolute_trajectory_error(est, ref);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().trans_m.rmse, 0, 1e-12);
  EXPECT_NEAR(r.value().alignment.x, -0.3, 1e-12);
  EXPECT_NEAR(r.value().alignment.y, 0.4, 1e-12);
  EXPECT_NEAR(r.value().alignment.theta, 0, 1e-12);
}

TEST(AbsoluteTrajectoryError, ScaledSquareKeepsItsResidual) {
  // A cross of radius 1 against the same cross of radius 2: no rigid motion helps (symmetry
  // fixes the identity), every point stays 1 m off.
  const std::vector<Pose2d> ref{{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  const std::vector<Pose2d> est{{2, 0, 0}, {0, 2, 0}, {-2, 0, 0}, {0, -2, 0}};
  const auto r = absolute_trajectory_error(est, ref);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().trans_m.rmse, 1.0, 1e-12);
  EXPECT_NEAR(r.value().trans_m.mean, 1.0, 1e-12);
  EXPECT_NEAR(r.value().alignment.theta, 0, 1e-12);
}

// Oracle: for noisy data, no angle on a fine grid (with its best translation) beats the
// closed form.
TEST(AbsoluteTrajectoryError, ClosedFormBeatsBruteForce) {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, 0.2);
  for (int trial = 0; trial < 5; ++trial) {
    const auto ref = random_path(30, 10 + trial);
    const Pose2d motion{noise(rng) * 20, noise(rng) * 20, wrap_angle(noise(rng) * 10)};
    std::vector<Point2d> e, q;
    std::vector<Pose2d> est;
    for (const Pose2d& p : ref) {
      const Point2d m = motion.transform({p.x + noise(rng), p.y + noise(rng)});
      e.push_back(m);
      q.push_back({p.x, p.y});
      est.push_back({m.x, m.y, 0});
    }
    const auto r = absolute_trajectory_error(est, ref);
    ASSERT_TRUE(r.ok());
    // RMSE at angle th with the best translation for that angle (the centroid difference).
    auto rmse_at = [&](double th) {
      const double c = std::cos(th), s = std::sin(th);
      double mx = 0, my = 0;
      for (std::size_t i = 0; i < e.size(); ++i) {
        mx += q[i].x - (c * e[i].x - s * e[i].y);
        my += q[i].y - (s * e[i].x + c * e[i].y);
      }
      mx /= static_cast<double>(e.size());
      my /= static_cast<double>(e.size());
      double sq = 0;
      for (std::size_t i = 0; i < e.size(); ++i) {
        const double dx = c * e[i].x - s * e[i].y + mx - q[i].x, dy = s * e[i].x + c * e[i].y + my - q[i].y;
        sq += dx * dx + dy * dy;
      }
      return std::sqrt(sq / static_cast<double>(e.size()));
    };
    // A coarse grid of 0.5 degree over the circle, then a fine one around its best cell.
    const double coarse = 2 * kPi<double> / 720;
    double best = 1e9, best_th = 0;
    for (int k = 0; k < 720; ++k) {
      const double th = -kPi<double> + coarse * k;
      const double v = rmse_at(th);
      if (v < best) {
        best = v;
        best_th = th;
      }
    }
    const double centre = best_th;
    for (int k = -1000; k <= 1000; ++k) best = std::min(best, rmse_at(centre + coarse * k / 1000.0));
    EXPECT_LE(r.value().trans_m.rmse, best + 1e-12);
    EXPECT_NEAR(r.value().trans_m.rmse, best, 1e-5);
    const auto a = align_se2(e, q);
    ASSERT_TRUE(a.ok());
    EXPECT_DOUBLE_EQ(a.value().theta, r.value().alignment.theta);
  }
}

TEST(AbsoluteTrajectoryError, BadInputs) {
  const auto ref = random_path(5, 3);
  std::vector<Pose2d> shorter(ref.begin(), ref.end() - 1);
  EXPECT_EQ(absolute_trajectory_error(shorter, ref).status(), Status::kInvalidArgument);
  EXPECT_EQ(absolute_trajectory_error({}, {}).status(), Status::kNoData);
  std::vector<Pose2d> bad = ref;
  bad[1].x = INFINITY;
  EXPECT_EQ(absolute_trajectory_error(bad, ref).status(), Status::kNotFinite);
  // All points on one spot: the angle is free, reported as 0, and the error is exact.
  const std::vector<Pose2d> spot(3, Pose2d{1, 1, 0}), other(3, Pose2d{2, 3, 0});
  const auto r = absolute_trajectory_error(spot, other);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.value().alignment.theta, 0);
  EXPECT_NEAR(r.value().trans_m.rmse, 0, 1e-12);
}

}  // namespace
}  // namespace kestrel::metrics
