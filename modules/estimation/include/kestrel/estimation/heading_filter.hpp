#pragma once
// The heading part of the decoupled navigation filter (paper 000 section 5.2): state
// [heading, yaw gyro bias] with the yaw gyro as input, psi' = psi + (w - b) dt, b' = b; the
// scan matcher measures psi. The yaw rate the filter reports is w - b.
#include <Eigen/Core>

#include "kestrel/estimation/axis_filter.hpp"

namespace kestrel::estimation {

struct HeadingState {
  Eigen::Vector2f x = Eigen::Vector2f::Zero();  // rad (wrapped to [-pi, pi)), rad/s
  Eigen::Matrix2f P = Eigen::Matrix2f::Zero();
};

void heading_predict(HeadingState& h, float gyro_z, float dt, float q_gyro, float q_bias);
// The innovation is wrapped to [-pi, pi).
// yaw_rate: the bias-corrected rate used to extrapolate over delta.
ScalarInnovation heading_innovation(const HeadingState& h, float z, float r, float delta, float yaw_rate);
void heading_update(HeadingState& h, const ScalarInnovation& in, float delta);

}  // namespace kestrel::estimation
