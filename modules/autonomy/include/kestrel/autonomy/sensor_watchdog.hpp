#pragma once
// Whether the devices the estimate stands on are still talking: what AutonomyStack tells the
// mission about the estimate, on its own so that it can be tested without the loop.
//
// Why: the mission's failsafe lands the vehicle when the estimate has been invalid for
// estimate_timeout_s, but the filter's state stays valid and finite once initialised, whatever
// its devices do. An IMU that falls silent freezes the estimate (and the filter then refuses
// every scan pose as from the future); a laser that falls silent leaves the position to the
// IMU alone. Neither ever made the estimate invalid, so neither ever landed the vehicle.
//
// A device counts as alive when the stack took something usable from it: an IMU sample the
// filter accepted, a scan that was well formed and in time order (matched, lost, or with too
// few returns: nothing within the laser's reach in a large room is the world's silence, not
// the device's, and flying on the IMU there is what the stack always did). A device that
// delivers only garbage is as silent as one that delivers nothing.
//
// Silence is judged where the device is read: the time from the last usable sample to the
// device's own task's latest poll of it. A loop that is merely late (a long match on a slow
// board, the map rebuild taking the only core) polls late and finds the samples waiting, so
// it does not make a healthy device look silent; a device is silent when its task polled and
// found nothing usable for the timeout. Times are the loop's (the tasks' releases), not the
// samples' stamps: a late but steady laser (paper 000's delayed scans) is alive, and a link
// whose stamps are on another clock does not look silent.
//
// The estimate is stale for the mission when either device is silent. With the IMU silent the
// estimate is frozen, so the controller stops steering on it at once (AutonomyStack::
// control_task: level, and in the failsafe a gentle blind descent); with only the laser
// silent the IMU still carries the velocity the descent needs.
//
// No heap, no exceptions.
#include <cmath>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel::autonomy {

struct SensorTimeouts {
  float imu_s = 0.1f;   // 20 samples at 200 Hz
  float scan_s = 0.5f;  // 5 URG-04LX scans, 20 UTM-30LX scans
  // Positive and at most a minute: beyond that nothing is being watched.
  bool valid() const {
    return std::isfinite(imu_s) && imu_s > 0 && imu_s <= 60 && std::isfinite(scan_s) && scan_s > 0 && scan_s <= 60;
  }
};

// How often each device fell silent (went from alive to silent), for metrics and telemetry.
struct SilenceCounters {
  uint32_t imu = 0;
  uint32_t scan = 0;
};

class SensorWatchdog {
 public:
  void configure(const SensorTimeouts& t) {
    imu_timeout_ = Duration::from_s(t.imu_s);
    scan_timeout_ = Duration::from_s(t.scan_s);
  }
  // Each device's task says when it polled, and when it took a usable sample (same time).
  void imu_polled(TimeUs now) { imu_.polled(now); }
  void imu_alive(TimeUs now) { imu_.heard(now); }
  void scan_polled(TimeUs now) { scan_.polled(now); }
  void scan_alive(TimeUs now) { scan_.heard(now); }

  bool imu_fresh() const { return imu_.fresh(imu_timeout_); }
  bool scan_fresh() const { return scan_.fresh(scan_timeout_); }

  // The estimate as the mission may use it: invalid while either device is silent. Also
  // counts the falls into silence (once per silence, however often it is asked).
  NavState for_mission(const NavState& nav) {
    const bool imu = imu_fresh();
    const bool scan = scan_fresh();
    counters_.imu += imu_.fell_silent(imu);
    counters_.scan += scan_.fell_silent(scan);
    NavState out = nav;
    out.valid = nav.valid && imu && scan;
    return out;
  }
  const SilenceCounters& counters() const { return counters_; }

 private:
  struct Device {
    TimeUs last_heard, last_polled;
    bool heard_once = false;
    bool was_fresh = false;
    void polled(TimeUs now) {
      // A clock that steps back (a reset) would leave the last sample in the future, and the
      // device fresh until the clock caught up: count it as heard at the step instead, so a
      // silence after the step still shows within the timeout.
      if (heard_once && now < last_heard) last_heard = now;
      last_polled = now;
    }
    void heard(TimeUs now) {
      polled(now);
      last_heard = now;
      heard_once = true;
    }
    bool fresh(Duration timeout) const { return heard_once && last_polled - last_heard <= timeout; }
    bool fell_silent(bool fresh_now) {
      const bool fell = was_fresh && !fresh_now;
      was_fresh = fresh_now;
      return fell;
    }
  };
  Duration imu_timeout_ = Duration::from_ms(100);
  Duration scan_timeout_ = Duration::from_ms(500);
  Device imu_, scan_;
  SilenceCounters counters_;
};

}  // namespace kestrel::autonomy
