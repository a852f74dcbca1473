#include "kestrel/estimation/axis_filter.hpp"

namespace kestrel::estimation {

void axis_predict(AxisState& a, float u, float dt, const AxisNoise& q, float extra_accel_var) {
  const float h = 0.5f * dt * dt;
  const float acc = u - a.x(2);
  a.x(0) += a.x(1) * dt + acc * h;
  a.x(1) += acc * dt;

  // F = [1 dt -h; 0 1 -dt; 0 0 1]; A = F P, then P' = A F^T (symmetric, upper triangle).
  Eigen::Matrix3f& P = a.P;
  const float a00 = P(0, 0) + dt * P(1, 0) - h * P(2, 0);
  const float a01 = P(0, 1) + dt * P(1, 1) - h * P(2, 1);
  const float a02 = P(0, 2) + dt * P(1, 2) - h * P(2, 2);
  const float a11 = P(1, 1) - dt * P(2, 1);
  const float a12 = P(1, 2) - dt * P(2, 2);
  const float a22 = P(2, 2);
  const float p00 = a00 + dt * a01 - h * a02;
  const float p01 = a01 - dt * a02;
  const float p11 = a11 - dt * a12;

  // Discretised white input noise (density qa) and the heading-induced input error.
  const float qa = q.accel * dt + extra_accel_var * dt * dt;
  const float dt2 = dt * dt;
  P(0, 0) = p00 + qa * dt2 * 0.25f + q.pos_walk * dt;
  P(0, 1) = P(1, 0) = p01 + qa * dt * 0.5f;
  P(0, 2) = P(2, 0) = a02;
  P(1, 1) = p11 + qa;
  P(1, 2) = P(2, 1) = a12;
  P(2, 2) = a22 + q.bias_walk * dt;
}

ScalarInnovation axis_position_innovation(const AxisState& a, float z, float r, float delta) {
  const Eigen::Matrix3f& P = a.P;
  ScalarInnovation in;
  in.nu = z - (a.x(0) + delta * a.x(1));
  in.s = P(0, 0) + 2.0f * delta * P(0, 1) + delta * delta * P(1, 1) + r;
  return in;
}

namespace {

// A scalar measurement's update given PH^T: x += K nu, P -= K S K^T (kept exactly symmetric).
void scalar_update(AxisState& a, const Eigen::Vector3f& ph, const ScalarInnovation& in) {
  if (!(in.s > 0.0f)) return;
  Eigen::Matrix3f& P = a.P;
  const Eigen::Vector3f k = ph / in.s;
  a.x += k * in.nu;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      const float v = P(i, j) - k(i) * ph(j);
      P(i, j) = v;
      P(j, i) = v;
    }
  }
}

}  // namespace

void axis_position_update(AxisState& a, const ScalarInnovation& in, float delta) {
  // PH^T = P column 0 + delta * column 1.
  scalar_update(a, a.P.col(0) + delta * a.P.col(1), in);
}

ScalarInnovation axis_velocity_innovation(const AxisState& a, float z, float r) {
  ScalarInnovation in;
  in.nu = z - a.x(1);
  in.s = a.P(1, 1) + r;
  return in;
}

void axis_velocity_update(AxisState& a, const ScalarInnovation& in) { scalar_update(a, a.P.col(1), in); }

}  // namespace kestrel::estimation
