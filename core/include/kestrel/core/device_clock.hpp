#pragma once
// A device's own clock mapped onto the board's. A device that stamps what it sends (a Hokuyo's
// millisecond counter, the far end of the HIL link) counts from its own zero; every module
// compares stamps with the board's clock (a scan's age, a measurement from the future), so a
// driver hands on stamp + offset. The offset is the smallest (arrival - device stamp) seen:
// the arrival with the least transfer delay, so stamps keep the device's own spacing instead
// of the link's jitter. It falls, as quicker frames come, by that jitter: well below a sample
// period once the first frames are in.
//
// Two clocks also run at slightly different rates (crystals: tens of ppm). A device clock
// slower than the board's makes the true offset grow, which a plain minimum never follows: at
// 50 ppm its stamps would fall 90 ms behind in a 30-minute flight, and the UTM-30LX's scans
// (older than 75 ms: stale, ReturnVelocityBound) would stop the flight home. So the kept
// offset rises by up to kDriftAllowancePpm of the board time between frames before the
// minimum is taken; the quickest frames of each second pull it back down.
//
// A driver that queues frames maps them as they are read out, after a whole backlog has been
// observed: mapped as each arrived, a backlog's stamps would close up onto its last (all
// arrived at once, each the quickest yet).
#include <cstdint>

#include "kestrel/core/time.hpp"

namespace kestrel {

class DeviceClock {
 public:
  static constexpr int64_t kDriftAllowancePpm = 200;

  // A frame stamped `stamp` on the device's clock arrived at `arrival` on the board's.
  void observe(TimeUs stamp, TimeUs arrival) {
    const int64_t offset = arrival.us - stamp.us;
    if (known_ && arrival.us > last_arrival_us_) {
      // Leaked in whole microseconds, the remainder carried, so slow frame rates leak too.
      leak_ppm_us_ += (arrival.us - last_arrival_us_) * kDriftAllowancePpm;
      offset_us_ += leak_ppm_us_ / 1'000'000;
      leak_ppm_us_ %= 1'000'000;
    }
    if (!known_ || offset < offset_us_) offset_us_ = offset;
    if (!known_ || arrival.us > last_arrival_us_) last_arrival_us_ = arrival.us;
    known_ = true;
  }
  // The board's time of a device stamp, by the offset observed so far (unchanged before any).
  TimeUs to_board(TimeUs stamp) const { return TimeUs{stamp.us + offset_us_}; }
  bool known() const { return known_; }
  int64_t offset_us() const { return offset_us_; }

 private:
  bool known_ = false;
  int64_t offset_us_ = 0;
  int64_t last_arrival_us_ = 0;
  int64_t leak_ppm_us_ = 0;  // leak not yet a whole microsecond, in ppm x us
};

}  // namespace kestrel
