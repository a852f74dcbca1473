#pragma once
// A MEMS-grade IMU of the kind on the small vehicles of the papers (the Hummingbird's own
// board, a MicroStrain 3DM-GX class unit). The biases are what makes double-integrated
// acceleration drift within seconds (paper 000, Figure 3a): with a 0.08 m/s² bias the
// velocity error grows by 0.8 m/s in 10 s and the position error by 4 m.
#include <cstddef>

#include "kestrel/sim/config_file.hpp"

namespace kestrel::sim {

struct ImuParams {
  double rate_hz = 200;                     // 100-200 Hz
  double accel_noise_density = 0.004;       // m/s²/√Hz (white)
  double accel_bias_std = 0.08;             // m/s², per axis, drawn once from the seed
  double accel_bias_walk = 0.0005;          // m/s³/√Hz (bias random walk)
  double gyro_noise_density = 0.0006;       // rad/s/√Hz
  double gyro_bias_std = 0.005;             // rad/s, per axis, drawn once
  double gyro_bias_walk = 0.00002;          // rad/s²/√Hz
  double gravity_mps2 = 9.81;               // [0, 50] (-1e300 flew NaN)

  static constexpr std::size_t kBindingCount = 8;
  void bindings(ConfigBinding (&out)[kBindingCount]);
  const char* validate() const;
};

}  // namespace kestrel::sim
