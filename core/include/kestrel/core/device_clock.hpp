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
// kDriftAllowancePpm (25 minutes for 300 ms), every scan looking that much older meanwhile. A
// step keeps one delay: so a run of kReseedFrames frames all later than the offset by more than
// kStepUs, whose least offsets in its first and second halves agree within kStepFlatUs, is a
// stepped clock too, and the offset is taken afresh as the run's least. A stall of fewer frames
// leaves the offset alone, and so does jitter below kStepUs, however long. A delay that keeps
// changing over the run is no step and its frames keep their true age: a draining backlog (its
// oldest frame latest), or a queue growing because the board reads slower than the device
// sends, whose scans must look as stale as they are. A device clock slower than the allowance
// covers is followed within about kStepUs, 30 ms at a time.
//  - What is traded: a link whose delay rose by more than kStepUs and stayed for a whole run
//    (a congested network), or rises by less than kStepFlatUs per half run (under 1 % of the
//    time at 40 Hz), is taken for a stepped or slow clock. Until its delay falls again (the
//    first quicker frame takes the offset back down) its stamps are mapped younger by the extra
//    delay than they are, where before they kept their true age.
//
// A driver that queues frames maps them as they are read out, after a whole backlog has been
// observed: mapped as each arrived, a backlog's stamps would close up onto its last (all
// arrived at once, each the quickest yet). Each stream goes through its own StreamStamps
// (core/stream_stamps.hpp): mapped as read, a sample read after the offset fell would hand on a
// time before the one read just before it.
#include <algorithm>
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
  // A stepped clock's frames keep one delay but for the link's jitter, whose least value over
  // half a run (20 frames) hardly moves; a draining backlog moves 25 ms a frame.
  static constexpr int64_t kStepFlatUs = 5'000;

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
        last_arrival_us_ = arrival.us;  // a refused frame's interval must not leak twice
      }
      const bool ahead = offset < offset_us_ - kMaxJumpUs;
      far_run_ = ahead || offset > offset_us_ + kMaxJumpUs ? far_run_ + 1 : 0;
      if (far_run_ >= kReseedFrames) {
        known_ = false;  // the device's clock restarted or stepped: start again from this frame
        far_run_ = 0;
        late_run_ = 0;
      } else if (ahead) {
        return false;  // a lone stamp from far ahead
      } else if (ends_a_step(offset)) {
        offset_us_ = std::min(half_min_[0], half_min_[1]);
        far_run_ = 0;
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
  int64_t half_min_[2] = {0, 0};  // the least offset in each half of that run

  // Counts the late run; true when it completes with one delay (a stepped clock).
  bool ends_a_step(int64_t offset) {
    if (!(offset > offset_us_ + kStepUs)) {
      late_run_ = 0;
      return false;
    }
    const int half = late_run_ < kReseedFrames / 2 ? 0 : 1;
    const bool first_of_half = late_run_ == 0 || late_run_ == kReseedFrames / 2;
    half_min_[half] = first_of_half ? offset : std::min(half_min_[half], offset);
    if (++late_run_ < kReseedFrames) return false;
    late_run_ = 0;
    const int64_t moved = half_min_[1] - half_min_[0];
    return moved <= kStepFlatUs && moved >= -kStepFlatUs;
  }
};

}  // namespace kestrel
