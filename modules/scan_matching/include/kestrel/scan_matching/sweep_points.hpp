#pragma once
// A laser scan's returns as points in the sensor frame at the scan's stamp, in one integer pass.
//
// The laser takes its beams one after another (the URG-04LX's 682 over 67 ms), so a vehicle
// that moves or turns meanwhile sees each beam from a different pose. Beam i is taken
// t = i * beam_interval after the stamp; with the velocity v (sensor frame) and yaw rate w held
// over the sweep, it was turned by a = w t and carried v t, and its point p = r (cos, sin) is
// moved to where the sensor was at the stamp, to second order in a (below a millimetre at 4 m
// over one sweep at 0.8 rad/s):
//   x' = (1 - a^2/2) x - a y + vx t,   y' = a x + (1 - a^2/2) y + vy t
//
// Why integer: this runs on every scan on the real-time path of the Verdex, whose XScale has no
// FPU, and in software floating point the former float deskew alone cost about 0.2 M
// instructions per URG-04LX scan. Here each point is a handful of 32 x 32-bit multiplies whose
// high word is kept (one SMULL each on ARMv5TE and on the Cortex-A8), and only the final
// int -> float of each coordinate is floating point; the per-scan constants are computed once,
// in float. Figures: `scan_matcher/points_*` in bench/, the README's on-target section.
//
// Fixed point: cos and sin of each beam in Q30; points in Q13 millimetres (a 65.5 m range
// turned by a radian plus 16 m of travel still fit int32); a = i * (turn per beam interval,
// Q30); v t = i * (sensor-frame displacement per beam interval, Q25 mm). Agreement with the
// float formula, evaluated in double, is tested: within 0.02 mm out to 30 m
// (sweep_points_test.cpp).
#include <array>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/scan_matching/scan_points.hpp"

namespace kestrel::scan_matching {

// Directions of a laser's beams in Q30, computed when its geometry changes (a sine and cosine
// per beam per scan would dominate the Verdex's software floating point).
class BeamTable {
 public:
  void update(const LaserScan& scan);
  int32_t cos_q30(std::size_t i) const { return cos_[i]; }
  int32_t sin_q30(std::size_t i) const { return sin_[i]; }

 private:
  std::array<int32_t, kMaxBeams> cos_{}, sin_{};
  float first_rad_ = 0, step_rad_ = 0;
  uint16_t beams_ = 0;
};

// The vehicle's motion during the sweep: world-frame velocity, yaw rate, and the heading at the
// stamp that turns the velocity into the sensor's frame. All zero: the scan is instantaneous.
struct SweepMotion {
  float heading_rad = 0;
  float vx_mps = 0, vy_mps = 0;
  float yaw_rate_radps = 0;
};

// Beyond these over one sweep (or beyond 0.06 m between two beams) the points are left where
// they are (the scan is taken as instantaneous), as they are for a motion that is not finite or
// a scan without a beam interval. No vehicle turns a radian or flies 16 m in a sweep (15 rad/s
// and 240 m/s for the URG-04LX); the bounds keep the fixed point inside int32, and at a radian
// the second-order formula is off by centimetres anyway.
inline constexpr float kMaxSweepTurnRad = 1.0f;
inline constexpr float kMaxSweepTravelM = 16.0f;

// The returns r with min_mm <= r < end_mm (as the floats compare: a return at the end is the
// sensor's maximum, no surface), in beam order, with their range and beam index; returns how
// many. The scan's geometry must be the table's (BeamTable::update).
uint16_t sweep_to_points(const LaserScan& scan, const BeamTable& beams, float min_mm, float end_mm,
                         const SweepMotion& motion, ScanPoints& out);

}  // namespace kestrel::scan_matching
