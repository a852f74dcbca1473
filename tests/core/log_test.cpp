#include "kestrel/core/log.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "kestrel/core/alloc_guard.hpp"

namespace kestrel {
namespace {

TEST(Logger, RecordsFormattedTextWithTime) {
  static Logger log;
  ManualTimeSource clock(TimeUs::from_us(1234));
  log.set_time_source(&clock);
  log.log(LogLevel::kWarn, "scan %d dropped: %s", 17, "all beams no-return");
  LogRecord r;
  ASSERT_TRUE(log.pop(r));
  EXPECT_EQ(r.stamp.us, 1234);
  EXPECT_EQ(r.level, LogLevel::kWarn);
  EXPECT_STREQ(r.text, "scan 17 dropped: all beams no-return");
  EXPECT_FALSE(log.pop(r));
}

TEST(Logger, OverwritesOldestWhenFullAndCountsDrops) {
  static Logger log;
  for (int i = 0; i < static_cast<int>(Logger::kCapacity) + 10; ++i) log.log(LogLevel::kInfo, "m%d", i);
  EXPECT_EQ(log.size(), Logger::kCapacity);
  EXPECT_EQ(log.dropped(), 10u);
  LogRecord r;
  ASSERT_TRUE(log.pop(r));
  EXPECT_STREQ(r.text, "m10");
}

TEST(Logger, TruncatesLongMessagesAndFiltersLevels) {
  static Logger log;
  log.set_min_level(LogLevel::kWarn);
  log.log(LogLevel::kInfo, "hidden");
  EXPECT_EQ(log.size(), 0u);
  char big[400];
  std::memset(big, 'a', sizeof(big) - 1);
  big[sizeof(big) - 1] = '\0';
  log.log(LogLevel::kError, "%s", big);
  LogRecord r;
  ASSERT_TRUE(log.pop(r));
  EXPECT_EQ(std::strlen(r.text), sizeof(r.text) - 1);
}

TEST(Logger, LoggingDoesNotAllocate) {
  static Logger log;
  log.log(LogLevel::kInfo, "warm-up %f", 1.0);
  alloc_guard::Scope guard;
  for (int i = 0; i < 1000; ++i) log.log(LogLevel::kInfo, "value %d %f", i, 0.5 * i);
  EXPECT_EQ(guard.allocations(), 0u);
}

}  // namespace
}  // namespace kestrel
