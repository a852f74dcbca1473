// Facing across an axis the scan matcher cannot measure (look_across.hpp): when it turns, which
// way, when it turns back, and that it is off by default and inside every explorer's step.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "kestrel/core/angle.hpp"
#include "kestrel/exploration/blend_explorer.hpp"
#include "kestrel/exploration/look_across.hpp"
#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

MatchConstraint match(double t_s, bool degenerate, float axis_rad = 0.0f) {
  MatchConstraint m;
  m.stamp = TimeUs{static_cast<int64_t>(std::llround(t_s * 1e6))};
  m.degenerate = degenerate;
  m.flat_axis_rad = axis_rad;
  m.usable = true;
  return m;
}

LookAcross configured(float after_s, float release_s) {
  LookAcrossParams p;
  p.after_s = after_s;
  p.release_s = release_s;
  EXPECT_TRUE(p.valid());
  LookAcross look;
  look.configure(p);
  return look;
}

TEST(LookAcross, TurnsAcrossOnlyOnceTheMatchHasBeenDegenerateLongEnough) {
  LookAcross look = configured(2.0f, 1.0f);
  for (int k = 0; k < 20; ++k) {  // 1.9 s of degenerate matches along x
    look.note(match(0.1 * k, true, 0.0f));
    EXPECT_FALSE(look.active()) << k;
    EXPECT_FLOAT_EQ(look.heading(kPi), kPi);
  }
  look.note(match(2.0, true, 0.0f));
  EXPECT_TRUE(look.active());
  EXPECT_EQ(look.looks(), 1u);
}

TEST(LookAcross, TakesTheHeadingAcrossTheAxisNearerTheTarget) {
  LookAcross look = configured(0.5f, 1.0f);
  look.note(match(0.0, true, 0.05f));  // a hallway along x, its axis either sense
  look.note(match(1.0, true, 0.05f));
  ASSERT_TRUE(look.active());
  // Facing west down the hall (the traced runaway): north or south, whichever is nearer.
  EXPECT_NEAR(look.heading(kPi - 0.3f), 0.05f + kPi / 2, 1e-5);   // west-north-west: north
  EXPECT_NEAR(look.heading(-kPi + 0.3f), 0.05f - kPi / 2, 1e-5);  // west-south-west: south
  // Never more than 90 degrees from the target, so the way flown stays in the laser's field.
  for (float target = -3.1f; target < 3.1f; target += 0.1f)
    EXPECT_LE(std::fabs(angle_diff(look.heading(target), target)), kPi / 2 + 1e-5f) << target;
  // The axis reported with the other sense gives the same two headings.
  look.note(match(2.0, true, 0.05f - kPi));
  EXPECT_NEAR(std::fabs(angle_diff(look.heading(kPi - 0.3f), 0.05f + kPi / 2)), 0.0f, 1e-5);
}

TEST(LookAcross, TurnsBackOnlyAfterTheMatchHasBeenClearForTheReleaseTime) {
  LookAcross look = configured(1.0f, 2.0f);
  look.note(match(0.0, true));
  look.note(match(1.0, true));
  ASSERT_TRUE(look.active());
  look.note(match(1.1, false));  // a jamb glimpsed for a scan
  look.note(match(1.2, true));   // and lost again: the clear spell starts over
  look.note(match(1.3, false));
  look.note(match(3.2, false));
  EXPECT_TRUE(look.active());  // 1.9 s clear
  look.note(match(3.3, false));
  EXPECT_FALSE(look.active());
  EXPECT_FLOAT_EQ(look.heading(1.0f), 1.0f);
  // A new degenerate spell needs its full time again.
  look.note(match(3.4, true));
  look.note(match(4.3, true));
  EXPECT_FALSE(look.active());
  look.note(match(4.4, true));
  EXPECT_TRUE(look.active());
  EXPECT_EQ(look.looks(), 2u);
}

TEST(LookAcross, OffByDefaultAndDeafToStaleOrNonFiniteMatches) {
  LookAcross off;
  off.configure(LookAcrossParams{});
  for (int k = 0; k < 100; ++k) off.note(match(0.1 * k, true));
  EXPECT_FALSE(off.active());

  LookAcross look = configured(1.0f, 1.0f);
  look.note(match(5.0, true));
  look.note(match(4.0, true));  // backwards: ignored, the spell still starts at 5 s
  look.note(match(5.0, true));  // repeated: ignored
  look.note(match(5.9, true));
  EXPECT_FALSE(look.active());
  look.note(match(6.0, true, NAN));  // no axis: ignored
  EXPECT_FALSE(look.active());
  look.note(match(6.1, true));
  EXPECT_TRUE(look.active());
  look.reset();
  EXPECT_FALSE(look.active());
  EXPECT_EQ(look.looks(), 0u);
}

TEST(LookAcross, ParametersOutsideTheirRangeDoNotConfigureAnExplorer) {
  for (float bad : {-1.0f, 601.0f, NAN, INFINITY}) {
    Params p;
    p.look_across.after_s = bad;
    EXPECT_EQ(p.validate(), Status::kInvalidArgument) << bad;
    p = Params{};
    p.look_across.release_s = bad;
    EXPECT_EQ(p.validate(), Status::kInvalidArgument) << bad;
  }
}

TEST(LookAcross, TheBlendsHeadingTurnsAcrossAndItsVelocityIsUnchanged) {
  // The same hall and pose, stepped with and without a degenerate spell: the velocity command
  // is the same, the heading target is across the hall's axis.
  test::SegmentWorld w;
  w.add_box(-3, -2, 9, 2);
  const test::LaserModel urg = test::LaserModel::urg04lx();
  Params p;
  p.srt.arrival_work_per_cycle = 0;  // the first waypoint in the first step
  p.look_across.after_s = 0.5f;
  auto plain = std::make_unique<BlendExplorer>();
  auto looking = std::make_unique<BlendExplorer>();
  LaserScan scan = w.scan(urg, 0, 0, 0);
  ASSERT_EQ(plain->configure(p, BeamGeometry::of(scan)), Status::kOk);
  ASSERT_EQ(looking->configure(p, BeamGeometry::of(scan)), Status::kOk);
  GuidanceSetpoint a, b;
  for (int k = 0; k <= 10; ++k) {
    scan.stamp = TimeUs{k * 100000};
    looking->note_match(match(0.1 * k, true, 0.0f));
    ASSERT_EQ(plain->step(test::nav_at(0, 0, 0), scan, a), Status::kOk);
    ASSERT_EQ(looking->step(test::nav_at(0, 0, 0), scan, b), Status::kOk);
    EXPECT_FLOAT_EQ(a.velocity_mps.x(), b.velocity_mps.x()) << k;
    EXPECT_FLOAT_EQ(a.velocity_mps.y(), b.velocity_mps.y()) << k;
  }
  EXPECT_FALSE(plain->status().looking_across);
  ASSERT_TRUE(looking->status().looking_across);
  EXPECT_EQ(looking->status().look_across_turns, 1u);
  EXPECT_NEAR(std::fabs(looking->status().heading_target_rad), kPi / 2, 1e-5);
  EXPECT_LE(std::fabs(angle_diff(looking->status().heading_target_rad, plain->status().heading_target_rad)),
            kPi / 2 + 1e-5f);
  // The yaw-rate limit still holds the turn: 0.5 rad/s over the last 0.5 s.
  EXPECT_LE(std::fabs(angle_diff(b.heading_rad, 0.0f)), 0.5f * 1.0f + 1e-4f);
}

}  // namespace
}  // namespace kestrel::exploration
