#pragma once
// A device's own clock mapped onto the board's. A device that stamps what it sends (a Hokuyo's
// millisecond counter, the far end of the HIL link) counts from its own zero; every module
// compares stamps with the board's clock (a scan's age, a measurement from the future), so a
// driver hands on stamp + offset. The offset is the smallest (arrival - device stamp) seen:
// the arrival with the least transfer delay, so stamps keep the device's own spacing instead
// of the link's jitter. It only falls, as quicker frames come, by that jitter: well below a
// sample period once the first frames are in. A driver that queues frames maps them as they
// are read out, after a whole backlog has been observed: mapped as each arrived, a backlog's
// stamps would close up onto its last (all arrived at once, each the quickest yet).
#include <cstdint>

#include "kestrel/core/time.hpp"

namespace kestrel {

class DeviceClock {
 public:
  // A frame stamped `stamp` on the device's clock arrived at `arrival` on the board's.
  void observe(TimeUs stamp, TimeUs arrival) {
    const int64_t offset = arrival.us - stamp.us;
    if (!known_ || offset < offset_us_) offset_us_ = offset;
    known_ = true;
  }
  // The board's time of a device stamp, by the offset observed so far (unchanged before any).
  TimeUs to_board(TimeUs stamp) const { return TimeUs{stamp.us + offset_us_}; }
  bool known() const { return known_; }
  int64_t offset_us() const { return offset_us_; }

 private:
  bool known_ = false;
  int64_t offset_us_ = 0;
};

}  // namespace kestrel
