// Hot paths of the navigation filter: one fixed-clock prediction (200 Hz IMU), and a pose that
// arrives one second late (restart at the slot one second back, replay 200 steps).
// Heap use here is set-up before each benchmark's timed loop (large objects that would not fit
// on the stack); the timed code itself never allocates (see the alloc_guard tests).
#include <benchmark/benchmark.h>

#include <memory>

#include "kestrel/estimation/nav_filter.hpp"

namespace {

using kestrel::Duration;
using kestrel::ImuSample;
using kestrel::PoseMeasurement2;
using kestrel::TimeUs;
using kestrel::estimation::NavFilter;

constexpr int64_t kImuPeriodUs = 5000;  // 200 Hz

ImuSample imu_at(int64_t k) {
  ImuSample s;
  s.stamp = TimeUs::from_us(k * kImuPeriodUs);
  s.accel_mps2 = Eigen::Vector3f(0.1f * static_cast<float>(k % 7), -0.05f, 9.8f);
  s.gyro_radps = Eigen::Vector3f(0.0f, 0.0f, 0.01f);
  return s;
}

PoseMeasurement2 pose_at(TimeUs t) {
  PoseMeasurement2 m;
  m.stamp = t;
  m.covariance = Eigen::Vector3f(1e-4f, 1e-4f, 1e-4f).asDiagonal();
  return m;
}

// Fills the history with 2 s of samples and a pose at 40 Hz.
std::unique_ptr<NavFilter> warmed_filter(int64_t& k) {
  auto f = std::make_unique<NavFilter>();
  (void)f->update_pose(pose_at(TimeUs{}));
  for (k = 1; k <= 400; ++k) {
    (void)f->predict(imu_at(k));
    if (k % 5 == 0) (void)f->update_pose(pose_at(imu_at(k).stamp));
  }
  return f;
}

void BM_Predict(benchmark::State& state) {
  int64_t k = 0;
  auto f = warmed_filter(k);
  for (auto _ : state) {
    benchmark::DoNotOptimize(f->predict(imu_at(k++)));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Predict)->Name("estimation/predict");

void BM_UpdateDelayed1s(benchmark::State& state) {
  int64_t k = 0;
  auto f = warmed_filter(k);
  // One 40 Hz scan period per iteration: five predictions, then a pose taken one second ago
  // (restart 200 slots back, replay them with the 40 poses logged in that second).
  for (auto _ : state) {
    for (int i = 0; i < 5; ++i) (void)f->predict(imu_at(k++));
    const TimeUs late = imu_at(k - 1).stamp - Duration::from_s(1.0);
    benchmark::DoNotOptimize(f->update_pose(pose_at(late + Duration::from_us(1000))));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_UpdateDelayed1s)->Name("estimation/update_delayed_1s");

}  // namespace
