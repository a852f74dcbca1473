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
// A stamp is a number off a link: one that would move the offset down by more than
// kMaxJumpUs (a stamp from far ahead: a corrupted frame that passed its CRC, a confused peer)
// is refused, not believed, or every later scan would look that much older. A run of
// kReseedFrames frames all that far off, either way, is the device's clock restarted or
// stepped: the offset is taken afresh from them. Stamps beyond +-2^62 us are refused outright
// (the differences below stay within 64 bits).
//
// A frame later than the offset says is mapped as it is: a stalled link's frame, or an old one
// of a drained backlog, is that old. But a device clock stepped back by less than kMaxJumpUs
// makes every later frame look late by the step, and the leak would follow it only at
// kDriftAllowancePpm (25 minutes for 300 ms), every scan looking that much older meanwhile. So
// a run of kReseedFrames frames all later than the offset by more than kStepUs is a stepped
// clock too, and the offset is taken afresh from the frame that ends the run, as for the far
// run; the quicker frames after it take it down to their least delay again. A stall of fewer
// frames leaves the offset alone, and so does jitter below kStepUs, however long. A device
// clock slower than the allowance covers is followed the same way, within about kStepUs.
//  - What is traded: a link whose delay rose by more than kStepUs for a whole run (a congested
//    network) is taken for a step. Until its delay falls again (the first quicker frame takes
//    the offset back down) its stamps are mapped onto their arrival, younger by the extra delay
//    than they are, where before they kept their true age (and scans that old were refused as
//    stale, rightly).
//  - A backlog arrives at once, its oldest frame latest and its newest least late. One from a
//    stall longer than kStepUs plus kReseedFrames frame periods ends such a run on its way in;
//    its newer frames then take the offset down again, so once the whole backlog is observed
//    (see below) the offset is its newest frame's: its stamps look younger by that frame's own
//    delay (within about a frame period) until the next quicker frame.
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
  static constexpr int64_t kMaxJumpUs = 1'000'000;
  static constexpr int kReseedFrames = 40;
  // Why 30 ms: a whole run of frames held back longer than this is no link's jitter. The loop
  // reads the links every millisecond, an FTDI-style USB serial adapter holds bytes up to 16 ms
  // by default, and the Overo's whole loop budget is 12.5 ms; the Verdex's 50 ms per scan holds
  // back only the frames that arrive during it, a backlog shorter than a run. Nor can it be
  // much larger: a step just under it stays (the leak takes 150 s over 30 ms), and a UTM-30LX
  // scan, most of its 25 ms period old when it is used, is stale at 75 ms.
  static constexpr int64_t kStepUs = 30'000;

  // A frame stamped `stamp` on the device's clock arrived at `arrival` on the board's. False
  // for a stamp refused (see above): the frame's stamp, and so the frame, cannot be trusted.
  bool observe(TimeUs stamp, TimeUs arrival) {
    constexpr int64_t kLimit = int64_t{1} << 62;
    if (!(stamp.us > -kLimit && stamp.us < kLimit && arrival.us > -kLimit && arrival.us < kLimit)) return false;
    const int64_t offset = arrival.us - stamp.us;
    if (known_) {
      if (arrival.us > last_arrival_us_ && arrival.us - last_arrival_us_ < kLimit / kDriftAllowancePpm) {
        // Leaked in whole microseconds, the remainder carried, so slow frame rates leak too.
        leak_ppm_us_ += (arrival.us - last_arrival_us_) * kDriftAllowancePpm;
        offset_us_ += leak_ppm_us_ / 1'000'000;
        leak_ppm_us_ %= 1'000'000;
      }
      const bool far = offset < offset_us_ - kMaxJumpUs || offset > offset_us_ + kMaxJumpUs;
      far_run_ = far ? far_run_ + 1 : 0;
      late_run_ = offset > offset_us_ + kStepUs ? late_run_ + 1 : 0;
      if (far_run_ >= kReseedFrames || late_run_ >= kReseedFrames) {
        known_ = false;  // the device's clock restarted or stepped: start again from this frame
        far_run_ = 0;
        late_run_ = 0;
      } else if (offset < offset_us_ - kMaxJumpUs) {
        return false;  // a lone stamp from far ahead
      }
      // A lone frame far behind is a late one (a stalled link): its stamp is mapped as it is.
    }
    if (!known_ || offset < offset_us_) offset_us_ = offset;
    if (!known_ || arrival.us > last_arrival_us_) last_arrival_us_ = arrival.us;
    known_ = true;
    return true;
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
  int far_run_ = 0;          // frames in a row more than kMaxJumpUs off the offset
  int late_run_ = 0;         // frames in a row later than the offset by more than kStepUs
};

}  // namespace kestrel
