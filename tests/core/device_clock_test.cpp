// A device's stamps on the board's clock (core/device_clock.hpp): the quickest arrival sets
// the offset, jitter does not move the stamps, a device clock running slow is followed, and so
// is one stepped back, while late frames of a stall, a backlog or a growing queue keep their age.
#include "kestrel/core/device_clock.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>

namespace kestrel {
namespace {

TEST(DeviceClock, TheQuickestArrivalSetsTheOffset) {
  DeviceClock c;
  EXPECT_FALSE(c.known());
  const TimeUs board0 = TimeUs::from_s(3600);
  // Device stamps every 5 ms; delays 3, 1, 4, 1 ms.
  const int64_t delay_us[] = {3000, 1000, 4000, 1000};
  for (int i = 0; i < 4; ++i) {
    const TimeUs stamp = TimeUs::from_us(5000 * i);
    c.observe(stamp, board0 + Duration::from_us(5000 * i + delay_us[i]));
  }
  EXPECT_TRUE(c.known());
  // The offset is the 1 ms arrival's (plus at most the drift allowance's leak over 20 ms).
  EXPECT_NEAR(static_cast<double>(c.offset_us()), static_cast<double>(board0.us + 1000), 5.0);
  EXPECT_NEAR(static_cast<double>(c.to_board(TimeUs::from_us(20'000)).us), static_cast<double>(board0.us + 21'000),
              5.0);
}

// A device crystal 50 ppm slow against the board: over a 30-minute flight of 40 Hz frames with
// 1-3 ms of jitter, a mapped stamp stays within a few milliseconds of when it truly left the
// device, never hours or a whole scan period behind, and never ahead of its arrival.
TEST(DeviceClock, FollowsADeviceClockRunningSlow) {
  for (const double ppm : {-50.0, 0.0, 50.0, 150.0}) {
    DeviceClock c;
    const int64_t board0 = 10'000'000'000;  // board up for almost three hours
    double worst_lag_us = 0;
    for (int64_t i = 0; i < 30 * 60 * 40; ++i) {
      const int64_t board_sent = board0 + i * 25'000;
      const int64_t stamp = static_cast<int64_t>(static_cast<double>(i * 25'000) * (1.0 - ppm * 1e-6));
      const int64_t delay = 1000 + (i * 7919 % 2000);  // 1-3 ms
      c.observe(TimeUs::from_us(stamp), TimeUs::from_us(board_sent + delay));
      const int64_t mapped = c.to_board(TimeUs::from_us(stamp)).us;
      ASSERT_LE(mapped, board_sent + delay) << ppm << " ppm, frame " << i;  // never after its arrival
      if (i > 400) worst_lag_us = std::max(worst_lag_us, static_cast<double>(board_sent - mapped));
    }
    // Within the 1 ms least delay and what leaks between quick frames, at any drift up to the
    // allowance; a plain minimum fell 90 ms behind at 50 ppm.
    EXPECT_LT(worst_lag_us, 5000.0) << ppm << " ppm";
    EXPECT_GT(worst_lag_us, -5000.0) << ppm << " ppm";
  }
}

TEST(DeviceClock, ABoardClockThatStandsStillLeaksNothing) {
  DeviceClock c;
  c.observe(TimeUs::from_us(1000), TimeUs::from_s(50));
  c.observe(TimeUs::from_us(2000), TimeUs::from_s(50));
  c.observe(TimeUs::from_us(3000), TimeUs::from_s(50));
  EXPECT_EQ(c.to_board(TimeUs::from_us(3000)), TimeUs::from_s(50));
  EXPECT_EQ(c.to_board(TimeUs::from_us(1000)), TimeUs::from_s(50) - Duration::from_ms(2));
}

// Review: one stamp from hours ahead (a corrupted frame that passed its CRC) moved the offset
// down for good, and every later stamp looked that much older. It is refused; a run of such
// frames is a clock that restarted or stepped, and the offset is taken afresh.
TEST(DeviceClock, ALoneStampFromFarAheadIsRefusedARunOfThemReseeds) {
  DeviceClock c;
  const TimeUs board0 = TimeUs::from_s(100);
  int64_t i = 0;
  auto frame = [&](int64_t stamp_shift_us) {
    const TimeUs arrival = board0 + Duration::from_us(5000 * i + 1000);
    const bool ok = c.observe(TimeUs::from_us(5000 * i + stamp_shift_us), arrival);
    ++i;
    return ok;
  };
  for (int k = 0; k < 10; ++k) ASSERT_TRUE(frame(0));
  const int64_t settled = c.offset_us();
  EXPECT_FALSE(frame(3'600'000'000));  // an hour ahead
  EXPECT_NEAR(static_cast<double>(c.offset_us()), static_cast<double>(settled), 5.0);
  EXPECT_TRUE(frame(-3'000'000));  // three seconds late: a stalled link's frame, kept
  EXPECT_NEAR(static_cast<double>(c.offset_us()), static_cast<double>(settled), 5.0);
  EXPECT_FALSE(c.observe(TimeUs::from_us(INT64_MAX), board0));  // beyond 2^62: refused outright
  EXPECT_FALSE(c.observe(TimeUs::from_us(0), TimeUs::from_us(INT64_MIN)));
  // The peer's clock steps 10 s ahead (a restart onto a clock set elsewhere): its first frames
  // are refused as lone ones were, and after a run of them it is followed again. (A step of
  // less than kMaxJumpUs back: ADeviceClockSteppedBackIsFollowedWithinARun.)
  const int64_t restart = 5000 * i - 10'000'000;
  bool followed = false;
  for (int k = 0; k < DeviceClock::kReseedFrames + 5; ++k) {
    const TimeUs arrival = board0 + Duration::from_us(5000 * i + 1000);
    (void)c.observe(TimeUs::from_us(5000 * i - restart), arrival);
    followed = c.to_board(TimeUs::from_us(5000 * i - restart)) == arrival;
    ++i;
  }
  EXPECT_TRUE(followed);
}

// A device sending a frame every 25 ms (40 Hz) with 1-3 ms of link delay, the board up for an
// hour. frame() sends the next one, `late_us` later than that delay, its stamp shifted by
// `stamp_shift_us` (a device clock stepped), and says how much older its mapped stamp looks
// than a frame of the least delay (1 ms) would: 0 for a right offset, negative for stamps that
// look younger than they are, and never positive when the offset is the quickest frame's.
struct Device40Hz {
  DeviceClock c;
  int64_t i = 0;
  bool accepted = true;
  int64_t frame(int64_t late_us = 0, int64_t stamp_shift_us = 0) {
    const int64_t board_sent = 3'600'000'000 + i * 25'000;
    const int64_t delay = 1000 + (i * 7919 % 2000) + late_us;
    const TimeUs stamp = TimeUs::from_us(i * 25'000 + stamp_shift_us);
    accepted = c.observe(stamp, TimeUs::from_us(board_sent + delay));
    ++i;
    return board_sent + 1000 - c.to_board(stamp).us;
  }
};

// Review: a device clock stepped back by less than kMaxJumpUs was not told from late frames.
// Every frame looked 300 ms late, the offset rose only by the drift allowance (25 minutes to
// follow), and meanwhile every scan looked 300 ms older: stale to the flight home. Now a run of
// kReseedFrames frames that late is a step, and the stamps are right again after it.
TEST(DeviceClock, ADeviceClockSteppedBackIsFollowedWithinARun) {
  Device40Hz d;
  for (int k = 0; k < 200; ++k) d.frame();
  const int64_t step_us = -300'000;  // the device's clock set back 300 ms
  for (int k = 0; k < DeviceClock::kReseedFrames - 1; ++k) {
    // Until the run is complete they are late frames, kept and mapped as they are.
    EXPECT_NEAR(static_cast<double>(d.frame(0, step_us)), 300'000.0, 3000.0) << k;
    EXPECT_TRUE(d.accepted);
  }
  for (int k = 0; k < 400; ++k) {
    const int64_t lag = d.frame(0, step_us);
    EXPECT_TRUE(d.accepted);
    EXPECT_LE(lag, 0) << k;      // the quickest frame's offset, from the run's last frame on
    EXPECT_GT(lag, -3000) << k;  // younger by no more than that frame's own 1-3 ms
  }
}

// A stalled link: fewer frames than a run, all 300 ms late, then on time again; twice, so the
// run starts afresh after an on-time frame. The late frames keep their age (mapped as they
// are) and the offset does not move.
TEST(DeviceClock, AStallShorterThanARunLeavesTheOffset) {
  Device40Hz d;
  for (int k = 0; k < 200; ++k) d.frame();
  const int64_t settled = d.c.offset_us();
  for (int stall = 0; stall < 2; ++stall) {
    for (int k = 0; k < DeviceClock::kReseedFrames - 1; ++k) {
      EXPECT_NEAR(static_cast<double>(d.frame(300'000)), 0.0, 3000.0) << stall << ' ' << k;
      EXPECT_TRUE(d.accepted);
    }
    EXPECT_NEAR(static_cast<double>(d.frame()), 0.0, 3000.0) << stall;
  }
  // Within what the drift allowance leaks over each 1 s stall (200 us) and the jitter.
  EXPECT_NEAR(static_cast<double>(d.c.offset_us()), static_cast<double>(settled), 1000.0);
}

// Frames late by less than kStepUs, however many, are jitter: the offset stays the quickest
// frame's. A delay raised to just under the threshold for ten runs, then delays spread up to
// it, then frames alternately on time and 100 ms late: none of them is a step.
TEST(DeviceClock, JitterBelowTheStepDoesNotReseed) {
  Device40Hz d;
  for (int k = 0; k < 200; ++k) d.frame();
  const int64_t settled = d.c.offset_us();
  const int64_t under = DeviceClock::kStepUs - 5000;  // with the 1-3 ms delay, under kStepUs late
  for (int k = 0; k < 10 * DeviceClock::kReseedFrames; ++k) {
    EXPECT_NEAR(static_cast<double>(d.frame(under)), 0.0, 3000.0) << k;  // mapped as they are
  }
  for (int k = 0; k < 10 * DeviceClock::kReseedFrames; ++k) (void)d.frame(k * 7907 % under);
  for (int k = 0; k < 10 * DeviceClock::kReseedFrames; ++k) (void)d.frame(k % 2 == 0 ? 0 : 100'000);
  // The raised delay's 10 s leaked 2 ms; the quicker frames after it took that back.
  EXPECT_NEAR(static_cast<double>(d.c.offset_us()), static_cast<double>(settled), 1000.0);
  EXPECT_NEAR(static_cast<double>(d.frame()), 0.0, 3000.0);
}

// The trade (device_clock.hpp): a link whose delay rose by more than kStepUs for a whole run is
// taken for a stepped clock. Its stamps are then mapped onto their arrival, 50 ms younger than
// they are, until the delay falls; the first quicker frame takes the offset back down.
TEST(DeviceClock, ALinkWhoseDelayRoseForARunIsTakenForAStepUntilItFalls) {
  Device40Hz d;
  for (int k = 0; k < 200; ++k) d.frame();
  for (int k = 0; k < DeviceClock::kReseedFrames - 1; ++k) {
    EXPECT_NEAR(static_cast<double>(d.frame(50'000)), 0.0, 3000.0) << k;
  }
  for (int k = 0; k < 200; ++k) EXPECT_NEAR(static_cast<double>(d.frame(50'000)), -50'000.0, 3000.0) << k;
  EXPECT_NEAR(static_cast<double>(d.frame()), 0.0, 3000.0);
}

// A backlog arrives at once, its oldest frame latest, its newest (here 3 ms in transit, 2 ms
// more than the least delay) least late. A stall shorter than a run's worth of late frames
// leaves the offset alone. So does a longer one (1.5 s: 61 frames later than kStepUs, 21 of
// them later than kMaxJumpUs, too few for the far run): its delay falls 25 ms a frame, no
// step's one delay. Every frame keeps its age, less only what the drift allowance leaked over
// the stall (100 and 300 us), and the next quicker frame sets the offset.
TEST(DeviceClock, ABacklogIsMappedAfterItIsObserved) {
  for (const int64_t stall_frames : {int64_t{DeviceClock::kReseedFrames / 2}, int64_t{60}}) {
    const bool long_stall = stall_frames > DeviceClock::kReseedFrames;
    DeviceClock c;
    const int64_t board0 = 3'600'000'000;
    int64_t i = 0;
    for (; i < 200; ++i) c.observe(TimeUs::from_us(i * 25'000), TimeUs::from_us(board0 + i * 25'000 + 1000));
    const int64_t first = i;
    const TimeUs drained = TimeUs::from_us(board0 + (first + stall_frames) * 25'000 + 3000);
    for (; i <= first + stall_frames; ++i) EXPECT_TRUE(c.observe(TimeUs::from_us(i * 25'000), drained));
    for (int64_t k = first; k <= first + stall_frames; ++k) {
      const int64_t lag = board0 + k * 25'000 + 1000 - c.to_board(TimeUs::from_us(k * 25'000)).us;
      EXPECT_NEAR(static_cast<double>(lag), long_stall ? -300.0 : -100.0, 50.0) << stall_frames << ' ' << k;
    }
    const TimeUs quick = TimeUs::from_us(board0 + i * 25'000 + 500);  // 0.5 ms of delay
    c.observe(TimeUs::from_us(i * 25'000), quick);
    EXPECT_EQ(c.to_board(TimeUs::from_us(i * 25'000)), quick) << stall_frames;
  }
}

// The board reading slower than the device sends: each frame 1 ms later than the one before
// (4 % of the time at 40 Hz). Its frames are later than kStepUs by the 31st, in runs of
// kReseedFrames, but their delay rises 20 ms over each half run: no step. Every scan keeps its
// true age, so the flight sees them stale; taken for a step, they would look at most one run's
// growth old, however far behind the board fell.
TEST(DeviceClock, AQueueGrowingBehindTheBoardIsNoStep) {
  Device40Hz d;
  for (int k = 0; k < 200; ++k) d.frame();
  for (int64_t k = 1; k <= 400; ++k) {
    const int64_t lag = d.frame(k * 1000);
    EXPECT_TRUE(d.accepted);
    // Mapped as it is, its true age: off only by the allowance's leak (2 ms in 10 s).
    EXPECT_NEAR(static_cast<double>(lag), 0.0, 3000.0) << k;
  }
}

// Review: a refused frame (a stamp from far ahead) leaked the time since the last accepted one
// again, so a burst of them raised the offset by the sum of those times (3.9 ms for 39 at
// 40 Hz, against 0.2 ms of allowance), and it broke a late run, so one corrupted frame during
// a step put the step's detection back by a whole run.
TEST(DeviceClock, ARefusedFrameLeaksOnceAndDoesNotBreakALateRun) {
  Device40Hz d;
  for (int k = 0; k < 200; ++k) d.frame();
  const int64_t settled = d.c.offset_us();
  for (int k = 0; k < DeviceClock::kReseedFrames - 1; ++k) {
    (void)d.frame(0, 5'000'000);  // stamped 5 s ahead: refused
    EXPECT_FALSE(d.accepted);
  }
  EXPECT_LT(d.c.offset_us() - settled, 400);  // 39 x 25 ms x 200 ppm = 195 us
  const int64_t step_us = -300'000;
  for (int k = 0; k < DeviceClock::kReseedFrames / 2; ++k) (void)d.frame(0, step_us);
  (void)d.frame(0, 5'000'000);
  EXPECT_FALSE(d.accepted);
  for (int k = 0; k < DeviceClock::kReseedFrames / 2; ++k) (void)d.frame(0, step_us);
  EXPECT_LE(d.frame(0, step_us), 0);  // followed: the run ended at its 40th late frame
}

// A device clock slower than the drift allowance covers: the leak falls behind, its frames
// look ever later, and a run of them later than kStepUs takes the offset afresh. At 1000 ppm
// slow for 10 minutes its stamps stay within about kStepUs; before, they fell behind by the
// 800 ppm the leak missed, 480 ms by the end, until at 1 s the far run took them afresh.
TEST(DeviceClock, ADeviceClockSlowerThanTheAllowanceIsFollowedWithinAStep) {
  DeviceClock c;
  int64_t worst_lag_us = 0;
  for (int64_t i = 0; i < 10 * 60 * 40; ++i) {
    const int64_t board_sent = 3'600'000'000 + i * 25'000;
    const int64_t stamp = i * 25'000 - i * 25;  // 1000 ppm slow
    const int64_t delay = 1000 + (i * 7919 % 2000);
    c.observe(TimeUs::from_us(stamp), TimeUs::from_us(board_sent + delay));
    worst_lag_us = std::max(worst_lag_us, board_sent + 1000 - c.to_board(TimeUs::from_us(stamp)).us);
  }
  EXPECT_LT(worst_lag_us, DeviceClock::kStepUs + 5000);
}

}  // namespace
}  // namespace kestrel
