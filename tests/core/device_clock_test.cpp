// A device's stamps on the board's clock (core/device_clock.hpp): the quickest arrival sets
// the offset, jitter does not move the stamps, and a device clock running slow is followed.
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
  // less than kMaxJumpUs back is not told from late frames: the stamps look that much older.)
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

}  // namespace
}  // namespace kestrel
