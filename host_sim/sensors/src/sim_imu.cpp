#include "kestrel/sim/sim_imu.hpp"

#include <cmath>

namespace kestrel::sim {

SimImu::SimImu(const ImuParams& params, Rng rng) : p_(params), rng_(rng) {
  period_ = Duration::from_us(static_cast<int64_t>(std::llround(1e6 / p_.rate_hz)));
  next_ = TimeUs{} + period_;
  for (int i = 0; i < 3; ++i) accel_bias_[i] = p_.accel_bias_std * rng_.gaussian();
  for (int i = 0; i < 3; ++i) gyro_bias_[i] = p_.gyro_bias_std * rng_.gaussian();
  // Continuous densities to per-sample deviations: white noise σ = density·√rate, random walk
  // σ per sample = density·√period.
  accel_sigma_ = p_.accel_noise_density * std::sqrt(p_.rate_hz);
  gyro_sigma_ = p_.gyro_noise_density * std::sqrt(p_.rate_hz);
  accel_walk_ = p_.accel_bias_walk * std::sqrt(period_.seconds());
  gyro_walk_ = p_.gyro_bias_walk * std::sqrt(period_.seconds());
}

Status SimImu::poll(ImuSample& out) { return queue_.pop(out) ? Status::kOk : Status::kNoData; }

bool SimImu::on_step(const VehicleState& after) {
  if (after.stamp < next_) return false;
  const Eigen::Matrix3d r = after.rotation();
  const Eigen::Vector3d f_world = after.accel_mps2 + Eigen::Vector3d(0, 0, p_.gravity_mps2);
  const Eigen::Vector3d f_body = r.transpose() * f_world;
  for (int i = 0; i < 3; ++i) {
    accel_bias_[i] += accel_walk_ * rng_.gaussian();
    gyro_bias_[i] += gyro_walk_ * rng_.gaussian();
  }
  ImuSample s;
  s.stamp = after.stamp;
  for (int i = 0; i < 3; ++i) {
    s.accel_mps2[i] = static_cast<float>(f_body[i] + accel_bias_[i] + accel_sigma_ * rng_.gaussian());
    s.gyro_radps[i] = static_cast<float>(after.body_rate_radps[i] + gyro_bias_[i] + gyro_sigma_ * rng_.gaussian());
  }
  last_ = s;
  if (!queue_.push(s)) ++overruns_;
  next_ = next_ + period_;
  if (next_ <= after.stamp) next_ = after.stamp + period_;  // never fall behind by a burst
  return true;
}

}  // namespace kestrel::sim
