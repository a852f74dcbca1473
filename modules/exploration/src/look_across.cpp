#include "kestrel/exploration/look_across.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kestrel/core/angle.hpp"

namespace kestrel::exploration {

void LookAcross::configure(const LookAcrossParams& p) {
  // A positive time, however short, is on: at least a microsecond.
  after_us_ = p.after_s > 0.0f ? std::max<int64_t>(1, std::llround(static_cast<double>(p.after_s) * 1e6)) : 0;
  release_us_ = static_cast<int64_t>(std::llround(static_cast<double>(p.release_s) * 1e6));
  reset();
}

void LookAcross::reset() {
  have_last_ = false;
  degenerate_ = false;
  active_ = false;
  side_ = 0;
  looks_ = 0;
}

void LookAcross::note(const MatchConstraint& m) {
  if (after_us_ == 0) return;
  if (have_last_ && m.stamp <= last_) return;
  const bool gap = have_last_ && (m.stamp - last_).us > kMaxGapUs;
  last_ = m.stamp;
  have_last_ = true;
  if (m.usable && m.degenerate && std::isfinite(m.flat_axis_rad)) {
    if (!degenerate_ || gap) degenerate_since_ = m.stamp;
    degenerate_ = true;
    axis_rad_ = m.flat_axis_rad;
    if (!active_ && (m.stamp - degenerate_since_).us >= after_us_) {
      active_ = true;
      side_ = 0;
      ++looks_;
    }
    return;
  }
  // Not a degenerate match: keep looking across until this spell has lasted release_s, so that
  // a feature glimpsed for a scan or two does not swing the heading back and forth.
  if (degenerate_ || gap) clear_since_ = m.stamp;
  degenerate_ = false;
  if (active_ && (m.stamp - clear_since_).us >= release_us_) active_ = false;
}

float LookAcross::heading(float target_rad) {
  if (!active_) return target_rad;
  constexpr float kQuarter = std::numbers::pi_v<float> / 2;
  const float plus = wrap_angle(axis_rad_ + kQuarter), minus = wrap_angle(axis_rad_ - kQuarter);
  const float off_plus = std::fabs(wrap_angle(plus - target_rad));
  const float off_minus = std::fabs(wrap_angle(minus - target_rad));
  const float off_kept = side_ > 0 ? off_plus : off_minus;
  if (side_ == 0 || off_kept > kQuarter + kSideHysteresisRad) side_ = off_plus <= off_minus ? 1.0f : -1.0f;
  return side_ > 0 ? plus : minus;
}

}  // namespace kestrel::exploration
