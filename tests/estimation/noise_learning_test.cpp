// Discriminative learning of the noise parameters (paper 000 section 5.2): on synthetic
// flights with ground truth, the learnt parameters give a smaller velocity error than the
// hand-chosen defaults, also on a flight not used for learning.
#include "kestrel/estimation/noise_learning.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "synthetic_flight.hpp"

namespace kestrel::estimation {
namespace {

TEST(NoiseLearning, LearntParametersReduceVelocityErrorOnHeldOutFlight) {
  const bool host = KESTREL_TARGET_IS_HOST;
  test::SyntheticConfig c;
  c.imu_hz = 100;
  c.duration_s = host ? 20.0 : 10.0;
  c.accel_sigma = 0.05f;
  c.pose_sigma = 0.02f;
  c.seed = 31;
  const auto train1 = test::make_flight(c);
  c.seed = 32;
  const auto train2 = test::make_flight(c);
  c.seed = 33;
  const auto held_out = test::make_flight(c);
  const RecordedRun runs[] = {train1.run(Duration::from_ms(25)), train2.run(Duration::from_ms(25))};

  // Hand-chosen: the defaults, with the scan matcher's covariance taken as too small.
  EkfParams hand;
  hand.pose_cov_scale = 0.2f;
  auto filter = std::make_unique<NavFilter>();
  LearningOptions opt;
  opt.max_evaluations = host ? 200 : 100;
  opt.position_time_s = 0.0f;  // the paper's objective: velocity error alone
  const LearningResult r = learn_noise_parameters(*filter, hand, runs, opt);
  EXPECT_LE(r.evaluations, opt.max_evaluations);
  EXPECT_GT(r.before.samples, 1000u);
  EXPECT_LT(r.after.rms_mps, 0.7 * r.before.rms_mps) << "before " << r.before.rms_mps << " after " << r.after.rms_mps;
  EXPECT_EQ(validate(r.params), Status::kOk);

  const RecordedRun test_run[] = {held_out.run(Duration::from_ms(25))};
  const VelocityError e_hand = evaluate_velocity_error(*filter, hand, test_run);
  const VelocityError e_learnt = evaluate_velocity_error(*filter, r.params, test_run);
  EXPECT_LT(e_learnt.rms_mps, 0.8 * e_hand.rms_mps) << "hand " << e_hand.rms_mps << " learnt " << e_learnt.rms_mps;
  EXPECT_LT(e_learnt.mean_mps, e_hand.mean_mps);
  std::printf(
      "velocity error, held-out flight: hand mean %.4f std %.4f rms %.4f m/s; learnt mean %.4f std %.4f rms %.4f m/s "
      "(%d evaluations)\n",
      e_hand.mean_mps, e_hand.std_mps, e_hand.rms_mps, e_learnt.mean_mps, e_learnt.std_mps, e_learnt.rms_mps,
      r.evaluations);
}

TEST(NoiseLearning, EvaluationIsDeterministicAndRejectsInvalidParameters) {
  test::SyntheticConfig c;
  c.duration_s = 3.0;
  const auto fl = test::make_flight(c);
  const RecordedRun runs[] = {fl.run()};
  auto filter = std::make_unique<NavFilter>();
  const VelocityError a = evaluate_velocity_error(*filter, EkfParams{}, runs);
  const VelocityError b = evaluate_velocity_error(*filter, EkfParams{}, runs);
  EXPECT_EQ(a.rms_mps, b.rms_mps);
  EXPECT_GT(a.samples, 0u);
  EkfParams bad;
  bad.pose_cov_scale = 0.0f;
  EXPECT_TRUE(std::isinf(evaluate_velocity_error(*filter, bad, runs).rms_mps));
  // The objective: velocity alone at tau = 0; position error over tau added otherwise, so it
  // is larger, and shrinks as tau grows; a negative tau is refused (infinite).
  EXPECT_EQ(a.objective, a.rms_mps);
  const VelocityError t1 = evaluate_velocity_error(*filter, EkfParams{}, runs, 1.0f);
  const VelocityError t2 = evaluate_velocity_error(*filter, EkfParams{}, runs, 2.0f);
  EXPECT_EQ(t1.rms_mps, a.rms_mps);
  EXPECT_GT(t1.objective, a.rms_mps);
  EXPECT_LT(t2.objective, t1.objective);
  EXPECT_GT(t2.objective, a.rms_mps);
  EXPECT_TRUE(std::isinf(evaluate_velocity_error(*filter, EkfParams{}, runs, -1.0f).objective));
  // No runs at all: no samples, infinite error.
  EXPECT_TRUE(std::isinf(evaluate_velocity_error(*filter, EkfParams{}, {}).rms_mps));
}

}  // namespace
}  // namespace kestrel::estimation
