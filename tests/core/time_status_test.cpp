#include <gtest/gtest.h>

#include <cstring>

#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel {
namespace {

TEST(Time, ArithmeticAndConversion) {
  const TimeUs t = TimeUs::from_s(1.5);
  EXPECT_EQ(t.us, 1'500'000);
  EXPECT_EQ((t + Duration::from_ms(20)).us, 1'520'000);
  EXPECT_EQ((t - TimeUs::from_us(500'000)).us, 1'000'000);
  EXPECT_EQ(Duration::from_s(-0.0000015).us, -2);  // rounds to nearest, away from zero on ties
  EXPECT_LT(TimeUs::from_us(1), TimeUs::from_us(2));
  EXPECT_DOUBLE_EQ(Duration::from_us(250).seconds(), 250e-6);
}

TEST(Time, ManualTimeSourceOnlyMovesWhenTold) {
  ManualTimeSource clock(TimeUs::from_us(10));
  EXPECT_EQ(clock.now().us, 10);
  clock.advance(Duration::from_us(5));
  EXPECT_EQ(clock.now().us, 15);
  clock.set(TimeUs::from_us(3));
  EXPECT_EQ(clock.now().us, 3);
}

Result<int> parse_digit(char c) {
  if (c < '0' || c > '9') return Status::kMalformed;
  return c - '0';
}

TEST(Status, ResultCarriesValueOrReason) {
  const Result<int> good = parse_digit('7');
  ASSERT_TRUE(good.ok());
  EXPECT_EQ(good.value(), 7);
  const Result<int> bad = parse_digit('x');
  EXPECT_FALSE(bad.ok());
  EXPECT_EQ(bad.status(), Status::kMalformed);
  EXPECT_EQ(bad.value_or(-1), -1);
  EXPECT_STREQ(to_string(Status::kTimeJump), "time jump");
  for (int s = 0; s <= static_cast<int>(Status::kRejected); ++s)
    EXPECT_STRNE(to_string(static_cast<Status>(s)), "unknown");
}

}  // namespace
}  // namespace kestrel
