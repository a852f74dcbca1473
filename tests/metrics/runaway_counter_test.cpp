// RunawayCounter: how often the estimate's error rises by more than 1 m within 10 s.
#include "kestrel/metrics/runaway_counter.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace kestrel::metrics {
namespace {

TEST(RunawayCounter, ASteadyOrSlowlyGrowingErrorIsNoRunaway) {
  RunawayCounter steady, slow;
  for (int i = 0; i <= 1000; ++i) {
    const double t = 0.1 * i;
    EXPECT_EQ(steady.add(t, 0.3), Status::kOk);
    EXPECT_EQ(slow.add(t, 0.05 * t), Status::kOk);  // 5 m in all, 0.5 m per window
  }
  EXPECT_EQ(steady.runaways(), 0u);
  EXPECT_EQ(slow.runaways(), 0u);
}

TEST(RunawayCounter, AJumpCountsOnceAndFastGrowthOncePerWindow) {
  RunawayCounter jump;
  for (int i = 0; i <= 300; ++i) {
    const double t = 0.1 * i;
    (void)jump.add(t, t < 10.0 ? 0.2 : 1.7);  // 1.5 m at t = 10 s, then held
  }
  EXPECT_EQ(jump.runaways(), 1u);

  RunawayCounter fast;  // 0.2 m/s for 30 s: more than 1 m within 10 s after 5 s
  for (int i = 0; i <= 300; ++i) (void)fast.add(0.1 * i, 0.02 * i);
  EXPECT_EQ(fast.runaways(), 3u);  // at about 5, 15 and 25 s

  RunawayCounter back;  // the error falls back and rises again: a second runaway
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.1 * i;
    (void)back.add(t, (t >= 5.0 && t < 20.0) || t >= 35.0 ? 2.0 : 0.1);
  }
  EXPECT_EQ(back.runaways(), 2u);
}

TEST(RunawayCounter, ABadWindowOrRiseCountsNothingAndNeverBreaks) {
  RunawayCounter negative(1.0, -5.0), nan_window(1.0, std::nan("")), nan_rise(std::nan(""), 10.0);
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.1 * i, e = 0.5 * t;  // 5 m in 10 s
    EXPECT_EQ(negative.add(t, e), Status::kOk);
    EXPECT_EQ(nan_window.add(t, e), Status::kOk);
    EXPECT_EQ(nan_rise.add(t, e), Status::kOk);
  }
  EXPECT_EQ(negative.runaways(), 0u);
  EXPECT_EQ(nan_window.runaways(), 0u);
  EXPECT_EQ(nan_rise.runaways(), 0u);
}

TEST(RunawayCounter, BadSamplesAreRefusedAndChangeNothing) {
  RunawayCounter c;
  EXPECT_EQ(c.add(0.0, 0.0), Status::kOk);
  EXPECT_EQ(c.add(1.0, std::nan("")), Status::kNotFinite);
  EXPECT_EQ(c.add(std::nan(""), 5.0), Status::kNotFinite);
  EXPECT_EQ(c.add(2.0, 0.1), Status::kOk);
  EXPECT_EQ(c.add(1.5, 9.0), Status::kInvalidArgument);  // earlier than the last sample
  EXPECT_EQ(c.runaways(), 0u);
  EXPECT_EQ(c.add(3.0, 1.2), Status::kOk);
  EXPECT_EQ(c.runaways(), 1u);
}

}  // namespace
}  // namespace kestrel::metrics
