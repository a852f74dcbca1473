// The flight home's velocity bound (AutonomyStack, Phase::kReturn): the explorer's approach
// limiter once per scan, the bounded velocity standing between scans, a hold without a recent
// scan or when the limiter cannot bound, and no heap.
#include "kestrel/autonomy/return_velocity_bound.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/exploration/blend_explorer.hpp"
#include "synthetic_world.hpp"

namespace kestrel::autonomy {
namespace {

using exploration::BeamGeometry;
using exploration::BlendExplorer;
using test::LaserModel;
using test::SegmentWorld;
using test::nav_at;

const LaserModel kUrg = LaserModel::urg04lx();
const Duration kPeriod = Duration::from_ms(100);  // the URG-04LX's 10 Hz
const TimeUs kT0 = TimeUs::from_s(10.0);

GuidanceSetpoint velocity(float vx, float vy) {
  GuidanceSetpoint sp;
  sp.mode = GuidanceSetpoint::Mode::kVelocity;
  sp.position_m = {1.0f, 2.0f, 1.0f};
  sp.velocity_mps = {vx, vy, 0.25f};
  sp.heading_rad = 0.3f;
  return sp;
}

class ReturnVelocityBoundTest : public ::testing::Test {
 protected:
  void SetUp() override {
    wall_.add_box(-5, -5, 0.8, 5);  // a wall 0.8 m ahead of the vehicle at the origin, heading 0
    scan_ = wall_.scan(kUrg, 0, 0, 0, kT0);
    ASSERT_EQ(explorer_->configure(exploration::Params{}, BeamGeometry::of(scan_)), Status::kOk);
  }

  SegmentWorld wall_;
  LaserScan scan_;
  std::unique_ptr<BlendExplorer> explorer_ = std::make_unique<BlendExplorer>();
  ReturnVelocityBound bound_;
};

TEST_F(ReturnVelocityBoundTest, BoundsOnAFreshScanAndKeepsThatVelocityUntilTheNext) {
  bool fresh = true;
  GuidanceSetpoint sp = velocity(0.6f, 0.0f);
  ASSERT_EQ(bound_.apply(kT0 + Duration::from_ms(5), kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_, sp),
            Status::kOk);
  EXPECT_FALSE(fresh);
  EXPECT_NEAR(sp.velocity_mps.x(), 0.4f, 0.01f);  // gain * (0.8 - stop distance 0.4)
  EXPECT_NEAR(sp.velocity_mps.y(), 0.0f, 0.01f);
  EXPECT_FLOAT_EQ(sp.velocity_mps.z(), 0.25f);  // only the horizontal velocity is bounded
  EXPECT_FLOAT_EQ(bound_.velocity().x(), sp.velocity_mps.x());
  EXPECT_FLOAT_EQ(bound_.velocity().y(), sp.velocity_mps.y());
  const Eigen::Vector2f bounded = sp.velocity_mps.head<2>();

  // No new scan: the bounded velocity stands whatever the mission now asks, even away from
  // the wall, and the rest of the set-point is the mission's.
  const float raw[][2] = {{0.6f, 0.0f}, {0.3f, 0.5f}, {-0.6f, 0.0f}};
  for (int k = 0; k < 3; ++k) {
    GuidanceSetpoint next = velocity(raw[k][0], raw[k][1]);
    next.heading_rad = 0.1f * static_cast<float>(k);
    ASSERT_EQ(bound_.apply(kT0 + Duration::from_ms(25 * (k + 1)), kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_,
                           next),
              Status::kOk);
    EXPECT_FLOAT_EQ(next.velocity_mps.x(), bounded.x()) << k;
    EXPECT_FLOAT_EQ(next.velocity_mps.y(), bounded.y()) << k;
    EXPECT_FLOAT_EQ(next.velocity_mps.z(), 0.25f) << k;
    EXPECT_FLOAT_EQ(next.heading_rad, 0.1f * static_cast<float>(k)) << k;
    EXPECT_FLOAT_EQ(next.position_m.y(), 2.0f) << k;
    EXPECT_FALSE(fresh);
  }
}

TEST_F(ReturnVelocityBoundTest, UsesEachScanOnceAndANewScanReplacesTheBound) {
  bool fresh = true;
  GuidanceSetpoint sp = velocity(0.6f, 0.0f);
  ASSERT_EQ(bound_.apply(kT0, kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_, sp), Status::kOk);
  ASSERT_NEAR(bound_.velocity().x(), 0.4f, 0.01f);
  // The same scan again, not fresh: the explorer is not asked (a non-finite heading would make
  // it refuse), the stored bound is applied.
  sp = velocity(0.6f, 0.0f);
  EXPECT_EQ(bound_.apply(kT0 + Duration::from_ms(50), kPeriod, scan_, fresh, nav_at(0, 0, NAN), *explorer_, sp),
            Status::kOk);
  EXPECT_NEAR(sp.velocity_mps.x(), 0.4f, 0.01f);

  // A new scan from 0.2 m closer: the wall is 0.6 m ahead, the bound 0.2 m/s replaces 0.4.
  const LaserScan closer = wall_.scan(kUrg, 0.2, 0, 0, kT0 + kPeriod);
  fresh = true;
  sp = velocity(0.6f, 0.0f);
  ASSERT_EQ(bound_.apply(kT0 + kPeriod, kPeriod, closer, fresh, nav_at(0.2f, 0, 0), *explorer_, sp), Status::kOk);
  EXPECT_FALSE(fresh);
  EXPECT_NEAR(sp.velocity_mps.x(), 0.2f, 0.01f);
  EXPECT_NEAR(bound_.velocity().x(), 0.2f, 0.01f);
  const float stored = bound_.velocity().x();
  sp = velocity(0.6f, 0.0f);
  ASSERT_EQ(bound_.apply(kT0 + kPeriod + Duration::from_ms(50), kPeriod, closer, fresh, nav_at(0.2f, 0, 0),
                         *explorer_, sp),
            Status::kOk);
  EXPECT_FLOAT_EQ(sp.velocity_mps.x(), stored);

  // A new scan with nothing within reach ahead: the mission's velocity passes unbounded.
  SegmentWorld far;
  far.add_box(-10, -10, 10, 10);
  const LaserScan open = far.scan(kUrg, 0, 0, 0, kT0 + kPeriod * 2);
  fresh = true;
  sp = velocity(0.6f, 0.0f);
  ASSERT_EQ(bound_.apply(kT0 + kPeriod * 2, kPeriod, open, fresh, nav_at(0, 0, 0), *explorer_, sp), Status::kOk);
  EXPECT_NEAR(sp.velocity_mps.x(), 0.6f, 1e-3f);
  EXPECT_FLOAT_EQ(bound_.velocity().x(), sp.velocity_mps.x());
}

TEST_F(ReturnVelocityBoundTest, HoldsWithoutARecentScan) {
  const Duration limit = kPeriod * ReturnVelocityBound::kScanMaxAgePeriods;
  ASSERT_EQ(ReturnVelocityBound::kScanMaxAgePeriods, 3);
  // Exactly at the age limit the scan is still recent: bounded.
  bool fresh = true;
  GuidanceSetpoint sp = velocity(0.6f, 0.0f);
  EXPECT_EQ(bound_.apply(kT0 + limit, kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_, sp), Status::kOk);
  EXPECT_FALSE(fresh);
  EXPECT_NEAR(sp.velocity_mps.x(), 0.4f, 0.01f);
  const Eigen::Vector2f stored = bound_.velocity();

  // One microsecond older: held, and reported.
  sp = velocity(0.6f, 0.3f);
  EXPECT_EQ(bound_.apply(kT0 + limit + Duration::from_us(1), kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_, sp),
            Status::kRejected);
  EXPECT_FLOAT_EQ(sp.velocity_mps.x(), 0.0f);
  EXPECT_FLOAT_EQ(sp.velocity_mps.y(), 0.0f);
  EXPECT_FLOAT_EQ(sp.velocity_mps.z(), 0.25f);
  EXPECT_FLOAT_EQ(sp.heading_rad, 0.3f);
  EXPECT_TRUE(bound_.velocity() == stored);  // the hold is not stored

  // A stale scan that was never used: held, and the scan stays unused.
  fresh = true;
  sp = velocity(0.6f, 0.0f);
  EXPECT_EQ(bound_.apply(kT0 + kPeriod * 10, kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_, sp),
            Status::kRejected);
  EXPECT_TRUE(fresh);
  EXPECT_FLOAT_EQ(sp.velocity_mps.head<2>().norm(), 0.0f);

  // No scan yet (beam_count 0), however young its stamp: held.
  ReturnVelocityBound first;
  const LaserScan none;
  for (bool f : {false, true}) {
    fresh = f;
    sp = velocity(0.6f, 0.0f);
    EXPECT_EQ(first.apply(none.stamp + Duration::from_ms(10), kPeriod, none, fresh, nav_at(0, 0, 0), *explorer_, sp),
              Status::kRejected);
    EXPECT_FLOAT_EQ(sp.velocity_mps.head<2>().norm(), 0.0f);
    EXPECT_EQ(fresh, f);
  }
}

// Regression: age was only checked one way. A scan stamped an hour ahead of the guidance
// clock (the laser's clock leapt, or the loop's stepped back) counted as recent for that
// hour, so if the laser then stalled the stored velocity stood for an hour instead of the
// hold after kScanMaxAgePeriods. Pinned: up to one scan period ahead is recent (stamping
// slack), beyond that the flight holds, as for a stale scan, and the scan stays unused.
TEST_F(ReturnVelocityBoundTest, HoldsOnAScanStampedFarAheadOfTheClock) {
  bool fresh = true;
  GuidanceSetpoint sp = velocity(0.6f, 0.0f);
  EXPECT_EQ(bound_.apply(kT0 - kPeriod, kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_, sp), Status::kOk);
  EXPECT_NEAR(sp.velocity_mps.x(), 0.4f, 0.01f);
  for (const Duration ahead : {kPeriod + Duration::from_us(1), Duration::from_s(3600.0)}) {
    fresh = true;
    sp = velocity(0.6f, 0.3f);
    EXPECT_EQ(bound_.apply(kT0 - ahead, kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_, sp), Status::kRejected);
    EXPECT_FLOAT_EQ(sp.velocity_mps.head<2>().norm(), 0.0f);
    EXPECT_FLOAT_EQ(sp.velocity_mps.z(), 0.25f);
    EXPECT_TRUE(fresh);
  }
}

TEST_F(ReturnVelocityBoundTest, HoldsWhenTheExplorerCannotBound) {
  // A non-finite heading: the explorer zeroes the horizontal velocity and says so; that zero
  // stands until the next scan, without being reported again.
  bool fresh = true;
  GuidanceSetpoint sp = velocity(0.6f, 0.2f);
  EXPECT_EQ(bound_.apply(kT0, kPeriod, scan_, fresh, nav_at(0, 0, NAN), *explorer_, sp), Status::kInvalidArgument);
  EXPECT_FALSE(fresh);
  EXPECT_FLOAT_EQ(sp.velocity_mps.x(), 0.0f);
  EXPECT_FLOAT_EQ(sp.velocity_mps.y(), 0.0f);
  EXPECT_FLOAT_EQ(sp.velocity_mps.z(), 0.25f);
  EXPECT_FLOAT_EQ(bound_.velocity().norm(), 0.0f);
  sp = velocity(0.6f, 0.2f);
  EXPECT_EQ(bound_.apply(kT0 + Duration::from_ms(50), kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_, sp),
            Status::kOk);
  EXPECT_FLOAT_EQ(sp.velocity_mps.head<2>().norm(), 0.0f);

  // A scan of another laser: refused the same way.
  const LaserScan other = wall_.scan(LaserModel::utm30lx(), 0, 0, 0, kT0 + kPeriod);
  fresh = true;
  sp = velocity(0.6f, 0.0f);
  EXPECT_EQ(bound_.apply(kT0 + kPeriod, kPeriod, other, fresh, nav_at(0, 0, 0), *explorer_, sp),
            Status::kInvalidArgument);
  EXPECT_FLOAT_EQ(sp.velocity_mps.head<2>().norm(), 0.0f);

  // An unconfigured explorer: refused the same way.
  auto unconfigured = std::make_unique<BlendExplorer>();
  ReturnVelocityBound other_bound;
  fresh = true;
  sp = velocity(0.6f, 0.0f);
  EXPECT_EQ(other_bound.apply(kT0, kPeriod, scan_, fresh, nav_at(0, 0, 0), *unconfigured, sp),
            Status::kInvalidArgument);
  EXPECT_FLOAT_EQ(sp.velocity_mps.head<2>().norm(), 0.0f);
}

TEST_F(ReturnVelocityBoundTest, LeavesAPositionSetpointAlone) {
  // In kPosition mode velocity_mps is the controller's feed-forward, not a command to bound:
  // refused, nothing touched, the scan left for the next velocity set-point.
  bool fresh = true;
  GuidanceSetpoint first = velocity(0.6f, 0.0f);
  ASSERT_EQ(bound_.apply(kT0, kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_, first), Status::kOk);
  const Eigen::Vector2f stored = bound_.velocity();
  const TimeUs stale = kT0 + kPeriod * 10;
  for (const TimeUs now : {kT0, stale}) {
    for (bool f : {false, true}) {
      fresh = f;
      GuidanceSetpoint sp = velocity(0.6f, 0.2f);
      sp.mode = GuidanceSetpoint::Mode::kPosition;
      EXPECT_EQ(bound_.apply(now, kPeriod, scan_, fresh, nav_at(0, 0, 0), *explorer_, sp), Status::kUnsupported);
      EXPECT_EQ(sp.mode, GuidanceSetpoint::Mode::kPosition);
      EXPECT_FLOAT_EQ(sp.velocity_mps.x(), 0.6f);
      EXPECT_FLOAT_EQ(sp.velocity_mps.y(), 0.2f);
      EXPECT_FLOAT_EQ(sp.velocity_mps.z(), 0.25f);
      EXPECT_FLOAT_EQ(sp.position_m.x(), 1.0f);
      EXPECT_EQ(fresh, f);
      EXPECT_TRUE(bound_.velocity() == stored);
    }
  }
}

TEST_F(ReturnVelocityBoundTest, NeverAllocates) {
  const LaserScan closer = wall_.scan(kUrg, 0.2, 0, 0, kT0 + kPeriod);
  const LaserScan none;
  const NavState here = nav_at(0, 0, 0), there = nav_at(0.2f, 0, 0), lost = nav_at(0, 0, NAN);
  Status last[6] = {};
  float vx[6] = {};
  uint64_t allocations = 0;
  {
    alloc_guard::Scope guard;
    bool fresh = true;
    GuidanceSetpoint sp = velocity(0.6f, 0.0f);
    last[0] = bound_.apply(kT0, kPeriod, scan_, fresh, here, *explorer_, sp);  // bounded
    vx[0] = sp.velocity_mps.x();
    sp = velocity(0.6f, 0.0f);
    last[1] = bound_.apply(kT0 + Duration::from_ms(50), kPeriod, scan_, fresh, here, *explorer_, sp);  // stands
    vx[1] = sp.velocity_mps.x();
    fresh = true;
    sp = velocity(0.6f, 0.0f);
    last[2] = bound_.apply(kT0 + kPeriod, kPeriod, closer, fresh, there, *explorer_, sp);  // a new bound
    vx[2] = sp.velocity_mps.x();
    sp = velocity(0.6f, 0.0f);
    last[3] = bound_.apply(kT0 + kPeriod * 5, kPeriod, closer, fresh, there, *explorer_, sp);  // stale: hold
    vx[3] = sp.velocity_mps.x();
    fresh = true;
    sp = velocity(0.6f, 0.0f);
    last[4] = bound_.apply(kT0 + kPeriod, kPeriod, closer, fresh, lost, *explorer_, sp);  // refused
    vx[4] = sp.velocity_mps.x();
    sp = velocity(0.6f, 0.0f);
    last[5] = bound_.apply(kT0, kPeriod, none, fresh, here, *explorer_, sp);  // no scan yet
    vx[5] = sp.velocity_mps.x();
    allocations = guard.allocations();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_TRUE(alloc_guard::active());
  // The calls did the work (the guard watched real calls).
  const Status want[6] = {Status::kOk, Status::kOk, Status::kOk, Status::kRejected, Status::kInvalidArgument,
                          Status::kRejected};
  for (int k = 0; k < 6; ++k) EXPECT_EQ(last[k], want[k]) << k;
  EXPECT_NEAR(vx[0], 0.4f, 0.01f);
  EXPECT_FLOAT_EQ(vx[1], vx[0]);
  EXPECT_NEAR(vx[2], 0.2f, 0.01f);
  EXPECT_FLOAT_EQ(vx[3], 0.0f);
  EXPECT_FLOAT_EQ(vx[4], 0.0f);
  EXPECT_FLOAT_EQ(vx[5], 0.0f);
}

}  // namespace
}  // namespace kestrel::autonomy
