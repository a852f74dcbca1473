#pragma once
// One stream's device stamps handed on in the board's time and in the device's own order.
// A DeviceClock's offset falls as quicker frames come (and when it is taken afresh after the
// device's clock jumped ahead); a sample read out after a fall of more than its period maps
// before the one read just before it, though the device stamped it later. The stack takes each
// stream's stamps as its time: the filter dropped such IMU samples as time running backwards
// (hil_hover with the CPU short: 13 to 27 of 3000 in a flight, and a test that rightly failed
// on them).
// So a sample the device stamped after the last one handed on is handed on after that one
// too, by at least 1 us: the fall is taken up by the next samples (they close up until the
// mapping passes the last stamp handed on) instead of reaching the stack as a step back. A
// scan so handed on is as good as simultaneous with the one before: the matcher predicts no
// motion over it, where before it refused the scan as from the past.
// Not without bound: a fall beyond DeviceClock::kMaxJumpUs is no link's jitter but a clock
// stepped (the board's, or the device's taken afresh), and holding the stream at one time until
// the device's stamps covered it would freeze every estimate that runs on it; such a stamp is
// handed on as mapped, for the stack's own checks. So is a stamp the device itself put at or
// before its previous one: that is the device's fault, for the stack to see and count.
#include <cstdint>
#include <limits>

#include "kestrel/core/device_clock.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel {

class StreamStamps {
 public:
  TimeUs to_board(const DeviceClock& clock, TimeUs device_stamp) {
    TimeUs board = clock.to_board(device_stamp);
    const bool in_order = have_ && device_stamp > last_device_;
    // How far back, in unsigned arithmetic: exact for any board <= last_board_, never overflowing.
    const bool held_back = in_order && !(board > last_board_) &&
                           static_cast<uint64_t>(last_board_.us) - static_cast<uint64_t>(board.us) <=
                               static_cast<uint64_t>(DeviceClock::kMaxJumpUs);
    if (held_back && last_board_.us < std::numeric_limits<int64_t>::max()) board = last_board_ + Duration{1};
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
