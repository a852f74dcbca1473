#include <gtest/gtest.h>

#include "kestrel/platform/linux/linux_clock.hpp"

namespace kestrel::platform {
namespace {

TEST(LinuxClock, IsMonotonicAndSleepsUntilADeadline) {
  LinuxClock clock;
  const TimeUs a = clock.now();
  const TimeUs deadline = a + Duration::from_ms(20);
  ASSERT_EQ(clock.sleep_until(deadline), Status::kOk);
  const TimeUs b = clock.now();
  EXPECT_GE(b, deadline);
  // A deadline in the past returns at once.
  ASSERT_EQ(clock.sleep_until(a), Status::kOk);
  EXPECT_GE(clock.now(), b);
}

}  // namespace
}  // namespace kestrel::platform
