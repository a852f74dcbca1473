#include "kestrel/metrics/horizontal_drift.hpp"

namespace kestrel::metrics {

Status HorizontalDriftAccumulator::add(const Eigen::Vector2d& est, const Eigen::Vector2d& truth, bool airborne) {
  if (!est.allFinite() || !truth.allFinite()) return Status::kNotFinite;
  if (drift_.samples == 0) start_ = truth;
  const double error = (est - truth).norm();
  const double from_start = (truth - start_).norm();
  // Strictly farther: on the way back past the same distance the far end's error stays the
  // one measured when the vehicle first got there.
  if (drift_.samples == 0 || from_start > drift_.far_from_start_m) {
    drift_.far_from_start_m = from_start;
    drift_.far_error_m = error;
  }
  drift_.final_error_m = error;
  ++drift_.samples;
  if (airborne) airborne_.add(error);
  return Status::kOk;
}

HorizontalDrift HorizontalDriftAccumulator::result() const {
  HorizontalDrift d = drift_;
  d.airborne_m = airborne_.stats();
  return d;
}

}  // namespace kestrel::metrics
