#include "kestrel/scan_matching/sweep_points.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::scan_matching {
namespace {

constexpr float kMetresPerUnit = 1e-3f / (1 << 13);  // points in Q13 mm
constexpr double kQ30 = 1 << 30;
// Between two beams at most this far (600 m/s at the URG-04LX's 98 us): the displacement per
// beam interval is an int32 in Q25 mm.
constexpr float kMaxStepTravelM = 0.06f;
// Beam indices times 2^20 fit int32.
static_assert(kMaxBeams <= 2048);

// The high word of a 32 x 32-bit product: one SMULL on ARMv5TE, SMMUL on ARMv7, where a
// 64-bit result shifted by anything else costs a chain of 64-bit operations.
inline int32_t mul_hi(int32_t a, int32_t b) { return static_cast<int32_t>((int64_t{a} * b) >> 32); }

// The sweep's motion per beam interval, in the sensor frame.
struct PerBeam {
  int32_t turn_q30 = 0;            // rad
  int32_t dx_q25 = 0, dy_q25 = 0;  // mm
  bool moving = false;
};

PerBeam per_beam(const LaserScan& scan, const SweepMotion& m) {
  PerBeam k;
  const float w = m.yaw_rate_radps;
  if (scan.beam_interval.us <= 0 || scan.beam_count < 2 || !std::isfinite(m.heading_rad) || !std::isfinite(w) ||
      !std::isfinite(m.vx_mps) || !std::isfinite(m.vy_mps) || (w == 0.0f && m.vx_mps == 0.0f && m.vy_mps == 0.0f)) {
    return k;  // nothing to correct with: the scan is taken as instantaneous
  }
  const float c = std::cos(m.heading_rad), s = std::sin(m.heading_rad);
  const float vx = c * m.vx_mps + s * m.vy_mps, vy = -s * m.vx_mps + c * m.vy_mps;  // sensor frame
  const float step_s = static_cast<float>(scan.beam_interval.seconds());
  const float sweep_s = step_s * static_cast<float>(scan.beam_count - 1);
  const float turn = w * step_s, dx = vx * step_s, dy = vy * step_s;
  // Written so that a product that overflows to infinity fails too.
  if (!(std::fabs(w) * sweep_s <= kMaxSweepTurnRad) || !(std::fabs(vx) * sweep_s <= kMaxSweepTravelM) ||
      !(std::fabs(vy) * sweep_s <= kMaxSweepTravelM) || !(std::fabs(dx) <= kMaxStepTravelM) ||
      !(std::fabs(dy) <= kMaxStepTravelM)) {
    return k;
  }
  // |turn_q30| * (beam_count - 1) <= 2^30 + beam_count / 2: a = i * turn_q30 fits int32.
  k.turn_q30 = static_cast<int32_t>(std::lround(static_cast<double>(turn) * kQ30));
  k.dx_q25 = static_cast<int32_t>(std::lround(static_cast<double>(dx) * 1e3 * (1 << 25)));
  k.dy_q25 = static_cast<int32_t>(std::lround(static_cast<double>(dy) * 1e3 * (1 << 25)));
  k.moving = k.turn_q30 != 0 || k.dx_q25 != 0 || k.dy_q25 != 0;
  return k;
}

// The least whole number of millimetres not below v, within [0, 65536]: for a whole r,
// r < v exactly when r < whole_mm_at_least(v), and r >= v when r >= it.
int32_t whole_mm_at_least(float v) {
  if (!(v > 0.0f)) return 0;
  if (!(v < 65536.0f)) return 65536;
  return static_cast<int32_t>(std::ceil(v));
}

}  // namespace

void BeamTable::update(const LaserScan& scan) {
  if (scan.beam_count == beams_ && scan.first_angle_rad == first_rad_ && scan.angle_step_rad == step_rad_) return;
  for (uint16_t i = 0; i < scan.beam_count; ++i) {
    const double a = scan.angle_of(i);  // the float angle, as the scan defines it
    cos_[i] = static_cast<int32_t>(std::lround(std::cos(a) * kQ30));
    sin_[i] = static_cast<int32_t>(std::lround(std::sin(a) * kQ30));
  }
  beams_ = scan.beam_count;
  first_rad_ = scan.first_angle_rad;
  step_rad_ = scan.angle_step_rad;
}

namespace {

// The pass, with and without the motion: two loops rather than a test per point keep the
// instantaneous one short and the registers free for the moving one.
template <bool kMoving>
uint16_t points_of(const LaserScan& scan, const BeamTable& beams, int32_t lo, int32_t end, const PerBeam& k,
                   ScanPoints& out) {
  // Locals: the uint16 stores below could alias the scan's uint16 fields for the compiler.
  const uint32_t beam_count = scan.beam_count;
  const uint16_t* range = scan.range_mm.data();
  const int32_t turn = k.turn_q30, dx = k.dx_q25, dy = k.dy_q25;
  uint32_t n = 0;
  for (uint32_t i = 0; i < beam_count; ++i) {
    const int32_t r = range[i];
    if (r < lo || r >= end) continue;
    int32_t c = beams.cos_q30(i), s = beams.sin_q30(i);
    int32_t tx = 0, ty = 0;
    if constexpr (kMoving) {
      // The beam's direction turned by a, then scaled by the range: r ((1 - h) c - a s) is
      // the formula's (1 - h) x - a y. h c and a s come in Q27 and Q28 (below 1e-8), scaled
      // back to Q30; turned by at most a radian, |c| grows by at most 12 %: int32 holds it.
      // (Operands straight from the table and a plain product: the compiler keeps each
      // mul_hi one 32 x 32 multiply, where it widens the result of an earlier one to 64 bits.)
      const int32_t a = turn * static_cast<int32_t>(i);  // Q30, |a| <= 1 rad
      const int32_t h = mul_hi(a, a);                     // a^2 / 2 in Q29
      const int32_t ct = c - (mul_hi(h, c) * 8 + mul_hi(a, s) * 4);
      const int32_t st = s - (mul_hi(h, s) * 8 - mul_hi(a, c) * 4);
      c = ct;
      s = st;
      // (d 2^25) (i 2^20) / 2^32: the travel in Q13 mm; 16 m of it is 2^27.
      const auto i20 = static_cast<int32_t>(i << 20);
      tx = mul_hi(dx, i20);
      ty = mul_hi(dy, i20);
    }
    // (r 2^15) (c 2^30) / 2^32: Q13 mm, |x| < 1.12 * 65535 * 2^13 < 2^29.2.
    out.x[n] = static_cast<float>(mul_hi(r << 15, c) + tx) * kMetresPerUnit;
    out.y[n] = static_cast<float>(mul_hi(r << 15, s) + ty) * kMetresPerUnit;
    out.range_mm[n] = static_cast<uint16_t>(r);
    out.beam[n] = static_cast<uint16_t>(i);
    ++n;
  }
  out.count = static_cast<uint16_t>(n);
  return out.count;
}

}  // namespace

uint16_t sweep_to_points(const LaserScan& scan, const BeamTable& beams, float min_mm, float end_mm,
                         const SweepMotion& motion, ScanPoints& out) {
  const PerBeam k = per_beam(scan, motion);
  const int32_t lo = std::max<int32_t>(whole_mm_at_least(min_mm), kMinValidRangeMm);  // range codes are no returns
  const int32_t end = whole_mm_at_least(end_mm);
  out.angle_step_rad = std::fabs(scan.angle_step_rad);
  return k.moving ? points_of<true>(scan, beams, lo, end, k, out) : points_of<false>(scan, beams, lo, end, k, out);
}

}  // namespace kestrel::scan_matching
