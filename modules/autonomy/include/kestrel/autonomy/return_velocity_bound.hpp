#pragma once
// The flight home's velocity bound: what AutonomyStack does to the mission's set-point in
// Phase::kReturn and in the Phase::kLand after it, on its own so that it can be tested without
// the loop, the devices or a simulated flight.
//
// Why: on the way home the trail is in the estimate's frame, which may have drifted since it
// was drawn, so retracing it is collision-free only as far as the estimate is right; home,
// where the vehicle then descends, is such a point too. The
// explorer's approach limiter (Explorer::bound_velocity) bounds the flight against the newest
// scan, in the body frame, matched or not: a run of rejected matches must not leave it looking
// at old walls. It runs once per scan, like the explorer; between scans the bounded velocity
// stands (the limiter has nothing new to say, and re-running it on the same returns is work
// for nothing). Without a recent scan nothing bounds the flight, so the vehicle holds.
//
// Flown through the whole stack: ExploreClosedLoop.LandsHeldOffAWallItTookOffBeside
// (exploration_sim_tests) takes off inside the limiter's stop distance of a wall and must land
// outside it.
//
// No heap, no exceptions: the stored velocity is the only state.
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"
#include "kestrel/exploration/explorer.hpp"
#include <Eigen/Core>

namespace kestrel::autonomy {

class ReturnVelocityBound {
 public:
  // A scan older than this many scan periods no longer bounds the flight.
  static constexpr int64_t kScanMaxAgePeriods = 3;

  // One guidance cycle of the flight home. `setpoint` holds the mission's set-point, which must
  // be kVelocity; only its horizontal velocity is changed. `scan` is the newest scan, matched
  // or not (beam_count 0: none yet), and `scan_fresh` says it has not been used yet.
  //  - The scan is recent when now - scan.stamp <= scan_period * kScanMaxAgePeriods, and it
  //    is not stamped more than one scan_period after now (a clock that leapt: its age is unknown).
  //    Not recent: the horizontal velocity is zeroed (hold), kRejected; nothing else changes
  //    (scan_fresh is left as it is, the stored velocity too).
  //  - Recent and fresh: scan_fresh is cleared, explorer.bound_velocity bounds the set-point
  //    against the scan and the heading of nav, and the result is stored. kOk, or its error
  //    (kInvalidArgument: it zeroed the horizontal velocity, and that zero is stored).
  //  - Recent, not fresh: the stored velocity replaces the horizontal velocity, kOk.
  // A set-point that is not kVelocity is not this class's to bound (the stack never passes
  // one): kUnsupported, and nothing is touched.
  Status apply(TimeUs now, Duration scan_period, const LaserScan& scan, bool& scan_fresh, const NavState& nav,
               exploration::Explorer& explorer, GuidanceSetpoint& setpoint);
  // The rule above for a scan recent enough to steer by (the mission's shortcut home uses it too).
  static bool recent(TimeUs now, Duration scan_period, const LaserScan& scan);

  // The horizontal velocity that stands until the next scan (m/s, navigation frame).
  const Eigen::Vector2f& velocity() const { return velocity_; }

 private:
  Eigen::Vector2f velocity_ = Eigen::Vector2f::Zero();
};

}  // namespace kestrel::autonomy
