#pragma once
// Wall-following velocity field, paper 002 section III (equations 2-4).
//
// Every in-range beam i pulls the vehicle along its own direction theta_i with the radial
// velocity v_ri = K_wf (r_i - r_t), or K_safe (r_i - r_t) when r_i < r_safe (equation 2); the
// contributions are projected on the body axes and summed (equation 3) and rotated into the
// inertial frame with the heading psi (equation 4). The sum attracts the vehicle to walls
// farther than r_t and repels it from walls nearer than r_t; long walls weigh more than short
// ones because they return more beams.
//
// The per-beam loop is integer only, for the FPU-less Verdex: ranges stay in millimetres,
// cos(theta_i) and sin(theta_i) come from Q14 tables (core Fixed<14>) built once at
// configuration time, products are 32-bit and sums 64-bit, split into the nominal and the safe
// beams so that the two gains (and the normalisation, see FieldNormalisation) are applied once
// per scan, not once per beam.
#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/exploration/beam_directions.hpp"
#include "kestrel/exploration/beam_geometry.hpp"
#include "kestrel/exploration/params.hpp"

namespace kestrel::exploration {

struct FieldResult {
  Eigen::Vector2f body_mps = Eigen::Vector2f::Zero();  // (u_cmd, v_cmd), equation 3
  uint16_t in_range = 0;                               // n: beams that contributed
  uint16_t in_safe = 0;                                // of those, beams closer than r_safe (K_safe)
  uint16_t nearest_beam = 0xFFFFu;                     // index of the nearest in-range return, 0xFFFF if none
  uint16_t nearest_mm = 0;
};

class WallFollowField {
 public:
  static constexpr int kTrigFracBits = BeamDirections::kFracBits;
  using Trig = BeamDirections::Trig;

  // Builds the per-beam tables; kInvalidArgument for a bad geometry or parameters.
  Status configure(const BeamGeometry& geometry, const WallFollowParams& params);
  bool configured() const { return configured_; }
  const BeamGeometry& geometry() const { return geometry_; }
  // The beams' directions, valid once configured (shared with the approach limiter).
  const BeamDirections& directions() const { return directions_; }

  // Equations 2 and 3 on one scan, body frame. kNotFound if unconfigured, kInvalidArgument if
  // the scan's geometry differs from the configured one (result zero in both cases). A scan
  // with no beam in range gives a zero field and kOk.
  Status body_velocity(const LaserScan& scan, FieldResult& out) const;

  // Equation 4: body frame to inertial frame with heading psi.
  static Eigen::Vector2f to_inertial(const Eigen::Vector2f& body, float heading_rad);

 private:
  BeamDirections directions_;
  BeamGeometry geometry_{};
  int32_t target_mm_ = 0;
  uint16_t safe_mm_ = 0;
  uint16_t max_mm_ = 0;
  float gain_wf_ = 0;
  float gain_safe_ = 0;
  float beam_weight_ = 1;  // per-beam factor of the normalisation, metres from millimetres folded in
  FieldNormalisation normalisation_ = FieldNormalisation::kPerRadian;
  bool configured_ = false;
};

}  // namespace kestrel::exploration
