#include "kestrel/metrics/relative_pose_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace kestrel::metrics {
namespace {

// A wandering reference trajectory.
std::vector<Pose2d> wander(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> step(0.0, 0.5), turn(-0.4, 0.4);
  std::vector<Pose2d> p{Pose2d{2.0, -1.0, 0.3}};
  for (int k = 1; k < n; ++k) p.push_back(p.back().compose(Pose2d{step(rng), step(rng) - 0.25, turn(rng)}));
  return p;
}

TEST(RelativePoseError, IdenticalTrajectoriesHaveNoError) {
  const auto ref = wander(50, 1);
  const auto r = relative_pose_error(ref, ref);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.value().trans_m.count, 49u);
  EXPECT_NEAR(r.value().trans_m.mean, 0, 1e-12);
  EXPECT_NEAR(r.value().rot_deg.max, 0, 1e-9);
}

TEST(RelativePoseError, AGlobalRigidOffsetDoesNotCount) {
  const auto ref = wander(50, 2);
  const Pose2d offset{10.0, -3.0, 2.0};
  std::vector<Pose2d> est;
  for (const Pose2d& p : ref) est.push_back(offset.compose(p));
  const auto r = relative_pose_error(est, ref);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().trans_m.max, 0, 1e-9);
  EXPECT_NEAR(r.value().rot_deg.max, 0, 1e-7);
}

TEST(RelativePoseError, TooLongStepsGiveTheTranslationExcess) {
  // Reference moves 1 m per step along its heading; the estimate 1.1 m, then 1.3 m alternately.
  std::vector<Pose2d> ref{{0, 0, 0.7}}, est{{5, 5, -1.0}};
  for (int k = 1; k <= 10; ++k) {
    ref.push_back(ref.back().compose({1.0, 0, 0}));
    est.push_back(est.back().compose({k % 2 == 1 ? 1.1 : 1.3, 0, 0}));
  }
  const auto r = relative_pose_error(est, ref);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().trans_m.mean, 0.2, 1e-12);
  EXPECT_NEAR(r.value().trans_m.std, 0.1, 1e-12);
  EXPECT_NEAR(r.value().rot_deg.mean, 0, 1e-12);
}

TEST(RelativePoseError, ExtraTurnShowsAsRotationOnly) {
  std::vector<Pose2d> ref{{0, 0, 0}}, est{{0, 0, 0}};
  for (int k = 1; k <= 5; ++k) {
    ref.push_back(ref.back().compose({1.0, 0, 0}));
    est.push_back(est.back().compose({1.0, 0, -deg_to_rad(2.0)}));
  }
  const auto r = relative_pose_error(est, ref);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().trans_m.max, 0, 1e-12);
  EXPECT_NEAR(r.value().rot_deg.mean, 2.0, 1e-9);
  EXPECT_NEAR(r.value().rot_deg.std, 0, 1e-9);
}

TEST(RelativePoseError, OnePairByHand) {
  // δ* = (1, 0, 0), δ = (1, 0.1, 0.1): ε = δ*⁻¹ ⊕ δ = (0, 0.1, 0.1).
  const Pose2d e = relative_error({0, 0, 0}, {1, 0.1, 0.1}, {3, 4, kPi<double> / 2}, {3, 5, kPi<double> / 2});
  EXPECT_NEAR(e.x, 0, 1e-12);
  EXPECT_NEAR(e.y, 0.1, 1e-12);
  EXPECT_NEAR(e.theta, 0.1, 1e-12);
  const std::vector<Pose2d> est{{0, 0, 0}, {1, 0.1, 0.1}}, ref{{3, 4, kPi<double> / 2}, {3, 5, kPi<double> / 2}};
  const auto r = relative_pose_error(est, ref);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().trans_m.mean, 0.1, 1e-12);
  EXPECT_NEAR(r.value().rot_deg.mean, rad_to_deg(0.1), 1e-9);
}

TEST(RelativePoseError, RotationErrorWrapsAcrossPi) {
  // Estimated turn +179°, reference -179°: the error is 2°, not 358°.
  const std::vector<Pose2d> est{{0, 0, 0}, {0, 0, deg_to_rad(179.0)}}, ref{{0, 0, 0}, {0, 0, deg_to_rad(-179.0)}};
  const auto r = relative_pose_error(est, ref);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().rot_deg.mean, 2.0, 1e-9);
}

TEST(RelativePoseError, DeltaAndExplicitPairsAgree) {
  const auto ref = wander(30, 3);
  auto est = ref;
  std::mt19937 rng(9);
  std::normal_distribution<double> n(0, 0.05);
  for (Pose2d& p : est) p = Pose2d{p.x + n(rng), p.y + n(rng), wrap_angle(p.theta + n(rng))};
  std::vector<PosePair> pairs;
  for (std::size_t k = 0; k + 3 < ref.size(); ++k) pairs.push_back({k, k + 3});
  const auto a = relative_pose_error(est, ref, 3);
  const auto b = relative_pose_error(est, ref, pairs);
  ASSERT_TRUE(a.ok());
  ASSERT_TRUE(b.ok());
  EXPECT_DOUBLE_EQ(a.value().trans_m.mean, b.value().trans_m.mean);
  EXPECT_DOUBLE_EQ(a.value().rot_deg.std, b.value().rot_deg.std);
  EXPECT_GT(a.value().trans_m.mean, 0.01);
}

TEST(RelativePoseError, BadInputs) {
  const auto ref = wander(5, 4);
  std::vector<Pose2d> shorter(ref.begin(), ref.end() - 1);
  EXPECT_EQ(relative_pose_error(shorter, ref).status(), Status::kInvalidArgument);
  EXPECT_EQ(relative_pose_error(ref, ref, 0).status(), Status::kInvalidArgument);
  EXPECT_EQ(relative_pose_error(ref, ref, 5).status(), Status::kNoData);
  std::vector<Pose2d> bad = ref;
  bad[2].y = std::nan("");
  EXPECT_EQ(relative_pose_error(bad, ref).status(), Status::kNotFinite);
  const PosePair past{0, 5};
  EXPECT_EQ(relative_pose_error(ref, ref, std::span<const PosePair>(&past, 1)).status(), Status::kOutOfRange);
  EXPECT_EQ(relative_pose_error(ref, ref, std::span<const PosePair>()).status(), Status::kNoData);
}

}  // namespace
}  // namespace kestrel::metrics
