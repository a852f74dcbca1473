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

void ClearanceGuard::apply(TimeUs now, float floor_m, bool in_flight, GuidanceSetpoint& setpoint) {
  if (!in_flight || params_.min_clearance_m <= 0.0f) {
    rise_m_ = 0.0f;
    return;
  }
  // Only a raised floor wants a rise: on the take-off floor the flight altitude is the
  // operator's, whatever the clearance. A floor or set-point that is not a number wants none,
  // and the standing one is held as any other (the controller refuses a set-point that is not
  // finite).
  const float want = floor_m + params_.min_clearance_m - setpoint.position_m.z();
  const float wanted = floor_m > 0.0f && std::isfinite(want) ? std::clamp(want, 0.0f, params_.max_rise_m) : 0.0f;
  // A clock that stepped back counts as the hold being over: it cannot stretch a rise forever.
  const bool held = now >= wanted_at_ && (now - wanted_at_).seconds() < params_.hold_s;
  if (wanted >= rise_m_ || !held) {
    rise_m_ = wanted;
    wanted_at_ = now;
  }
  setpoint.position_m.z() += rise_m_;
}

}  // namespace kestrel::autonomy
