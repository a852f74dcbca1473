#pragma once
// Approach limiter: the last word on an explorer's velocity command, on the raw scan in the
// body frame, so that it holds however far the navigation estimate has drifted.
//
// Paper 002's blend keeps off walls only on balance: K_safe pushes back from the few beams of a
// door jamb inside r_safe while K_fr (x_waypoint - x) pulls towards a waypoint whose straight
// path grazes the jamb, and in closed loop the two settle with the 0.27 m vehicle touching it.
// Every return i, at range r_i along the body-frame unit vector u_i, bounds the speed at which
// the vehicle may close on it:
//     v . u_i <= gain (r_i - stop_distance)
// (negative inside stop_distance: the vehicle must back off). Motion away from the returns is
// untouched, motion along a wall is slowed only as much as the wall's oblique returns ask. The
// command is projected onto the most broken of these half-planes, again and again (a wall
// needs one cut, a corner two or three); if bounds are still broken after kMaxCuts the command
// is scaled down until none is (zero, the last resort, breaks none while every return is
// beyond stop_distance). Each cut is a pass over the returns within reach. Integer only, in
// mm/s and Q14 directions, for the FPU-less Verdex.
//
// Behind the laser (the URG-04LX's 120 degrees, the UTM-30LX's 90) nothing is seen: the
// yaw-rate limit turns the heading towards a new waypoint over seconds while equation 5 pulls
// towards it at once, so the vehicle may slide sideways or backwards past a door jamb it
// cannot see. Every direction of that arc bounds the closing speed at blind_speed_mps.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <span>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/exploration/beam_directions.hpp"
#include "kestrel/exploration/params.hpp"

namespace kestrel::exploration {

struct ApproachResult {
  uint8_t cuts = 0;          // projections onto a broken bound
  bool scaled = false;       // bounds still broken after the last cut: the command was scaled
  bool stopped = false;      // ... down to zero (a return inside stop_distance was still closed on)
  float removed_mps = 0.0f;  // |command in - command out|
};

// A return the laser cannot give but the vehicle must keep off: the nearest point of an
// operator keep-out box (a glass window passes the beams), in the body frame.
struct VirtualReturn {
  float dir_x = 1, dir_y = 0;  // unit vector towards it
  float range_m = 0;           // 0 when inside the box: dir points away from the nearest way out
};

class ApproachLimiter {
 public:
  static constexpr uint8_t kMaxCuts = 12;
  static constexpr std::size_t kMaxBlind = 72;    // directions sampled in the blind arc
  static constexpr std::size_t kMaxVirtual = 4;   // virtual returns per call (keep-out boxes)

  // kInvalidArgument for parameters that fail ApproachParams::validate or an invalid geometry
  // (the limiter is then off).
  Status configure(const ApproachParams& params, const BeamGeometry& geometry);
  bool enabled() const { return enabled_; }

  // Limits the body-frame command v (m/s) against the scan's returns, beam i along
  // directions.cos/sin[i]. The scan must have the geometry the directions were built for.
  // The first kMaxVirtual of `virtual_returns` bound it as returns do.
  ApproachResult limit(const LaserScan& scan, const BeamDirections& directions, Eigen::Vector2f& v,
                       std::span<const VirtualReturn> virtual_returns = {}) const;

 private:
  struct Virtual {
    int64_t c = 0, s = 0, bound = 0;  // Q14 direction, bound in mm/s
  };
  void scale_to_bounds(const LaserScan& scan, const BeamDirections& directions, std::span<const Virtual> extra,
                       int64_t& vx, int64_t& vy, ApproachResult& out) const;

  int32_t stop_mm_ = 0;
  int32_t gain_q8_ = 0;  // 1/s in Q8: bound (mm/s) = (gain_q8 * (r - stop)) >> 8
  int32_t max_mm_ = 0;
  int32_t blind_bound_mmps_ = 0;
  std::array<BeamDirections::Trig, kMaxBlind> blind_cos_{}, blind_sin_{};
  uint8_t blind_count_ = 0;
  bool enabled_ = false;
};

}  // namespace kestrel::exploration
