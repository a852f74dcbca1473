#include "kestrel/autonomy/clearance_guard.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::autonomy {

Status validate(const ClearanceParams& p) {
  const bool ok = std::isfinite(p.min_clearance_m) && p.min_clearance_m >= 0.0f && p.min_clearance_m <= 3.0f &&
                  std::isfinite(p.max_rise_m) && p.max_rise_m >= 0.0f && p.max_rise_m <= 3.0f &&
                  std::isfinite(p.hold_s) && p.hold_s >= 0.0f && p.hold_s <= 60.0f;
  return ok ? Status::kOk : Status::kInvalidArgument;
}

float ClearanceGuard::floor_under(float placed_floor_m, std::optional<float> weighed_floor_m) {
  if (!weighed_floor_m.has_value() || !std::isfinite(*weighed_floor_m)) return placed_floor_m;
  if (!std::isfinite(placed_floor_m)) return *weighed_floor_m;
  return std::max(placed_floor_m, *weighed_floor_m);
}

void ClearanceGuard::apply(TimeUs now, float floor_m, bool in_flight, GuidanceSetpoint& setpoint) {
  if (!in_flight || params_.min_clearance_m <= 0.0f) {
    rise_m_ = 0.0f;
    kept_above_m_ = kNothingUnder;
    raised_for_kept_ = false;
    return;
  }
  // Only a raised floor wants a height: on the take-off floor the flight altitude is the
  // operator's, whatever the clearance. A floor that is not a number wants none, and the
  // standing height is held as any other. A height, not a rise, is held: a set-point that
  // already stands above it (the estimated height the mission holds the cycle it turns home,
  // already raised) is not raised again.
  const float wanted = floor_m > 0.0f && std::isfinite(floor_m) ? floor_m + params_.min_clearance_m : kNothingUnder;
  // A clock that stepped back counts as the hold being over: it cannot stretch a rise forever.
  const bool held = now >= wanted_at_ && (now - wanted_at_).seconds() < params_.hold_s;
  if (wanted >= kept_above_m_ || !held) {
    // A height kept anew after the hold that raises nothing ends the rise: the next is another.
    if (!held && !(wanted > setpoint.position_m.z())) raised_for_kept_ = false;
    kept_above_m_ = wanted;
    wanted_at_ = now;
  }
  // The controller refuses a set-point that is not finite: it is passed on unraised.
  const float rise = kept_above_m_ - setpoint.position_m.z();
  rise_m_ = std::isfinite(rise) ? std::clamp(rise, 0.0f, params_.max_rise_m) : 0.0f;
  setpoint.position_m.z() += rise_m_;
  if (rise_m_ > 0.0f && !raised_for_kept_) ++rises_;
  raised_for_kept_ = raised_for_kept_ || rise_m_ > 0.0f;
}

}  // namespace kestrel::autonomy
