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
  EXPECT_EQ(p.validate(), Status::kOk);
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

TEST(LookAcross, TakesTheHeadingAcrossTheAxisNearerTheTargetAndKeepsItsSide) {
  const auto looking = [](float axis_rad) {
    LookAcross look = configured(0.5f, 1.0f);
    look.note(match(0.0, true, axis_rad));
    look.note(match(0.5, true, axis_rad));
    EXPECT_TRUE(look.active());
    return look;
  };
  // A hallway along x, facing west down it (the traced runaway): north or south, whichever is
  // nearer the target, whichever sense the axis is reported in.
  for (float axis : {0.05f, 0.05f - kPi}) {
    LookAcross a = looking(axis);
    EXPECT_NEAR(a.heading(kPi - 0.3f), 0.05f + kPi / 2, 1e-5) << axis;  // west-north-west: north
    LookAcross b = looking(axis);
    EXPECT_NEAR(b.heading(-kPi + 0.3f), 0.05f - kPi / 2, 1e-5) << axis;  // west-south-west: south
  }
  // Once turned to a side it stays there while the target wavers across the axis: each swap
  // would be a half turn.
  LookAcross look = looking(0.0f);
  ASSERT_NEAR(look.heading(kPi - 0.1f), kPi / 2, 1e-5);
  EXPECT_NEAR(look.heading(-kPi + 0.1f), kPi / 2, 1e-5);  // 100 degrees off: kept
  EXPECT_NEAR(look.heading(-kPi / 2 - 0.3f), -kPi / 2, 1e-5);  // beyond 90 + 20 degrees: swapped
  // Never beyond 90 degrees plus the hysteresis of the target, inside the laser's 120.
  for (float target = -3.1f; target < 3.1f; target += 0.05f) {
    const float h = look.heading(target);
    EXPECT_LE(std::fabs(angle_diff(h, target)), kPi / 2 + LookAcross::kSideHysteresisRad + 1e-5f) << target;
    EXPECT_NEAR(std::fabs(angle_diff(h, 0.0f)), kPi / 2, 1e-5) << target;
  }
}

TEST(LookAcross, TurnsBackOnlyAfterTheMatchHasBeenClearForTheReleaseTime) {
  LookAcross look = configured(1.0f, 2.0f);
  // Matches every 0.1 s (the URG-04LX's rate) from t0 to t1 s, all degenerate or all clear.
  const auto spell = [&look](int t0_ds, int t1_ds, bool degenerate) {
    for (int k = t0_ds; k <= t1_ds; ++k) look.note(match(0.1 * k, degenerate));
  };
  spell(0, 10, true);
  ASSERT_TRUE(look.active());
  spell(11, 11, false);  // a jamb glimpsed for a scan
  spell(12, 12, true);   // and lost again: the clear spell starts over
  spell(13, 32, false);
  EXPECT_TRUE(look.active());  // 1.9 s clear
  spell(33, 33, false);
  EXPECT_FALSE(look.active());
  EXPECT_FLOAT_EQ(look.heading(1.0f), 1.0f);
  // A new degenerate spell needs its full time again.
  spell(34, 43, true);
  EXPECT_FALSE(look.active());
  spell(44, 44, true);
  EXPECT_TRUE(look.active());
  EXPECT_EQ(look.looks(), 2u);
}

TEST(LookAcross, OffByDefaultAndDeafToStaleMatches) {
  LookAcross off;
  off.configure(LookAcrossParams{});
  for (int k = 0; k < 100; ++k) off.note(match(0.1 * k, true));
  EXPECT_FALSE(off.active());

  LookAcross look = configured(1.0f, 1.0f);
  look.note(match(5.0, false));
  look.note(match(4.0, true));   // backwards: ignored (else a spell from 4 s)
  look.note(match(5.0, true));   // repeated: ignored
  look.note(match(5.05, true));  // the spell starts here
  look.note(match(5.5, true));
  look.note(match(6.0, true));
  EXPECT_FALSE(look.active());
  look.note(match(6.05, true));
  EXPECT_TRUE(look.active());
  look.reset();
  EXPECT_FALSE(look.active());
  EXPECT_EQ(look.looks(), 0u);
  // However short, a positive time is on.
  LookAcross soon = configured(1e-9f, 1.0f);
  soon.note(match(1.0, true));
  soon.note(match(1.001, true));
  EXPECT_TRUE(soon.active());
}

TEST(LookAcross, ALostMatchOrAGapEndsTheSpell) {
  // Lost matches (facing across, the fan may hold too little) end the spell and count towards
  // turning back: they cannot tell which way to look.
  LookAcross look = configured(1.0f, 1.0f);
  look.note(match(0.0, true));
  look.note(match(0.5, true));
  MatchConstraint lost = match(0.9, true);
  lost.usable = false;
  look.note(lost);
  look.note(match(1.0, true));  // a new spell from here
  EXPECT_FALSE(look.active());
  look.note(match(1.5, true));
  look.note(match(2.0, true));
  ASSERT_TRUE(look.active());
  for (int k = 1; k <= 10; ++k) {
    lost.stamp = TimeUs{2000000 + k * 100000};
    look.note(lost);
  }
  EXPECT_TRUE(look.active());  // 0.9 s of lost matches since the first
  lost.stamp = TimeUs{3100000};
  look.note(lost);
  EXPECT_FALSE(look.active());  // 1 s: turned back
  // Two matches 0.9 s apart are no spell of 0.9 s.
  LookAcross gap = configured(0.8f, 1.0f);
  gap.note(match(10.0, true));
  gap.note(match(10.9, true));
  EXPECT_FALSE(gap.active());
  gap.note(match(11.3, true));
  gap.note(match(11.7, true));
  EXPECT_TRUE(gap.active());
  // A degenerate match without an axis is no direction to look in: it ends the spell too.
  LookAcross nan_axis = configured(1.0f, 0.5f);
  nan_axis.note(match(0.0, true));
  nan_axis.note(match(0.5, true, NAN));
  nan_axis.note(match(1.0, true));
  EXPECT_FALSE(nan_axis.active());
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
  // The yaw-rate limit still holds the turn: at 0.5 rad/s, 0.5 rad in the 1 s stepped.
  EXPECT_LE(std::fabs(angle_diff(b.heading_rad, 0.0f)), 0.5f * 1.0f + 1e-4f);
}

}  // namespace
}  // namespace kestrel::exploration
