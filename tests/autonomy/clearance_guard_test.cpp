// The altitude set-point kept clear of what the altimeter finds under the vehicle
// (clearance_guard.hpp): raised to the floor's height plus the clearance, by at most
// max_rise_m, held hold_s after the floor falls, and never changed outside the flight altitude.
#include "kestrel/autonomy/clearance_guard.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <optional>

namespace kestrel::autonomy {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
const TimeUs kT0 = TimeUs::from_s(100.0);

GuidanceSetpoint at_height(float z, GuidanceSetpoint::Mode mode = GuidanceSetpoint::Mode::kVelocity) {
  GuidanceSetpoint sp;
  sp.mode = mode;
  sp.position_m = {3.0f, 4.0f, z};
  sp.velocity_mps = {0.4f, -0.1f, 0.0f};
  sp.heading_rad = 0.7f;
  return sp;
}

// The set-point's height after one cycle at `t` over `floor_m`.
float height_after(ClearanceGuard& g, TimeUs t, float floor_m, float z = 1.0f, bool in_flight = true) {
  GuidanceSetpoint sp = at_height(z);
  g.apply(t, floor_m, in_flight, sp);
  return sp.position_m.z();
}

// GIVEN a flight at 1.0 m, THEN the take-off floor and 0.75 m desks (clearance 0.25 m) leave
// the set-point alone, and nothing but its height is ever changed.
TEST(ClearanceGuard, AFloorClearByTheMarginLeavesTheSetpointAlone) {
  ClearanceGuard g;
  EXPECT_FLOAT_EQ(height_after(g, kT0, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(height_after(g, kT0 + Duration::from_ms(100), 0.75f), 1.0f);
  GuidanceSetpoint sp = at_height(1.0f, GuidanceSetpoint::Mode::kPosition);
  g.apply(kT0 + Duration::from_ms(200), 0.9f, true, sp);
  const GuidanceSetpoint before = at_height(1.0f, GuidanceSetpoint::Mode::kPosition);
  EXPECT_EQ(sp.mode, before.mode);
  EXPECT_EQ(sp.position_m.head<2>(), before.position_m.head<2>());
  EXPECT_EQ(sp.velocity_mps, before.velocity_mps);
  EXPECT_EQ(sp.heading_rad, before.heading_rad);
}

// GIVEN gt-building's 0.9 m box under a 1.0 m flight, THEN the set-point rises to 1.15 m, in
// either mode; a floor near the ceiling raises it by max_rise_m only.
TEST(ClearanceGuard, AFloorWithinTheMarginRaisesTheSetpointToKeepIt) {
  ClearanceGuard g;
  EXPECT_NEAR(height_after(g, kT0, 0.9f), 1.15f, 1e-6f);
  EXPECT_NEAR(g.rise_m(), 0.15f, 1e-6f);
  GuidanceSetpoint sp = at_height(1.0f, GuidanceSetpoint::Mode::kPosition);
  g.apply(kT0 + Duration::from_ms(100), 0.9f, true, sp);
  EXPECT_NEAR(sp.position_m.z(), 1.15f, 1e-6f);
  EXPECT_NEAR(height_after(g, kT0 + Duration::from_ms(200), 2.0f), 1.5f, 1e-6f);
}

// GIVEN the set-point raised over the box, WHEN the altimeter leaves it (the floor back to 0),
// THEN the rise stands hold_s (the body's rim is still over the box) and is then dropped; a
// second box within the hold renews it.
TEST(ClearanceGuard, TheRiseIsHeldAfterTheFloorFallsThenDropped) {
  ClearanceParams p;
  p.hold_s = 2.0f;
  ClearanceGuard g(p);
  (void)height_after(g, kT0, 0.9f);
  EXPECT_NEAR(height_after(g, kT0 + Duration::from_ms(1900), 0.0f), 1.15f, 1e-6f);
  EXPECT_FLOAT_EQ(height_after(g, kT0 + Duration::from_ms(2000), 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(g.rise_m(), 0.0f);
  (void)height_after(g, kT0 + Duration::from_ms(3000), 0.85f);  // a lower box: 0.1 m
  (void)height_after(g, kT0 + Duration::from_ms(3500), 0.95f);  // a higher one: 0.2 m at once
  EXPECT_NEAR(g.rise_m(), 0.2f, 1e-6f);
  EXPECT_NEAR(height_after(g, kT0 + Duration::from_ms(5400), 0.85f), 1.2f, 1e-6f);
  EXPECT_NEAR(height_after(g, kT0 + Duration::from_ms(5500), 0.85f), 1.1f, 1e-6f);
}

// GIVEN a rise standing over the box, WHEN one cycle's set-point already stands higher (the
// mission holds the estimated, raised, height the cycle it turns home) or part way up, THEN it is
// raised to the height kept and no further: the height is held, not the rise.
TEST(ClearanceGuard, ASetpointAlreadyRaisedIsNotRaisedAgain) {
  ClearanceGuard g;
  EXPECT_NEAR(height_after(g, kT0, 0.9f), 1.15f, 1e-6f);
  EXPECT_NEAR(height_after(g, kT0 + Duration::from_ms(100), 0.9f, 1.16f), 1.16f, 1e-6f);
  EXPECT_FLOAT_EQ(g.rise_m(), 0.0f);
  EXPECT_NEAR(height_after(g, kT0 + Duration::from_ms(200), 0.0f, 1.1f), 1.15f, 1e-6f);  // held
  EXPECT_NEAR(g.rise_m(), 0.05f, 1e-6f);
  EXPECT_NEAR(height_after(g, kT0 + Duration::from_ms(300), 0.0f), 1.15f, 1e-6f);
  EXPECT_EQ(g.rises(), 1u) << "one raised floor, interrupted by a higher set-point, is one rise";
}

// Rises are counted once per raised floor, or floors within one another's hold; a floor that
// wants a height the set-point already clears is none; after the hold or outside the flight
// altitude, the next raised floor is another.
TEST(ClearanceGuard, RisesAreCountedOncePerRaisedFloor) {
  ClearanceGuard g;
  (void)height_after(g, kT0, 0.6f);  // wants 0.85 m: clear at 1.0 m
  EXPECT_EQ(g.rises(), 0u);
  (void)height_after(g, kT0 + Duration::from_ms(100), 0.9f);
  (void)height_after(g, kT0 + Duration::from_ms(200), 0.95f);
  (void)height_after(g, kT0 + Duration::from_ms(1000), 0.0f);
  EXPECT_EQ(g.rises(), 1u);
  (void)height_after(g, kT0 + Duration::from_ms(2500), 0.0f);  // the hold over: dropped
  ASSERT_FLOAT_EQ(g.rise_m(), 0.0f);
  (void)height_after(g, kT0 + Duration::from_ms(3000), 0.9f);
  EXPECT_EQ(g.rises(), 2u);
  (void)height_after(g, kT0 + Duration::from_ms(3100), 0.9f, 0.5f, false);
  (void)height_after(g, kT0 + Duration::from_ms(3200), 0.9f);
  EXPECT_EQ(g.rises(), 3u);
  // Off the box onto a desk the flight clears: the box's height held, then, kept anew, the
  // desk's, which raises nothing; the next box is another rise.
  (void)height_after(g, kT0 + Duration::from_ms(4000), 0.75f);
  (void)height_after(g, kT0 + Duration::from_ms(5300), 0.75f);
  ASSERT_FLOAT_EQ(g.rise_m(), 0.0f);
  (void)height_after(g, kT0 + Duration::from_ms(5400), 0.9f);
  EXPECT_EQ(g.rises(), 4u);
}

// Taking off, landing or on the ground the height is the mission's own: nothing is changed and
// a standing rise is forgotten, so that the next flight altitude starts unraised.
TEST(ClearanceGuard, OutsideTheFlightAltitudeNothingChangesAndTheRiseIsForgotten) {
  ClearanceGuard g;
  (void)height_after(g, kT0, 0.9f);
  ASSERT_GT(g.rise_m(), 0.0f);
  EXPECT_FLOAT_EQ(height_after(g, kT0 + Duration::from_ms(100), 0.9f, 0.5f, false), 0.5f);
  EXPECT_FLOAT_EQ(g.rise_m(), 0.0f);
  EXPECT_FLOAT_EQ(height_after(g, kT0 + Duration::from_ms(200), 0.0f), 1.0f);
}

// On the take-off floor the flight altitude is the operator's, whatever the clearance: a 0.3 m
// flight with a 0.5 m clearance is not raised until a raised floor is found.
TEST(ClearanceGuard, OnTheTakeOffFloorNothingIsRaisedWhateverTheClearance) {
  ClearanceParams p;
  p.min_clearance_m = 0.5f;
  ClearanceGuard g(p);
  EXPECT_FLOAT_EQ(height_after(g, kT0, 0.0f, 0.3f), 0.3f);
  EXPECT_FLOAT_EQ(height_after(g, kT0 + Duration::from_ms(100), -0.2f, 0.3f), 0.3f);
  EXPECT_NEAR(height_after(g, kT0 + Duration::from_ms(200), 0.15f, 0.3f), 0.65f, 1e-6f);
}

TEST(ClearanceGuard, ZeroClearanceTurnsItOff) {
  ClearanceParams p;
  p.min_clearance_m = 0.0f;
  ClearanceGuard g(p);
  EXPECT_FLOAT_EQ(height_after(g, kT0, 0.95f), 1.0f);
}

// A floor that is not a number wants no rise; the standing one is held as any other and then
// dropped. A clock that stepped back ends the hold: it cannot keep a rise forever.
TEST(ClearanceGuard, ANonFiniteFloorOrABackwardClockNeverStretchesARise) {
  ClearanceGuard g;
  (void)height_after(g, kT0, 0.9f);
  EXPECT_NEAR(height_after(g, kT0 + Duration::from_ms(500), kNaN), 1.15f, 1e-6f);
  EXPECT_FLOAT_EQ(height_after(g, kT0 + Duration::from_ms(2500), kNaN), 1.0f);
  (void)height_after(g, kT0 + Duration::from_ms(3000), 0.9f);
  EXPECT_FLOAT_EQ(height_after(g, kT0 - Duration::from_s(50), 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(height_after(g, kT0 + Duration::from_ms(3100), std::numeric_limits<float>::infinity()), 1.0f);
}

// The floor the filter is weighing counts before it is placed (the filter refuses the run of
// readings for altitude_relock_s) where it lies over the placed one; leaving a raised floor, the
// placed one stands until the filter decides. A floor not finite is passed over.
TEST(ClearanceGuard, TheFloorBeingWeighedCountsBeforeItIsPlaced) {
  EXPECT_NEAR(ClearanceGuard::floor_under(0.0f, 0.9f), 0.9f, 1e-6f);
  EXPECT_NEAR(ClearanceGuard::floor_under(0.9f, std::nullopt), 0.9f, 1e-6f);
  EXPECT_NEAR(ClearanceGuard::floor_under(0.9f, 0.0f), 0.9f, 1e-6f);
  EXPECT_NEAR(ClearanceGuard::floor_under(kNaN, 0.9f), 0.9f, 1e-6f);
  EXPECT_NEAR(ClearanceGuard::floor_under(0.2f, kNaN), 0.2f, 1e-6f);
  EXPECT_NEAR(ClearanceGuard::floor_under(0.2f, std::numeric_limits<float>::infinity()), 0.2f, 1e-6f);
}

TEST(ClearanceGuard, ValidateRefusesWhatIsNotAClearance) {
  EXPECT_EQ(validate(ClearanceParams{}), Status::kOk);
  for (auto broken : {+[](ClearanceParams& p) { p.min_clearance_m = -0.1f; },
                      +[](ClearanceParams& p) { p.min_clearance_m = kNaN; },
                      +[](ClearanceParams& p) { p.max_rise_m = -1.0f; },
                      +[](ClearanceParams& p) { p.max_rise_m = 10.0f; },
                      +[](ClearanceParams& p) { p.hold_s = kNaN; },
                      +[](ClearanceParams& p) { p.hold_s = -1.0f; }}) {
    ClearanceParams p;
    broken(p);
    EXPECT_EQ(validate(p), Status::kInvalidArgument);
  }
}

}  // namespace
}  // namespace kestrel::autonomy
