// kestrel-tune-ekf's core on a short run: recorded closed-loop flights become RecordedRuns
// with ordered, de-duplicated streams; learning the noise parameters on one flight reduces
// the velocity error on a held-out flight of another seed; the learned file loads back; the
// Figure 6b plot is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "kestrel/params/param_file.hpp"
#include "kestrel/tuning/ekf_tuning.hpp"

namespace kestrel::tuning {
namespace {

FlightLog fly(uint64_t seed) {
  FlightSpec spec;
  spec.kind = FlightKind::kWaypoints;
  spec.sim.seed = seed;
  spec.duration_s = 20;
  spec.waypoints = arena_waypoints();
  FlightLog log;
  EXPECT_EQ(fly_and_record(spec, log), "");
  return log;
}

template <typename T>
bool increasing(const std::vector<T>& v) {
  for (std::size_t i = 1; i < v.size(); ++i)
    if (!(v[i - 1].stamp < v[i].stamp)) return false;
  return true;
}

TEST(EkfTuning, LearningReducesHeldOutVelocityErrorAndTheFileLoadsBack) {
  const FlightLog train = fly(1), test = fly(11);
  for (const FlightLog* l : {&train, &test}) {
    ASSERT_FALSE(l->collided);
    EXPECT_GT(l->poses.size(), 500u);  // 40 Hz scans
    EXPECT_GT(l->altitude.size(), 500u);
    EXPECT_TRUE(increasing(l->imu));
    EXPECT_TRUE(increasing(l->poses));
    EXPECT_TRUE(increasing(l->altitude));  // each queued height recorded once
    EXPECT_TRUE(increasing(l->attitude));
  }
  const RunData train_d = make_run_data(train), test_d = make_run_data(test);
  EXPECT_GT(train_d.latency.us, 0);
  const estimation::RecordedRun train_r[1] = {train_d.run()};
  const estimation::RecordedRun test_r[1] = {test_d.run()};

  auto filter = std::make_unique<estimation::NavFilter>();
  const estimation::EkfParams hand;
  estimation::LearningOptions lo;
  lo.max_evaluations = 40;
  const estimation::LearningResult learned = estimation::learn_noise_parameters(*filter, hand, train_r, lo);
  EXPECT_LT(learned.after.objective, learned.before.objective);
  const float tau = lo.position_time_s;
  const estimation::VelocityError before = estimation::evaluate_velocity_error(*filter, hand, test_r, tau);
  const estimation::VelocityError after = estimation::evaluate_velocity_error(*filter, learned.params, test_r, tau);
  ASSERT_GT(before.samples, 1000u);
  EXPECT_LT(after.objective, before.objective) << before.objective << " -> " << after.objective;

  const auto dir = std::filesystem::temp_directory_path() / "kestrel_ekf_tuning_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "ekf.params").string();
  estimation::EkfParams out = learned.params;
  params::ParamError err;
  ASSERT_EQ(params::save_params_file(path.c_str(), estimation::ekf_param_fields(out), "test", err), Status::kOk);
  estimation::EkfParams back;
  ASSERT_EQ(estimation::load_ekf_params(path.c_str(), back, err), Status::kOk) << err.message;
  auto a = estimation::ekf_param_fields(out);
  auto b = estimation::ekf_param_fields(back);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(*a[i].value, *b[i].value) << a[i].key;

  const VelocityTrace tb = trace_velocity(*filter, hand, test_r[0]);
  const VelocityTrace ta = trace_velocity(*filter, learned.params, test_r[0]);
  EXPECT_GT(tb.t_s.size(), 1000u);
  const std::string png = (dir / "velocity.png").string();
  ASSERT_EQ(write_velocity_plot(png, truth_velocity(test_r[0]), tb, ta), Status::kOk);
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace kestrel::tuning

namespace kestrel::tuning {
namespace {

TEST(EkfTuning, BlendLogMovesOnlyTheLearnableParametersGeometrically) {
  estimation::EkfParams from, to;
  to.accel_noise_xy = from.accel_noise_xy * 100.0f;
  to.pose_cov_scale = from.pose_cov_scale / 4.0f;
  to.pose_gate_chi2 = from.pose_gate_chi2 * 2.0f;  // not learnable: stays
  const estimation::EkfParams half = blend_log(from, to, 0.5);
  EXPECT_NEAR(half.accel_noise_xy, from.accel_noise_xy * 10.0f, 1e-4f * from.accel_noise_xy * 10.0f);
  EXPECT_NEAR(half.pose_cov_scale, from.pose_cov_scale / 2.0f, 1e-5f);
  EXPECT_EQ(half.pose_gate_chi2, from.pose_gate_chi2);
  EXPECT_NEAR(blend_log(from, to, 1.0).accel_noise_xy, to.accel_noise_xy, 1e-4f * to.accel_noise_xy);
  EXPECT_FLOAT_EQ(blend_log(from, to, 0.0).accel_noise_xy, from.accel_noise_xy);
}

}  // namespace
}  // namespace kestrel::tuning
