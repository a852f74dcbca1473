// The approach limiter: no return is closed on faster than gain * (range - stop_distance),
// motion along or away from the returns is kept, and the command is never made unsafe.
#include "kestrel/exploration/approach_limiter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using test::LaserModel;
using test::SegmentWorld;
using test::uniform_scan;

struct Rig {
  explicit Rig(const LaserModel& m, ApproachParams p = {}) : model(m), params(p) {
    const LaserScan probe = uniform_scan(m, 1000);
    directions->build(BeamGeometry::of(probe));
    EXPECT_EQ(limiter.configure(params, BeamGeometry::of(probe)), Status::kOk);
  }
  // Body-frame command after the limiter, the vehicle at the origin heading along +x.
  Eigen::Vector2f run(const SegmentWorld& w, Eigen::Vector2f v, ApproachResult* result = nullptr) const {
    const LaserScan s = w.scan(model, 0, 0, 0);
    const ApproachResult r = limiter.limit(s, *directions, v);
    if (result != nullptr) *result = r;
    return v;
  }
  LaserModel model;
  ApproachParams params;
  std::unique_ptr<BeamDirections> directions = std::make_unique<BeamDirections>();
  ApproachLimiter limiter;
};

// The largest amount by which a command closes on any return, or on any direction of the
// laser's blind arc, beyond its bound (m/s), in double precision from the scan itself.
double worst_excess(const LaserScan& s, const ApproachParams& p, const Eigen::Vector2f& v) {
  double worst = -1e9;
  const double fov = std::fabs(static_cast<double>(s.angle_step_rad)) * (s.beam_count - 1);
  const double last = static_cast<double>(s.first_angle_rad) + fov;  // counter-clockwise scans here
  for (double a = last + 0.1; a < s.first_angle_rad + 2 * M_PI - 0.1; a += 0.01)
    worst = std::max(worst, v.x() * std::cos(a) + v.y() * std::sin(a) - p.blind_speed_mps);
  for (int i = 0; i < s.beam_count; ++i) {
    if (s.range_mm[i] < kMinValidRangeMm) continue;
    const double a = static_cast<double>(s.first_angle_rad) + static_cast<double>(s.angle_step_rad) * i;
    const double closing = v.x() * std::cos(a) + v.y() * std::sin(a);
    const double bound = p.gain * (s.range_mm[i] * 1e-3 - p.stop_distance_m);
    worst = std::max(worst, closing - bound);
  }
  return worst;
}

TEST(ApproachLimiter, FreeSpaceLeavesTheCommandAlone) {
  const Rig rig(LaserModel::utm30lx());
  SegmentWorld far;
  far.add_box(-10, -10, 10, 10);
  ApproachResult r;
  const Eigen::Vector2f v = rig.run(far, {0.5f, 0.2f}, &r);
  EXPECT_NEAR(v.x(), 0.5f, 1e-3);
  EXPECT_NEAR(v.y(), 0.2f, 1e-3);
  EXPECT_EQ(r.cuts, 0);
  EXPECT_FALSE(r.stopped);
}

TEST(ApproachLimiter, WallAheadCapsTheClosingSpeed) {
  // GIVEN a wall 0.8 m ahead and a 0.5 m/s command straight into it
  const Rig rig(LaserModel::urg04lx());
  SegmentWorld w;
  w.add(0.8, -5, 0.8, 5);
  ApproachResult r;
  const Eigen::Vector2f v = rig.run(w, {0.5f, 0.0f}, &r);
  // THEN the closing speed is gain * (0.8 - 0.4), in one cut
  // (to a few mm/s: the beams are 0.35 degrees apart and the ranges whole millimetres)
  EXPECT_NEAR(v.x(), 1.0f * (0.8f - 0.4f), 0.006);
  EXPECT_NEAR(v.y(), 0.0f, 0.006);
  EXPECT_EQ(r.cuts, 1);
}

TEST(ApproachLimiter, SlideAlongAWallIsKeptWhileClosingIsCut) {
  // GIVEN the same wall and 0.3 m/s along it as well
  const Rig rig(LaserModel::urg04lx());
  SegmentWorld w;
  w.add(0.8, -5, 0.8, 5);
  const Eigen::Vector2f v = rig.run(w, {0.5f, 0.3f});
  // THEN the oblique returns ahead-left bound it a little below the head-on 0.4 m/s; the
  // slide is kept; no return is closed on too fast
  EXPECT_GT(v.x(), 0.3f);
  EXPECT_LT(v.x(), 0.4f);
  EXPECT_GT(v.y(), 0.25f);
  EXPECT_LE(worst_excess(w.scan(rig.model, 0, 0, 0), rig.params, v), 0.003);
  // Slide alone, 0.45 m from the wall: untouched.
  SegmentWorld near;
  near.add(0.45, -5, 0.45, 5);
  const Eigen::Vector2f slide = rig.run(near, {0.0f, 0.02f});
  EXPECT_NEAR(slide.x(), 0.0f, 0.002);
  EXPECT_NEAR(slide.y(), 0.02f, 0.002);
}

TEST(ApproachLimiter, InsideTheStopDistanceItBacksOff) {
  const Rig rig(LaserModel::urg04lx());
  SegmentWorld w;
  w.add(0.3, -5, 0.3, 5);
  const Eigen::Vector2f v = rig.run(w, {0.0f, 0.0f});
  EXPECT_NEAR(v.x(), -1.0f * (0.4f - 0.3f), 0.006);  // away at gain * (stop - r)
  EXPECT_NEAR(v.y(), 0.0f, 0.006);
}

TEST(ApproachLimiter, MovingAwayIsNeverCut) {
  // A wall 0.45 m to the left, the command away from it to the right and ahead (well inside
  // the laser's view).
  const Rig rig(LaserModel::utm30lx());
  SegmentWorld w;
  w.add(-5, 0.45, 5, 0.45);
  const Eigen::Vector2f v = rig.run(w, {0.4f, -0.3f});
  EXPECT_NEAR(v.x(), 0.4f, 1e-3);
  EXPECT_NEAR(v.y(), -0.3f, 1e-3);
}

TEST(ApproachLimiter, WhatTheLaserCannotSeeIsApproachedAtACreep) {
  // GIVEN free space all round and a command straight back, into the laser's blind arc
  const Rig rig(LaserModel::utm30lx());
  SegmentWorld far;
  far.add_box(-10, -10, 10, 10);
  const Eigen::Vector2f back = rig.run(far, {-0.5f, 0.0f});
  // THEN it is slowed to the blind creep (the sampled directions nearest straight back, 2.4
  // degrees either side, bound it)
  EXPECT_NEAR(back.x(), -rig.params.blind_speed_mps, 0.005);
  EXPECT_NEAR(back.y(), 0.0f, 0.02);
  // Sideways at 90 degrees closes on the blind arc's edge (135 degrees) too: the nearest
  // allowed command keeps most of the slide and turns it forward, away from the arc.
  const Eigen::Vector2f side = rig.run(far, {0.0f, 0.5f});
  EXPECT_GT(side.x(), 0.1f);
  EXPECT_GT(side.y(), 0.3f);
  EXPECT_LT(side.y(), 0.4f);
  // Forward and sideways within the view are free.
  const Eigen::Vector2f ahead = rig.run(far, {0.5f, 0.2f});
  EXPECT_NEAR(ahead.x(), 0.5f, 1e-3);
  EXPECT_NEAR(ahead.y(), 0.2f, 1e-3);
  // A 360-degree laser has no blind arc.
  const LaserModel ring{1080, 2 * M_PI, 30000};
  const Rig all(ring);
  const Eigen::Vector2f any = all.run(far, {-0.5f, 0.0f});
  EXPECT_NEAR(any.x(), -0.5f, 1e-3);
}

TEST(ApproachLimiter, DoorJambIsPassedNotHit) {
  // GIVEN a door jamb's end 0.45 m ahead-left of the vehicle and a command at 45 degrees
  // towards it (the closed-loop case that clipped jambs)
  const Rig rig(LaserModel::utm30lx());
  SegmentWorld w;
  w.add(0.32, 0.32, 0.32, 5);  // the jamb's wall runs away from the vehicle
  const Eigen::Vector2f v = rig.run(w, {0.35f, 0.35f});
  const LaserScan s = w.scan(rig.model, 0, 0, 0);
  // THEN no return is closed on beyond its bound, and the vehicle still moves forward
  EXPECT_LE(worst_excess(s, rig.params, v), 0.005);
  EXPECT_GT(v.norm(), 0.05f);
}

TEST(ApproachLimiter, CornerBoundsBothWalls) {
  const Rig rig(LaserModel::utm30lx());
  SegmentWorld w;
  w.add(0.6, -5, 0.6, 0.7);
  w.add(-5, 0.7, 0.6, 0.7);
  ApproachResult r;
  const Eigen::Vector2f v = rig.run(w, {0.5f, 0.5f}, &r);
  // Head-on each wall allows gain * (0.6 - 0.4) and gain * (0.7 - 0.4); the returns in between
  // allow less. Both walls are respected and the command still heads into the corner.
  EXPECT_LE(worst_excess(w.scan(rig.model, 0, 0, 0), rig.params, v), 0.003);
  EXPECT_GT(v.x(), 0.0f);
  EXPECT_LE(v.x(), 0.2f + 0.002f);
  EXPECT_GT(v.y(), 0.0f);
  EXPECT_LE(v.y(), 0.3f + 0.002f);
  EXPECT_FALSE(r.stopped);
}

TEST(ApproachLimiter, APassageNarrowerThanTwiceTheStopDistanceStopsTheVehicle) {
  // Walls 0.3 m either side: each asks the vehicle to back off the other way. No command keeps
  // both bounds; the cuts do not settle and the command is scaled down to zero.
  const Rig rig(LaserModel::utm30lx());
  SegmentWorld w;
  w.add(-5, 0.3, 5, 0.3);
  w.add(-5, -0.3, 5, -0.3);
  ApproachResult r;
  const Eigen::Vector2f v = rig.run(w, {0.4f, 0.0f}, &r);
  EXPECT_EQ(r.cuts, ApproachLimiter::kMaxCuts);
  EXPECT_TRUE(r.scaled);
  EXPECT_TRUE(r.stopped);
  EXPECT_FLOAT_EQ(v.norm(), 0.0f);
}

TEST(ApproachLimiter, RangeCodesAndDisabledLimiterAreIgnored) {
  // Range codes (no return, errors) are not obstacles.
  LaserModel m = LaserModel::urg04lx();
  Rig rig(m);
  LaserScan s = uniform_scan(m, range_code::kNoReturn);
  Eigen::Vector2f v{0.5f, 0.0f};
  rig.limiter.limit(s, *rig.directions, v);
  EXPECT_NEAR(v.x(), 0.5f, 1e-3);
  // Disabled: the paper's blend alone.
  ApproachParams off;
  off.enabled = false;
  Rig none(m, off);
  s = uniform_scan(m, 300);
  v = {0.5f, 0.0f};
  EXPECT_EQ(none.limiter.limit(s, *none.directions, v).cuts, 0);
  EXPECT_FLOAT_EQ(v.x(), 0.5f);
}

TEST(ApproachLimiter, NonFiniteCommandBecomesASafeOne) {
  const Rig rig(LaserModel::urg04lx());
  SegmentWorld w;
  w.add_box(-1, -1, 1, 1);
  const Eigen::Vector2f v = rig.run(w, {NAN, 0.2f});
  EXPECT_TRUE(v.allFinite());
  EXPECT_NEAR(v.norm(), 0.0f, 1e-3);
}

TEST(ApproachLimiter, RefusesBadParameters) {
  ApproachLimiter l;
  const BeamGeometry g = BeamGeometry::of(uniform_scan(LaserModel::urg04lx(), 1000));
  ApproachParams p;
  p.stop_distance_m = 0.0f;
  EXPECT_EQ(l.configure(p, g), Status::kInvalidArgument);
  EXPECT_FALSE(l.enabled());
  p = {};
  p.gain = NAN;
  EXPECT_EQ(l.configure(p, g), Status::kInvalidArgument);
  p = {};
  p.gain = 50.0f;
  EXPECT_EQ(l.configure(p, g), Status::kInvalidArgument);
  EXPECT_EQ(l.configure(ApproachParams{}, g), Status::kOk);
  EXPECT_TRUE(l.enabled());
}

// Property: in random rooms with random clutter and commands, with every return beyond the
// stop distance, the output never closes on a return beyond its bound (a zeroed command
// included), and is never faster than the input.
TEST(ApproachLimiterProperty, NoBoundIsBrokenOutsideTheStopDistance) {
  for (const LaserModel& m : {LaserModel::urg04lx(), LaserModel::utm30lx()}) {
    const Rig rig(m);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int bounded = 0;
    for (int trial = 0; trial < 400; ++trial) {
      SegmentWorld w;
      w.add_box(-0.5 - 2 * std::fabs(u(rng)), -0.5 - 2 * std::fabs(u(rng)), 0.5 + 2 * std::fabs(u(rng)),
                0.5 + 2 * std::fabs(u(rng)));
      for (int k = 0; k < 3; ++k) {
        const double cx = 1.5 * u(rng), cy = 1.5 * u(rng);
        if (std::hypot(cx, cy) < 0.75) continue;
        w.add(cx, cy, cx + 0.4 * u(rng), cy + 0.4 * u(rng));
      }
      if (w.clearance(0, 0) < 0.42) continue;
      const LaserScan s = w.scan(m, 0, 0, 0);
      Eigen::Vector2f v{static_cast<float>(0.6 * u(rng)), static_cast<float>(0.6 * u(rng))};
      const float speed_in = v.norm();
      const ApproachResult r = rig.limiter.limit(s, *rig.directions, v);
      EXPECT_LE(worst_excess(s, rig.params, v), 0.004) << "trial " << trial;
      EXPECT_LE(v.norm(), speed_in + 0.003f) << "trial " << trial;  // beyond stop: never faster
      if (r.cuts > 0) ++bounded;
    }
    EXPECT_GT(bounded, 50);  // the property was put to work, not passed vacuously
  }
}

}  // namespace
}  // namespace kestrel::exploration
