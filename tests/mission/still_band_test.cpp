#include "kestrel/mission/still_band.hpp"

#include <gtest/gtest.h>

namespace kestrel::mission {
namespace {

TEST(StillBand, AnEmptyBandTakesAnyValue) {
  const StillBand band(0.02f);
  EXPECT_TRUE(band.takes(-5.0f));
  EXPECT_TRUE(band.takes(100.0f));
}

TEST(StillBand, TakesWhatKeepsTheRunWithinItsWidthOnEitherSide) {
  StillBand band(0.02f);
  band.add(1.000f);
  band.add(1.015f);
  EXPECT_TRUE(band.takes(0.996f));   // spread 0.019
  EXPECT_FALSE(band.takes(0.990f));  // spread 0.025: under the lowest by more than the room left
  EXPECT_TRUE(band.takes(1.019f));
  EXPECT_FALSE(band.takes(1.025f));
}

TEST(StillBand, AValueThatCreepsOutIsRefusedAgainstTheWholeRunNotTheLastValue) {
  StillBand band(0.02f);
  for (float v = 1.0f; v < 1.0195f; v += 0.005f) {
    ASSERT_TRUE(band.takes(v));
    band.add(v);
  }
  EXPECT_FALSE(band.takes(1.025f));  // 0.01 over the last value, 0.025 over the first
}

TEST(StillBand, ClearStartsANewRun) {
  StillBand band(0.02f);
  band.add(1.0f);
  ASSERT_FALSE(band.takes(2.0f));
  band.clear();
  EXPECT_TRUE(band.takes(2.0f));
  band.add(2.0f);
  EXPECT_FALSE(band.takes(1.0f));
}

}  // namespace
}  // namespace kestrel::mission
