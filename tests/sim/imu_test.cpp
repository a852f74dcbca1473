// The fake IMU: gravity in the body frame, white noise, constant bias, bias random walk, and
// the drift of double integration that paper 000 Figure 3a shows.
#include <gtest/gtest.h>

#include <cmath>

#include "kestrel/sim/sim_imu.hpp"

namespace kestrel::sim {
namespace {

VehicleState rest(TimeUs t, double pitch = 0) {
  VehicleState s;
  s.stamp = t;
  s.pitch_rad = pitch;
  return s;
}

TEST(SimImu, AtRestReadsGravityOnZPlusBiasWithTheRightNoise) {
  ImuParams p;
  p.accel_bias_walk = p.gyro_bias_walk = 0;
  SimImu imu(p, Rng(21));
  EXPECT_EQ(imu.sample_period().us, 5000);
  Eigen::Vector3d s1 = Eigen::Vector3d::Zero(), s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d g1 = Eigen::Vector3d::Zero(), g2 = Eigen::Vector3d::Zero();
  int n = 0;
  for (int64_t ms = 1; ms <= 100000; ++ms) {
    imu.on_step(rest(TimeUs{ms * 1000}));
    ImuSample smp;
    while (imu.poll(smp) == Status::kOk) {
      EXPECT_EQ(smp.stamp.us % 5000, 0);
      const Eigen::Vector3d a = smp.accel_mps2.cast<double>(), g = smp.gyro_radps.cast<double>();
      s1 += a;
      s2 += a.cwiseProduct(a);
      g1 += g;
      g2 += g.cwiseProduct(g);
      ++n;
    }
  }
  ASSERT_EQ(n, 20000);
  const Eigen::Vector3d mean = s1 / n, gmean = g1 / n;
  const Eigen::Vector3d want = Eigen::Vector3d(0, 0, 9.81) + imu.accel_bias();
  const double sigma_a = p.accel_noise_density * std::sqrt(p.rate_hz);
  const double sigma_g = p.gyro_noise_density * std::sqrt(p.rate_hz);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(mean[i], want[i], 4 * sigma_a / std::sqrt(n));
    EXPECT_NEAR(std::sqrt(s2[i] / n - mean[i] * mean[i]), sigma_a, 0.03 * sigma_a);
    EXPECT_NEAR(gmean[i], imu.gyro_bias()[i], 4 * sigma_g / std::sqrt(n));
    EXPECT_NEAR(std::sqrt(g2[i] / n - gmean[i] * gmean[i]), sigma_g, 0.03 * sigma_g);
  }
}

TEST(SimImu, BiasesAcrossSeedsHaveTheConfiguredSpread) {
  ImuParams p;
  double sa = 0, sg = 0;
  const int n = 400;
  for (int seed = 0; seed < n; ++seed) {
    SimImu imu(p, Rng(static_cast<uint64_t>(seed)));
    sa += imu.accel_bias().squaredNorm();
    sg += imu.gyro_bias().squaredNorm();
  }
  EXPECT_NEAR(std::sqrt(sa / (3 * n)), p.accel_bias_std, 0.1 * p.accel_bias_std);
  EXPECT_NEAR(std::sqrt(sg / (3 * n)), p.gyro_bias_std, 0.1 * p.gyro_bias_std);
}

TEST(SimImu, BiasRandomWalkGrowsWithTheSquareRootOfTime) {
  ImuParams p;
  p.accel_bias_std = p.gyro_bias_std = 0;
  p.accel_noise_density = p.gyro_noise_density = 0;
  p.accel_bias_walk = 0.01;
  double s2 = 0;
  const int n = 200;
  const int64_t seconds = 25;
  for (int seed = 0; seed < n; ++seed) {
    SimImu imu(p, Rng(static_cast<uint64_t>(seed) + 1000));
    for (int64_t k = 1; k <= seconds * 200; ++k) imu.on_step(rest(TimeUs{k * 5000}));
    s2 += imu.accel_bias().squaredNorm();
  }
  EXPECT_NEAR(std::sqrt(s2 / (3 * n)), p.accel_bias_walk * std::sqrt(static_cast<double>(seconds)), 0.008);
}

TEST(SimImu, TiltedBodySeesGravityAlongItsAxes) {
  ImuParams p;
  p.accel_bias_std = p.gyro_bias_std = p.accel_noise_density = p.gyro_noise_density = 0;
  p.accel_bias_walk = p.gyro_bias_walk = 0;
  SimImu imu(p, Rng(1));
  const double pitch = 0.3;  // nose down: the body x axis points partly down
  imu.on_step(rest(TimeUs{5000}, pitch));
  ImuSample s;
  ASSERT_EQ(imu.poll(s), Status::kOk);
  EXPECT_NEAR(s.accel_mps2.x(), -9.81 * std::sin(pitch), 1e-5);
  EXPECT_NEAR(s.accel_mps2.y(), 0, 1e-6);
  EXPECT_NEAR(s.accel_mps2.z(), 9.81 * std::cos(pitch), 1e-5);
}

TEST(SimImu, DoubleIntegrationDriftsWithinSecondsLikePaper000Figure3a) {
  // Standing still, integrate the horizontal specific force for 10 s: the velocity error is
  // about bias * 10 s, i.e. tenths of m/s to m/s with MEMS-grade defaults.
  ImuParams p;
  double mean_abs_v = 0;
  const int n = 60;
  for (int seed = 0; seed < n; ++seed) {
    SimImu imu(p, Rng(static_cast<uint64_t>(seed) + 77));
    double vx = 0;
    for (int64_t k = 1; k <= 2000; ++k) {
      imu.on_step(rest(TimeUs{k * 5000}));
      ImuSample s;
      while (imu.poll(s) == Status::kOk) vx += s.accel_mps2.x() * 0.005;
    }
    mean_abs_v += std::fabs(vx) / n;
  }
  // E|N(0, 0.8)| = 0.64 m/s.
  EXPECT_GT(mean_abs_v, 0.4);
  EXPECT_LT(mean_abs_v, 0.9);
}

TEST(SimImu, UnreadSamplesOverflowAreCounted) {
  SimImu imu(ImuParams{}, Rng(1));
  for (int64_t k = 1; k <= 300; ++k) imu.on_step(rest(TimeUs{k * 5000}));
  EXPECT_EQ(imu.overruns(), 300u - 256u);
}

}  // namespace
}  // namespace kestrel::sim
