#include "kestrel/sim/imu_params.hpp"

#include <cmath>

namespace kestrel::sim {

void ImuParams::bindings(ConfigBinding (&out)[kBindingCount]) {
  ConfigBinding b[kBindingCount] = {
      {"imu.rate_hz", &rate_hz},
      {"imu.accel_noise_density", &accel_noise_density},
      {"imu.accel_bias_std", &accel_bias_std},
      {"imu.accel_bias_walk", &accel_bias_walk},
      {"imu.gyro_noise_density", &gyro_noise_density},
      {"imu.gyro_bias_std", &gyro_bias_std},
      {"imu.gyro_bias_walk", &gyro_bias_walk},
      {"imu.gravity_mps2", &gravity_mps2}};
  for (std::size_t i = 0; i < kBindingCount; ++i) out[i] = b[i];
}

const char* ImuParams::validate() const {
  if (!(rate_hz >= 10 && rate_hz <= 1000)) return "imu.rate_hz must be in [10, 1000]";
  const double period_us = 1e6 / rate_hz;
  if (std::fabs(period_us - std::round(period_us)) > 1e-6)
    return "imu.rate_hz must give a whole number of microseconds per sample";
  if (!(accel_noise_density >= 0 && accel_bias_std >= 0 && accel_bias_walk >= 0 &&
        gyro_noise_density >= 0 && gyro_bias_std >= 0 && gyro_bias_walk >= 0))
    return "imu noise and bias parameters must be >= 0";
  if (!(gravity_mps2 >= 0 && gravity_mps2 <= 50)) return "imu.gravity_mps2 must be in [0, 50] m/s^2";
  return "";
}

}  // namespace kestrel::sim
