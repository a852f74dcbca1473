// Least-squares identification of paper 000 equations 1 and 2 on synthetic logs with known
// gains.
#include "kestrel/control/model_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace kestrel::control {
namespace {

// A log of one axis: a varied command, the response k u + k2 s' + b plus white noise, and the
// rate integrated from it.
void fill(ModelFit& fit, double k, double k2, double b, double noise, uint32_t seed, int n = 4000) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> w(0.0, noise);
  double rate = 0.0;
  const double dt = 0.025;
  for (int i = 0; i < n; ++i) {
    const double t = i * dt;
    const double u = 0.1 * std::sin(0.9 * t) + 0.05 * std::sin(2.3 * t + 0.4) - 0.3 * rate / k;  // some feedback
    const double acc = k * u + k2 * rate + b;
    fit.add(u, rate + w(rng) * 0.1, acc + w(rng));
    rate += acc * dt;
  }
}

TEST(ModelFit, RecoversKnownGainsAndOffsets) {
  ModelFit fit;
  fill(fit, 9.3, 0.0, 0.25, 0.05, 1);
  const Result<UndampedFit> r = fit.fit_undamped();
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().k, 9.3, 0.05);
  EXPECT_NEAR(r.value().b, 0.25, 0.01);
  EXPECT_NEAR(r.value().rms, 0.05, 0.01);  // the noise level: the model explains the rest
  EXPECT_EQ(fit.samples(), 4000u);
}

// Paper 000: fitting the damped model to the data gives k2 ~ 0 (the vehicle is undamped);
// and on damped data the same fit does find the damping.
TEST(ModelFit, DampedModelFindsNoDampingOnUndampedData) {
  ModelFit undamped;
  fill(undamped, 9.8, 0.0, -0.1, 0.05, 2);
  const Result<DampedFit> r = undamped.fit_damped();
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().k1, 9.8, 0.1);
  EXPECT_NEAR(r.value().k2, 0.0, 0.02);
  EXPECT_NEAR(r.value().b, -0.1, 0.02);
  ModelFit damped;
  fill(damped, 9.8, -0.6, -0.1, 0.05, 3);
  const Result<DampedFit> d = damped.fit_damped();
  ASSERT_TRUE(d.ok());
  EXPECT_NEAR(d.value().k2, -0.6, 0.05);
}

TEST(ModelFit, RefusesDegenerateLogsAndSkipsBadSamples) {
  ModelFit constant;
  for (int i = 0; i < 100; ++i) constant.add(0.5, 0.0, 1.0);  // the command never varies
  EXPECT_EQ(constant.fit_undamped().status(), Status::kInvalidArgument);
  EXPECT_EQ(constant.fit_damped().status(), Status::kInvalidArgument);
  ModelFit few;
  few.add(0.1, 0.0, 1.0);
  few.add(0.2, 0.0, 2.0);
  few.add(0.3, 0.0, 3.0);
  EXPECT_EQ(few.fit_undamped().status(), Status::kInvalidArgument);
  few.add(std::nan(""), 0.0, 1.0);
  few.add(0.1, 0.0, INFINITY);
  EXPECT_EQ(few.skipped(), 2u);
  EXPECT_EQ(few.samples(), 3u);
  few.add(0.4, 0.0, 4.0);
  ASSERT_TRUE(few.fit_undamped().ok());
  EXPECT_NEAR(few.fit_undamped().value().k, 10.0, 1e-9);
  EXPECT_NEAR(few.fit_undamped().value().b, 0.0, 1e-9);
}

// A whole flight log in the world frame with the vehicle yawing: the body-frame fit recovers
// the four axes of equation 1.
TEST(ModelFit, FitsTheVehicleModelFromAWorldFrameLog) {
  VehicleModel truth;
  truth.pitch = {9.5f, 0.2f};
  truth.roll = {10.1f, -0.15f};
  truth.thrust = {18.0f, -9.2f};
  truth.yaw = {0.9f, 0.02f};
  std::mt19937 rng(4);
  std::normal_distribution<float> w(0.0f, 0.05f);
  std::vector<ModelSample> log;
  float psi = 0.0f;
  Eigen::Vector3f vel = Eigen::Vector3f::Zero();
  for (int i = 0; i < 6000; ++i) {
    const float t = static_cast<float>(i) * 0.02f;
    ModelSample s;
    s.command.pitch_rad = 0.1f * std::sin(0.7f * t);
    s.command.roll_rad = 0.08f * std::sin(1.1f * t + 1.0f);
    s.command.thrust = 0.5f + 0.05f * std::sin(0.5f * t);
    s.command.yaw_rate_radps = 0.3f * std::sin(0.2f * t);
    const float axb = truth.pitch.k * s.command.pitch_rad + truth.pitch.b;
    const float ayb = truth.roll.k * s.command.roll_rad + truth.roll.b;
    s.accel_mps2 = Eigen::Vector3f(std::cos(psi) * axb - std::sin(psi) * ayb, std::sin(psi) * axb + std::cos(psi) * ayb,
                                   truth.thrust.k * s.command.thrust + truth.thrust.b) +
                   Eigen::Vector3f(w(rng), w(rng), w(rng));
    s.yaw_rate_radps = truth.yaw.k * s.command.yaw_rate_radps + truth.yaw.b + 0.1f * w(rng);
    s.heading_rad = psi;
    s.velocity_mps = vel;
    log.push_back(s);
    psi += s.yaw_rate_radps * 0.02f;
    vel += s.accel_mps2 * 0.02f;
  }
  const Result<VehicleModel> r = fit_vehicle_model(log);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.value().pitch.k, truth.pitch.k, 0.05f);
  EXPECT_NEAR(r.value().pitch.b, truth.pitch.b, 0.01f);
  EXPECT_NEAR(r.value().roll.k, truth.roll.k, 0.05f);
  EXPECT_NEAR(r.value().roll.b, truth.roll.b, 0.01f);
  EXPECT_NEAR(r.value().thrust.k, truth.thrust.k, 0.1f);
  EXPECT_NEAR(r.value().thrust.b, truth.thrust.b, 0.05f);
  EXPECT_NEAR(r.value().yaw.k, truth.yaw.k, 0.01f);
  EXPECT_NEAR(r.value().hover_thrust(), truth.hover_thrust(), 0.005f);
  // An empty log cannot be fitted.
  EXPECT_EQ(fit_vehicle_model({}).status(), Status::kInvalidArgument);
}

}  // namespace
}  // namespace kestrel::control
