#include "kestrel/estimation/heading_filter.hpp"

#include "kestrel/core/angle.hpp"

namespace kestrel::estimation {

void heading_predict(HeadingState& h, float gyro_z, float dt, float q_gyro, float q_bias) {
  h.x(0) = wrap_angle(h.x(0) + (gyro_z - h.x(1)) * dt);
  // F = [1 -dt; 0 1].
  Eigen::Matrix2f& P = h.P;
  const float p00 = P(0, 0) - 2.0f * dt * P(0, 1) + dt * dt * P(1, 1);
  const float p01 = P(0, 1) - dt * P(1, 1);
  P(0, 0) = p00 + q_gyro * dt;
  P(0, 1) = P(1, 0) = p01;
  P(1, 1) += q_bias * dt;
}

// A measurement delta seconds after the state sees psi + (w - b) delta, so H = [1 -delta].
ScalarInnovation heading_innovation(const HeadingState& h, float z, float r, float delta, float yaw_rate) {
  const Eigen::Matrix2f& P = h.P;
  ScalarInnovation in;
  in.nu = angle_diff(z, h.x(0) + yaw_rate * delta);
  in.s = P(0, 0) - 2.0f * delta * P(0, 1) + delta * delta * P(1, 1) + r;
  return in;
}

void heading_update(HeadingState& h, const ScalarInnovation& in, float delta) {
  if (!(in.s > 0.0f)) return;
  Eigen::Matrix2f& P = h.P;
  const Eigen::Vector2f ph = P.col(0) - delta * P.col(1);
  const Eigen::Vector2f k = ph / in.s;
  h.x += k * in.nu;
  h.x(0) = wrap_angle(h.x(0));
  const float p00 = P(0, 0) - k(0) * ph(0);
  const float p01 = P(0, 1) - k(0) * ph(1);
  const float p11 = P(1, 1) - k(1) * ph(1);
  P(0, 0) = p00;
  P(0, 1) = P(1, 0) = p01;
  P(1, 1) = p11;
}

}  // namespace kestrel::estimation
