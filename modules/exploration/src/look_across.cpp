#include "kestrel/exploration/look_across.hpp"

#include <cmath>
#include <numbers>

#include "kestrel/core/angle.hpp"

namespace kestrel::exploration {

void LookAcross::configure(const LookAcrossParams& p) {
  after_us_ = static_cast<int64_t>(std::llround(static_cast<double>(p.after_s) * 1e6));
  release_us_ = static_cast<int64_t>(std::llround(static_cast<double>(p.release_s) * 1e6));
  reset();
}

void LookAcross::reset() {
  have_last_ = false;
  degenerate_ = false;
  active_ = false;
  looks_ = 0;
}

void LookAcross::note(const MatchConstraint& m) {
  if (after_us_ == 0) return;
  if (have_last_ && m.stamp.us <= last_.us) return;
  if (!std::isfinite(m.flat_axis_rad)) return;
  last_ = m.stamp;
  have_last_ = true;
  if (m.degenerate) {
    if (!degenerate_) degenerate_since_ = m.stamp;
    degenerate_ = true;
    axis_rad_ = m.flat_axis_rad;
    if (!active_ && (m.stamp - degenerate_since_).us >= after_us_) {
      active_ = true;
      ++looks_;
    }
    return;
  }
  // A clear match: keep looking across until the clear spell has lasted release_s, so that a
  // feature glimpsed for a scan or two does not swing the heading back and forth.
  if (degenerate_) clear_since_ = m.stamp;
  degenerate_ = false;
  if (active_ && (m.stamp - clear_since_).us >= release_us_) active_ = false;
}

float LookAcross::heading(float target_rad) const {
  if (!active_) return target_rad;
  const float across = wrap_angle(axis_rad_ + static_cast<float>(std::numbers::pi / 2));
  return std::fabs(wrap_angle(across - target_rad)) <= static_cast<float>(std::numbers::pi / 2)
             ? across
             : wrap_angle(across + static_cast<float>(std::numbers::pi));
}

}  // namespace kestrel::exploration
