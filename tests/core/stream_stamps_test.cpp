// A stream's stamps keep the device's order on the board's clock (core/stream_stamps.hpp),
// though the offset they are mapped by falls between two reads.
#include "kestrel/core/stream_stamps.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>

namespace kestrel {
namespace {

const TimeUs kBoard = TimeUs::from_s(3600);

// GIVEN three samples queued 5 ms apart, whose quickest arrival set the offset 40 ms late,
// WHEN the first is read out, then a frame 34 ms quicker arrives, then the rest are read,
// THEN the later samples are handed on after the first (1 us apart), and the stream is back
// on the clock's mapping as soon as that passes the last stamp handed on.
TEST(StreamStamps, AFallingOffsetDoesNotStepTheStreamBack) {
  DeviceClock clock;
  StreamStamps imu;
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(clock.observe(TimeUs::from_us(5000 * i), kBoard + Duration::from_ms(50)));
  const TimeUs first = imu.to_board(clock, TimeUs::from_us(0));
  EXPECT_EQ(first, kBoard + Duration::from_ms(40));
  ASSERT_TRUE(clock.observe(TimeUs::from_us(45'000), kBoard + Duration::from_ms(51)));
  ASSERT_LT(clock.to_board(TimeUs::from_us(5000)), first);  // what the mapping alone would hand on
  EXPECT_EQ(imu.to_board(clock, TimeUs::from_us(5000)), first + Duration{1});
  EXPECT_EQ(imu.to_board(clock, TimeUs::from_us(10'000)), first + Duration{2});
  EXPECT_EQ(imu.to_board(clock, TimeUs::from_us(45'000)), clock.to_board(TimeUs::from_us(45'000)));
}

// A device that stamps a sample at or before its last one is at fault: its stamp is mapped as
// it is, for the stack's checks to count, and does not move the stream's later stamps.
TEST(StreamStamps, ADevicesOwnStepBackIsHandedOnAsItIs) {
  DeviceClock clock;
  StreamStamps s;
  ASSERT_TRUE(clock.observe(TimeUs::from_us(10'000), kBoard));
  EXPECT_EQ(s.to_board(clock, TimeUs::from_us(10'000)), kBoard);
  EXPECT_EQ(s.to_board(clock, TimeUs::from_us(10'000)), kBoard);
  EXPECT_EQ(s.to_board(clock, TimeUs::from_us(4000)), kBoard - Duration::from_ms(6));
  EXPECT_EQ(s.to_board(clock, TimeUs::from_us(15'000)), kBoard + Duration::from_ms(5));
}

// A fall beyond DeviceClock::kMaxJumpUs is a clock stepped, not jitter: held at the last
// stamp, the stream would stand still for the whole step. The stamp is handed on as mapped.
TEST(StreamStamps, AFallBeyondAClockStepIsHandedOnAsMapped) {
  DeviceClock clock;
  StreamStamps s;
  ASSERT_TRUE(clock.observe(TimeUs::from_us(0), kBoard + Duration::from_s(3.0)));
  EXPECT_EQ(s.to_board(clock, TimeUs::from_us(0)), kBoard + Duration::from_s(3.0));
  // The device's frames now arrive 2 s quicker (its clock was taken afresh): a run of them.
  for (int i = 1; i <= DeviceClock::kReseedFrames; ++i)
    (void)clock.observe(TimeUs::from_us(5000 * i), kBoard + Duration::from_s(1.0) + Duration::from_us(5000 * i));
  ASSERT_LT(clock.offset_us(), (kBoard + Duration::from_s(2.0)).us);
  EXPECT_EQ(s.to_board(clock, TimeUs::from_us(5000)), clock.to_board(TimeUs::from_us(5000)));
  EXPECT_EQ(s.to_board(clock, TimeUs::from_us(10'000)), clock.to_board(TimeUs::from_us(10'000)));
}

// Property: over streams whose offset falls by random amounts between reads, the stamps handed
// on rise strictly while the device's do, and never run ahead of the mapping by more than the
// falls so far (nor lag it at all).
TEST(StreamStamps, HandedOnStampsRiseStrictlyAndStayWithinTheFalls) {
  uint32_t seed = 12345;
  auto next = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return seed >> 8;
  };
  for (int run = 0; run < 50; ++run) {
    DeviceClock clock;
    StreamStamps s;
    int64_t arrival_delay_us = 80'000, falls_us = 0;
    TimeUs last{INT64_MIN};
    for (int k = 0; k < 400; ++k) {
      const TimeUs stamp = TimeUs::from_us(5000 * k);
      if (next() % 8 == 0 && arrival_delay_us > 1000) {
        const int64_t fall = static_cast<int64_t>(next() % 30'000);
        falls_us += std::min(fall, arrival_delay_us - 1000);
        arrival_delay_us -= std::min(fall, arrival_delay_us - 1000);
      }
      ASSERT_TRUE(clock.observe(stamp, kBoard + Duration::from_us(5000 * k + arrival_delay_us)));
      const TimeUs mapped = clock.to_board(stamp);
      const TimeUs handed = s.to_board(clock, stamp);
      ASSERT_GT(handed, last) << run << " " << k;
      ASSERT_GE(handed, mapped);
      ASSERT_LE((handed - mapped).us, falls_us + k) << run << " " << k;
      last = handed;
    }
  }
}

}  // namespace
}  // namespace kestrel
