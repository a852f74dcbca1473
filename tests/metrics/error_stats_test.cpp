#include "kestrel/metrics/error_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace kestrel::metrics {
namespace {

TEST(ErrorStats, KnownAnswers) {
  ErrorAccumulator acc;
  EXPECT_EQ(acc.stats().count, 0u);
  EXPECT_EQ(acc.stats().mean, 0.0);
  for (double e : {1.0, 2.0, 3.0, 4.0}) acc.add(e);
  const ErrorStats s = acc.stats();
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));   // population
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));   // (1 + 4 + 9 + 16) / 4
  EXPECT_DOUBLE_EQ(s.max, 4.0);
}

TEST(ErrorStats, StableForLargeOffsets) {
  ErrorAccumulator acc;
  for (int k = 0; k < 100000; ++k) acc.add(1e6 + (k % 2 == 0 ? 0.1 : 0.3));
  EXPECT_NEAR(acc.stats().std, 0.1, 1e-6);
  EXPECT_NEAR(acc.stats().mean, 1e6 + 0.2, 1e-6);
}

}  // namespace
}  // namespace kestrel::metrics
