#include "kestrel/mission/touchdown_sense.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace kestrel::mission {
namespace {

constexpr float kLandedM = 0.12f;
constexpr float kMaxAgeS = 0.5f;
const std::optional<bool> kDown(true);
const std::optional<bool> kNotDown(false);

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
  EXPECT_FALSE(s.t.floor_under(1.0f, 0.0f).has_value());
}

TEST(TouchdownSense, ARecentReadingOverTheLandedHeightIsAirborneAndAStaleOneIsNothing) {
  Sense s;
  s.read(1.0, 0.5f);
  EXPECT_EQ(s.t.on_ground(), kNotDown);
  s.silent(1.0 + kMaxAgeS);
  EXPECT_EQ(s.t.on_ground(), kNotDown);
  s.silent(1.01 + kMaxAgeS);
  EXPECT_FALSE(s.t.on_ground().has_value());
  EXPECT_FALSE(s.t.floor_under(0.5f, 0.0f).has_value());
}

// Low readings are touchdown once they have held still (within kStillM) for kStillS: one alone
// is not yet, nor are low readings still descending (0.3 m/s: 0.03 m in 0.1 s, at 40 Hz).
TEST(TouchdownSense, LowReadingsHeldStillAreTouchdownOneOrMovingOnesAreNot) {
  Sense s;
  s.read(1.0, 0.05f);
  EXPECT_EQ(s.t.on_ground(), kNotDown);
  s.read(1.1, 0.3f);  // over it again: the run starts over
  EXPECT_EQ(s.t.on_ground(), kNotDown);
  for (int i = 0; i < 4; ++i) {  // descending at 0.3 m/s, 25 ms apart
    s.read(1.2 + 0.025 * i, 0.11f - 0.0075f * static_cast<float>(i));
    EXPECT_EQ(s.t.on_ground(), kNotDown) << i;
  }
  s.read(1.3, 0.08f);
  EXPECT_EQ(s.t.on_ground(), kNotDown);  // 0.03 m over the last 0.1 s: moving
  s.read(1.35, 0.075f);
  EXPECT_EQ(s.t.on_ground(), kNotDown);  // within 0.02 m since 1.275 s: still, but for 0.075 s
  s.read(1.4, 0.079f);
  EXPECT_EQ(s.t.on_ground(), kDown);
}

// Readings that stop after reading the vehicle down (under the laser's minimum range) leave it
// on the ground, however long the silence; a reading over the landed height ends it.
TEST(TouchdownSense, SilenceAfterTouchdownStaysOnTheGround) {
  Sense s;
  s.read(1.0, 0.006f);
  s.read(1.1, -0.001f);  // the floor's noise reads a little under it
  s.silent(60.0);
  EXPECT_EQ(s.t.on_ground(), kDown);
  s.read(60.1, 0.5f);
  EXPECT_EQ(s.t.on_ground(), kNotDown);
}

// A reading given again (the same stamp) or an older one is not a new reading: an old one over
// the landed height would otherwise say airborne.
TEST(TouchdownSense, TheSameReadingGivenAgainOrAnOlderOneIsIgnored) {
  Sense s;
  s.read(1.0, 0.05f);
  s.read(1.1, 0.05f);
  ASSERT_EQ(s.t.on_ground(), kDown);
  const AltimeterSample older = reading(0.8, 0.5f);
  s.t.observe(at(1.2), &older, kLandedM, kMaxAgeS);
  EXPECT_EQ(s.t.on_ground(), kDown);
  const AltimeterSample again = reading(1.1, 0.5f);
  s.t.observe(at(1.2), &again, kLandedM, kMaxAgeS);
  EXPECT_EQ(s.t.on_ground(), kDown);
}

TEST(TouchdownSense, ReadingsOutOfReasonGiveNoVerdict) {
  Sense s;
  double t = 1.0;
  for (const float bad : {std::nanf(""), std::numeric_limits<float>::infinity(), TouchdownSense::kMinHeightM - 0.1f,
                          TouchdownSense::kMaxHeightM + 1.0f}) {
    s.read(t, bad);
    t += 0.05;
    EXPECT_FALSE(s.t.on_ground().has_value()) << bad;
  }
  s.read(t, 0.5f);
  EXPECT_EQ(s.t.on_ground(), kNotDown);
  s.read(t + 0.05, std::nanf(""));  // not a height: the airborne reading stands
  EXPECT_EQ(s.t.on_ground(), kNotDown);
}

// The floor under an airborne reading: the estimated height carried back to the reading's stamp
// at the estimated vertical speed, less the reading; none from a low or a stale reading.
TEST(TouchdownSense, TheFloorUnderIsTheEstimatedHeightAtTheReadingLessTheReading) {
  Sense s;
  const AltimeterSample r = reading(1.0, 0.8f);
  s.t.observe(at(1.0), &r, kLandedM, kMaxAgeS);
  ASSERT_TRUE(s.t.floor_under(0.05f, 0.0f).has_value());
  EXPECT_NEAR(*s.t.floor_under(0.05f, 0.0f), -0.75f, 1e-6f);
  // 0.1 s later, descending at 0.3 m/s: the estimate then stood 0.03 m higher.
  s.t.observe(at(1.1), nullptr, kLandedM, kMaxAgeS);
  EXPECT_NEAR(*s.t.floor_under(0.02f, -0.3f), -0.75f, 1e-5f);
  EXPECT_FALSE(s.t.floor_under(std::nanf(""), 0.0f).has_value());
  EXPECT_FALSE(s.t.floor_under(0.05f, std::nanf("")).has_value());
  s.t.observe(at(1.0 + kMaxAgeS + 0.01), nullptr, kLandedM, kMaxAgeS);
  EXPECT_FALSE(s.t.floor_under(0.05f, 0.0f).has_value());
  s.read(2.0, 0.05f);
  EXPECT_FALSE(s.t.floor_under(0.05f, 0.0f).has_value());
}

// At the URG-04LX's 10 Hz with a few millimetres of noise: on the floor, touchdown at the
// second reading; descending at 0.3 m/s, never.
TEST(TouchdownSense, TenHertzNoisyReadingsOnTheFloorAndDescending) {
  const float noise[] = {0.004f, -0.003f, 0.005f, -0.004f, 0.002f};
  Sense floor;
  floor.read(1.0, 0.003f + noise[0]);
  EXPECT_EQ(floor.t.on_ground(), kNotDown);
  for (int i = 1; i < 5; ++i) {
    floor.read(1.0 + 0.1 * i, 0.003f + noise[i]);
    EXPECT_EQ(floor.t.on_ground(), kDown) << i;
  }
  Sense descending;
  for (int i = 0; i < 4; ++i) {
    descending.read(1.0 + 0.1 * i, 0.11f - 0.03f * static_cast<float>(i) + noise[i]);
    EXPECT_EQ(descending.t.on_ground(), kNotDown) << i;
  }
}

// A gap between two low readings, or a reading out of reason between them, says nothing of what
// the vehicle did meanwhile: the run starts again.
TEST(TouchdownSense, AGapOrAnUnusableReadingStartsTheRunAgain) {
  Sense gap;
  gap.read(1.0, 0.05f);
  gap.read(1.0 + TouchdownSense::kMaxGapS + 0.01, 0.05f);
  EXPECT_EQ(gap.t.on_ground(), kNotDown);
  gap.read(1.1 + TouchdownSense::kMaxGapS + 0.01, 0.05f);
  EXPECT_EQ(gap.t.on_ground(), kDown);
  Sense garbage;
  garbage.read(1.0, 0.05f);
  garbage.read(1.05, std::nanf(""));
  garbage.read(1.1, 0.05f);
  EXPECT_EQ(garbage.t.on_ground(), kNotDown);
}

// A vehicle rocking on its legs, read at the uneven gaps of a starved loop, never reads still;
// low readings, none over the landed height, each within kLowGapS of the one before, are
// touchdown after kLowS all the same. A reading over the height, or a longer gap, starts the
// wait again.
TEST(TouchdownSense, LowReadingsThatNeverHoldStillAreTouchdownAfterTheLowWait) {
  const double gaps[] = {0.04, 0.27, 0.08, 0.15, 0.05, 0.2};
  auto rock = [&](Sense& s, double from_s, double until_s) {
    int i = 0;
    for (double t = from_s; t < until_s; t += gaps[i % 6], ++i) {
      s.read(t, i % 2 == 0 ? 0.01f : 0.04f);
      if (t - from_s < TouchdownSense::kLowS) {
        EXPECT_EQ(s.t.on_ground(), kNotDown) << t;
      }
    }
  };
  const double low_s = TouchdownSense::kLowS;
  Sense s;
  rock(s, 1.0, 1.0 + low_s + 0.3);
  EXPECT_EQ(s.t.on_ground(), kDown);

  Sense lifted;
  rock(lifted, 1.0, 1.0 + low_s - 0.3);
  lifted.read(1.0 + low_s - 0.2, 0.2f);  // over the landed height: not standing on the floor
  rock(lifted, 1.0 + low_s - 0.1, 1.0 + low_s + 0.5);
  EXPECT_EQ(lifted.t.on_ground(), kNotDown);

  Sense gap;
  rock(gap, 1.0, 1.0 + low_s - 0.3);
  rock(gap, 1.0 + low_s - 0.3 + TouchdownSense::kLowGapS + 0.05, 1.0 + low_s + 0.6);
  EXPECT_EQ(gap.t.on_ground(), kNotDown);
}

// The low wait's edges: readings kLowGapS apart still make one run, a longer gap or a reading
// out of reason between two low ones starts it again.
TEST(TouchdownSense, TheLowWaitHoldsAcrossGapsUpToItsLimitAndNotAcrossGarbage) {
  const double step = TouchdownSense::kLowGapS;
  const int steps = static_cast<int>(TouchdownSense::kLowS / step + 0.5);  // kLowS in steps
  auto rock = [](Sense& s, double t, int i) { s.read(t, i % 2 == 0 ? 0.01f : 0.04f); };
  Sense edge;
  for (int i = 0; i <= steps; ++i) {
    rock(edge, 1.0 + step * i, i);
    EXPECT_EQ(edge.t.on_ground(), i == steps ? kDown : kNotDown) << i;
  }
  Sense longer;
  for (int i = 0; i <= steps; ++i) rock(longer, 1.0 + step * i + (i >= 2 ? 0.01 : 0.0), i);
  EXPECT_EQ(longer.t.on_ground(), kNotDown);
  Sense garbage;
  for (int i = 0; i <= steps; ++i) {
    rock(garbage, 1.0 + step * i, i);
    if (i == 1) garbage.read(1.0 + step * i + 0.01, std::nanf(""));
  }
  EXPECT_EQ(garbage.t.on_ground(), kNotDown);
}

TEST(TouchdownSense, ResetForgetsEverything) {
  Sense s;
  s.read(1.0, 0.05f);
  s.read(1.1, 0.05f);
  ASSERT_EQ(s.t.on_ground(), kDown);
  s.t.reset();
  EXPECT_FALSE(s.t.on_ground().has_value());
  s.read(1.2, 0.05f);
  EXPECT_EQ(s.t.on_ground(), kNotDown);
}

}  // namespace
}  // namespace kestrel::mission
