#include "kestrel/mission/held_descent.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

namespace kestrel::mission {
namespace {

constexpr float kStepS = 0.025f;  // the guidance rate at 40 Hz
constexpr float kDeskM = 0.75f;
const float kNaN = std::numeric_limits<float>::quiet_NaN();

// A landing's steps at kStepS, each with a new estimate.
struct Steps {
  HeldDescent h;
  TimeUs stamp;
  int steps = 0;  // since the last first_held()
  void step(float height_m, float setpoint_m, float speed_mps = 0.0f, std::optional<float> reading = std::nullopt,
            float dt_s = kStepS) {
    stamp += Duration::from_s(dt_s);
    h.observe(dt_s, stamp, height_m, speed_mps, setpoint_m, reading);
  }
  // Steps for at most `for_s`; the steps' time until the first held, or NaN.
  float first_held(float for_s, float height_m, float setpoint_m, float speed_mps = 0.0f,
                   std::optional<float> reading = std::nullopt) {
    for (steps = 1; static_cast<float>(steps) * kStepS < for_s + 1e-4f; ++steps) {
      step(height_m, setpoint_m, speed_mps, reading);
      if (h.held()) return static_cast<float>(steps - 1) * kStepS;  // from the run's first step
    }
    return kNaN;
  }
};

TEST(HeldDescent, StillWithTheSetPointWellUnderForASecondIsHeld) {
  Steps s;
  EXPECT_NEAR(s.first_held(2.0f, kDeskM, kDeskM - HeldDescent::kGapM - 0.01f), HeldDescent::kHeldS, 1e-3f);
}

// The ramp's own aim, 0.2 m under the floor the vehicle rests on, is touchdown's business.
TEST(HeldDescent, ASetPointNoFurtherUnderThanTheGapIsNeverHeld) {
  Steps s;
  EXPECT_TRUE(std::isnan(s.first_held(10.0f, 0.0f, -0.2f)));
  EXPECT_TRUE(std::isnan(s.first_held(10.0f, kDeskM, kDeskM - HeldDescent::kGapM + 0.01f)));
}

TEST(HeldDescent, AVehicleMovingIsNotHeld) {
  Steps s;
  EXPECT_TRUE(std::isnan(s.first_held(5.0f, kDeskM, 0.0f, -HeldDescent::kStillSpeedMps)));
  EXPECT_TRUE(std::isnan(s.first_held(5.0f, kDeskM, 0.0f, 0.3f)));
}

// Descending slowly, 4 cm a second (under the speed called still): the height leaves the band
// within the second and the run starts again, so no second passes with it still.
TEST(HeldDescent, AHeightThatCreepsOutOfTheBandStartsTheRunAgain) {
  Steps s;
  for (int i = 0; i < 400; ++i) {
    s.step(kDeskM - 0.04f * static_cast<float>(i) * kStepS, -0.2f, -0.04f);
    ASSERT_FALSE(s.h.held()) << "step " << i;
  }
}

// The estimate frozen while the vehicle sinks under it: its readings move, and the wait starts
// again with each that leaves the band. On a rim they stay; and the silence of an altimeter
// that stopped reading leaves the estimate's word.
TEST(HeldDescent, ReadingsThatMoveAreNotHeldStillOnesAre) {
  Steps s;
  for (int i = 0; i < 400; ++i) {
    s.step(kDeskM, 0.0f, 0.0f, kDeskM - 0.3f * static_cast<float>(i) * kStepS);
    ASSERT_FALSE(s.h.held()) << "step " << i;
  }
  Steps rim;
  EXPECT_NEAR(rim.first_held(2.0f, 0.3f, -0.2f, 0.0f, 0.3f), HeldDescent::kHeldS, 1e-3f);
  Steps silent;
  EXPECT_TRUE(std::isnan(silent.first_held(0.5f, kDeskM, 0.0f, 0.0f, 0.02f)));
  EXPECT_NEAR(silent.first_held(2.0f, kDeskM, 0.0f), HeldDescent::kHeldS - 0.5f, 1e-3f);
}

// A state that stops advancing (the filter not run) says nothing of the vehicle.
TEST(HeldDescent, AnEstimateThatIsNotNewStartsTheWaitAgain) {
  Steps s;
  EXPECT_TRUE(std::isnan(s.first_held(0.9f, kDeskM, 0.0f)));
  s.h.observe(kStepS, s.stamp, kDeskM, 0.0f, 0.0f, std::nullopt);  // the same stamp again
  EXPECT_FALSE(s.h.held());
  EXPECT_NEAR(s.first_held(2.0f, kDeskM, 0.0f), HeldDescent::kHeldS, 1e-3f);
}

TEST(HeldDescent, ABreakOrANonFiniteValueStartsTheWaitAgain) {
  const float under = kDeskM - 0.5f;
  Steps s;
  EXPECT_TRUE(std::isnan(s.first_held(0.9f, kDeskM, under)));
  s.h.interrupt();  // an estimate not believed for a step
  EXPECT_NEAR(s.first_held(2.0f, kDeskM, under), HeldDescent::kHeldS, 1e-3f);

  for (const float bad : {kNaN, std::numeric_limits<float>::infinity()}) {
    for (int which = 0; which < 4; ++which) {
      Steps g;
      EXPECT_TRUE(std::isnan(g.first_held(0.9f, kDeskM, under, 0.0f, kDeskM)));
      g.step(which == 0 ? bad : kDeskM, which == 1 ? bad : under, which == 2 ? bad : 0.0f,
             which == 3 ? bad : kDeskM);
      EXPECT_FALSE(g.h.held()) << which;
      EXPECT_NEAR(g.first_held(2.0f, kDeskM, under, 0.0f, kDeskM), HeldDescent::kHeldS, 1e-3f) << which;
    }
  }
}

// A stalled loop's step counts 0.1 s, a step back in time none: two steps a second apart are
// not a second held.
TEST(HeldDescent, ALongOrABackwardStepIsNotTimeHeld) {
  Steps s;
  s.step(kDeskM, 0.0f);
  s.step(kDeskM, 0.0f, 0.0f, std::nullopt, 1.0f);
  s.step(kDeskM, 0.0f, 0.0f, std::nullopt, 5.0f);
  EXPECT_FALSE(s.h.held());
  for (int i = 0; i < 7; ++i) s.step(kDeskM, 0.0f, 0.0f, std::nullopt, 0.1f);  // 0.9 s in all
  s.h.observe(-3600.0f, s.stamp + Duration::from_s(0.1), kDeskM, 0.0f, 0.0f, std::nullopt);
  EXPECT_FALSE(s.h.held());
  s.step(kDeskM, 0.0f, 0.0f, std::nullopt, 0.2f);
  EXPECT_TRUE(s.h.held());
  s.h.reset();
  EXPECT_FALSE(s.h.held());
}

}  // namespace
}  // namespace kestrel::mission
