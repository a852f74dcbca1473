#pragma once
// One stream's device stamps handed on in the board's time and in the device's own order.
// A DeviceClock's offset falls as quicker frames come (and is taken afresh after a stepped
// clock); a sample read out after a fall of more than its period maps before the one read
// just before it, though the device stamped it later. The stack takes each stream's stamps as
// its time: the filter dropped such IMU samples as time running backwards (hil_hover with the
// CPU short: 13 to 27 of 3000 in a flight, and a test that rightly failed on them).
// So a sample the device stamped after the last one handed on is handed on after that one
// too, by at least 1 us: the fall is taken up by the next samples (they close up until the
// mapping passes the last stamp handed on) instead of reaching the stack as a step back. A
// stamp the device itself put at or before its previous one is mapped as it is: that is the
// device's fault, for the stack's own checks to see and count.
#include <cstdint>

#include "kestrel/core/device_clock.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel {

class StreamStamps {
 public:
  TimeUs to_board(const DeviceClock& clock, TimeUs device_stamp) {
    TimeUs board = clock.to_board(device_stamp);
    if (have_ && device_stamp > last_device_ && !(board > last_board_) && last_board_.us < INT64_MAX)
      board = last_board_ + Duration{1};
    have_ = true;
    last_device_ = device_stamp;
    last_board_ = board;
    return board;
  }

 private:
  bool have_ = false;
  TimeUs last_device_{};
  TimeUs last_board_{};
};

}  // namespace kestrel
