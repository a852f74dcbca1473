#pragma once
// One world axis of the decoupled navigation filter (paper 000 section 5.2): state
// [position, velocity, accelerometer bias] with the bias-corrected, world-frame accelerometer
// reading as the input of a constant-acceleration-over-the-step model:
//   p' = p + v dt + (u - b) dt^2 / 2,   v' = v + (u - b) dt,   b' = b.
// The covariance products are written out for the 3x3 case (about 40 multiplications per
// step instead of 54 for the generic F P F^T), because on the FPU-less Verdex every float
// operation is a library call.
//
// A measurement of position taken delta seconds after the state's time uses H = [1 delta 0]
// (the acceleration term over a few milliseconds is below a micrometre).
#include <Eigen/Core>

namespace kestrel::estimation {

struct AxisState {
  Eigen::Vector3f x = Eigen::Vector3f::Zero();  // m, m/s, m/s^2
  Eigen::Matrix3f P = Eigen::Matrix3f::Zero();
};

struct AxisNoise {
  float accel = 0;       // (m/s^2)^2/Hz, white noise on the input
  float bias_walk = 0;   // (m/s^3)^2/Hz
  float pos_walk = 0;    // m^2/s
};

struct ScalarInnovation {
  float nu = 0;  // measurement minus prediction
  float s = 0;   // its variance H P H^T + r
};

// u: measured acceleration along this axis, world frame, gravity removed, bias not removed.
// extra_accel_var: (m/s^2)^2 of input error not in the noise density (heading uncertainty).
void axis_predict(AxisState& a, float u, float dt, const AxisNoise& q, float extra_accel_var);
ScalarInnovation axis_position_innovation(const AxisState& a, float z, float r, float delta);
void axis_position_update(AxisState& a, const ScalarInnovation& in, float delta);
// A velocity measurement (H = [0 1 0]; over the few milliseconds between a slot and a stamp
// the bias term is negligible), used for zero-velocity updates while the vehicle rests.
ScalarInnovation axis_velocity_innovation(const AxisState& a, float z, float r);
void axis_velocity_update(AxisState& a, const ScalarInnovation& in);

}  // namespace kestrel::estimation
