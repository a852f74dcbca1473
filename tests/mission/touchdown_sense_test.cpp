#include "kestrel/mission/touchdown_sense.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace kestrel::mission {
namespace {

constexpr float kLandedM = 0.12f;
constexpr float kMaxAgeS = 0.5f;

TimeUs at(double s) { return TimeUs{} + Duration::from_s(s); }

AltimeterSample reading(double stamp_s, float height_m) { return {at(stamp_s), height_m, 1e-4f}; }

struct Sense {
  TouchdownSense t;
  void read(double now_s, float height_m) {
    const AltimeterSample r = reading(now_s, height_m);
    t.observe(at(now_s), &r, kLandedM, kMaxAgeS);
  }
  void silent(double now_s) { t.observe(at(now_s), nullptr, kLandedM, kMaxAgeS); }
};

TEST(TouchdownSense, WithoutAReadingItHasNoVerdict) {
  Sense s;
  s.silent(1.0);
  EXPECT_FALSE(s.t.on_ground().has_value());
  EXPECT_FALSE(s.t.floor_under(1.0f).has_value());
}

TEST(TouchdownSense, ARecentReadingOverTheLandedHeightIsAirborneAndAStaleOneIsNothing) {
  Sense s;
  s.read(1.0, 0.5f);
  EXPECT_EQ(s.t.on_ground(), std::optional<bool>(false));
  s.silent(1.0 + kMaxAgeS);
  EXPECT_EQ(s.t.on_ground(), std::optional<bool>(false));
  s.silent(1.01 + kMaxAgeS);
  EXPECT_FALSE(s.t.on_ground().has_value());
  EXPECT_FALSE(s.t.floor_under(0.5f).has_value());
}

// Low readings are touchdown once they have held still (within kStillM) for kStillS: one alone
// is not, nor are low readings still descending (0.3 m/s: 0.03 m in 0.1 s, at 40 Hz).
TEST(TouchdownSense, LowReadingsHeldStillAreTouchdownOneOrMovingOnesAreNot) {
  Sense s;
  s.read(1.0, 0.05f);
  EXPECT_FALSE(s.t.on_ground().has_value());
  s.read(1.1, 0.3f);  // over it again: the run starts over
  EXPECT_EQ(s.t.on_ground(), std::optional<bool>(false));
  for (int i = 0; i < 4; ++i) {  // descending at 0.3 m/s, 25 ms apart
    s.read(1.2 + 0.025 * i, 0.11f - 0.0075f * static_cast<float>(i));
    EXPECT_FALSE(s.t.on_ground().has_value()) << i;
  }
  s.read(1.3, 0.08f);
  EXPECT_FALSE(s.t.on_ground().has_value());  // 0.03 m over the last 0.1 s: moving
  s.read(1.35, 0.075f);
  EXPECT_FALSE(s.t.on_ground().has_value());  // within 0.02 m since 1.275 s: still, but for 0.075 s
  s.read(1.4, 0.079f);
  EXPECT_EQ(s.t.on_ground(), std::optional<bool>(true));
}

// Readings that stop after reading the vehicle down (under the laser's minimum range) leave it
// on the ground, however long the silence; a reading over the landed height ends it.
TEST(TouchdownSense, SilenceAfterTouchdownStaysOnTheGround) {
  Sense s;
  s.read(1.0, 0.006f);
  s.read(1.1, -0.001f);  // the floor's noise reads a little under it
  s.silent(60.0);
  EXPECT_EQ(s.t.on_ground(), std::optional<bool>(true));
  s.read(60.1, 0.5f);
  EXPECT_EQ(s.t.on_ground(), std::optional<bool>(false));
}

TEST(TouchdownSense, TheSameReadingGivenAgainCountsOnce) {
  Sense s;
  const AltimeterSample r = reading(1.0, 0.05f);
  for (int i = 0; i < 20; ++i) s.t.observe(at(1.0 + 0.01 * i), &r, kLandedM, kMaxAgeS);
  EXPECT_FALSE(s.t.on_ground().has_value());
  const AltimeterSample older = reading(0.8, 0.05f);
  s.t.observe(at(1.3), &older, kLandedM, kMaxAgeS);
  EXPECT_FALSE(s.t.on_ground().has_value());
}

TEST(TouchdownSense, ReadingsOutOfReasonAreIgnored) {
  Sense s;
  for (const float bad : {std::nanf(""), std::numeric_limits<float>::infinity(), TouchdownSense::kMinHeightM - 0.1f,
                          TouchdownSense::kMaxHeightM + 1.0f}) {
    s.read(1.0, bad);
    EXPECT_FALSE(s.t.on_ground().has_value()) << bad;
  }
  s.read(1.1, 0.05f);
  s.read(1.15, -1.0f);  // ignored: it neither counts nor breaks the run
  s.read(1.2, 0.05f);
  EXPECT_EQ(s.t.on_ground(), std::optional<bool>(true));
}

TEST(TouchdownSense, TheFloorUnderIsTheEstimatedHeightLessTheReading) {
  Sense s;
  s.read(1.0, 0.8f);
  ASSERT_TRUE(s.t.floor_under(0.05f).has_value());
  EXPECT_NEAR(*s.t.floor_under(0.05f), -0.75f, 1e-6f);
  EXPECT_FALSE(s.t.floor_under(std::nanf("")).has_value());
}

TEST(TouchdownSense, ResetForgetsEverything) {
  Sense s;
  s.read(1.0, 0.05f);
  s.read(1.1, 0.05f);
  ASSERT_EQ(s.t.on_ground(), std::optional<bool>(true));
  s.t.reset();
  EXPECT_FALSE(s.t.on_ground().has_value());
  s.read(1.2, 0.05f);
  EXPECT_FALSE(s.t.on_ground().has_value());
}

}  // namespace
}  // namespace kestrel::mission
