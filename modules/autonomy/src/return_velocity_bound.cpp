#include "kestrel/autonomy/return_velocity_bound.hpp"

namespace kestrel::autonomy {

bool ReturnVelocityBound::recent(TimeUs now, Duration scan_period, const LaserScan& scan) {
  return scan.beam_count > 0 && now - scan.stamp <= scan_period * kScanMaxAgePeriods && scan.stamp - now <= scan_period;
}

Status ReturnVelocityBound::apply(TimeUs now, Duration scan_period, const LaserScan& scan, bool& scan_fresh,
                                  const NavState& nav, exploration::Explorer& explorer, GuidanceSetpoint& setpoint) {
  if (setpoint.mode != GuidanceSetpoint::Mode::kVelocity) return Status::kUnsupported;
  if (!recent(now, scan_period, scan)) {
    setpoint.velocity_mps.x() = 0.0f;
    setpoint.velocity_mps.y() = 0.0f;
    return Status::kRejected;
  }
  if (scan_fresh) {
    scan_fresh = false;
    const Status s = explorer.bound_velocity(nav, scan, setpoint);
    velocity_ = setpoint.velocity_mps.head<2>();
    return s;
  }
  setpoint.velocity_mps.head<2>() = velocity_;
  return Status::kOk;
}

}  // namespace kestrel::autonomy
