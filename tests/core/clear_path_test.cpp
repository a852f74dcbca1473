// straight_path_clear (clear_path.hpp): whether a scan vouches for a straight way.
#include "kestrel/core/clear_path.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic_world.hpp"

namespace kestrel {
namespace {

using test::LaserModel;
using test::corridor_with_a_door;
using test::SegmentWorld;

constexpr float kClearance = 0.45f;

TEST(StraightPathClear, AlongTheCorridorIsClearAndThroughItsWallIsNot) {
  const SegmentWorld w = corridor_with_a_door();
  // Held 0.43 m off the north wall, west of the door, facing west: home is 2.6 m down the corridor.
  const Pose2 at{4.1f, 8.57f, static_cast<float>(M_PI)};
  const LaserScan scan = w.scan(LaserModel::urg04lx(), at.x, at.y, at.theta);
  EXPECT_TRUE(straight_path_clear(scan, at, {1.5f, 8.0f}, kClearance));
  // Through the wall into the room, or along it closer than the clearance: blocked.
  EXPECT_FALSE(straight_path_clear(scan, at, {3.0f, 9.6f}, kClearance));
  EXPECT_FALSE(straight_path_clear(scan, at, {1.5f, 8.7f}, kClearance));
  // Into the end wall's clearance.
  EXPECT_FALSE(straight_path_clear(scan, at, {0.3f, 8.0f}, kClearance));
}

TEST(StraightPathClear, ThroughTheDoorIsClearOnlyWithRoomBesideTheJambs) {
  const SegmentWorld w = corridor_with_a_door();
  const Pose2 at{5.6f, 7.6f, static_cast<float>(M_PI / 2)};  // below the door, facing north
  const LaserScan scan = w.scan(LaserModel::urg04lx(), at.x, at.y, at.theta);
  EXPECT_TRUE(straight_path_clear(scan, at, {5.6f, 10.5f}, kClearance));      // straight through its middle
  EXPECT_FALSE(straight_path_clear(scan, at, {5.6f, 10.5f}, 0.65f));           // wider than the half door
  EXPECT_FALSE(straight_path_clear(scan, at, {4.4f, 10.5f}, kClearance));      // across the west jamb
}

// The returns beside the start are left behind when the path leads away from them: a vehicle
// held inside the clearance of a wall may still leave it.
TEST(StraightPathClear, ReturnsThePathLeavesBehindDoNotBlockIt) {
  const SegmentWorld w = corridor_with_a_door();
  const Pose2 at{3.0f, 8.7f, 0.0f};  // 0.3 m off the north wall, facing east along it
  const LaserScan scan = w.scan(LaserModel::urg04lx(), at.x, at.y, at.theta);
  EXPECT_TRUE(straight_path_clear(scan, at, {4.0f, 7.9f}, 0.4f));   // away from it, aslant
  // Along it, the wall further on is as near as the clearance does not allow: blocked.
  EXPECT_FALSE(straight_path_clear(scan, at, {4.0f, 8.7f}, 0.4f));
  EXPECT_FALSE(straight_path_clear(scan, at, {4.0f, 7.4f}, 0.4f));  // into the south wall's clearance
}

// Where the scan cannot vouch for the way, it is not clear.
TEST(StraightPathClear, NotClearWhereTheScanSaysNothing) {
  const SegmentWorld w = corridor_with_a_door();
  const Pose2 at{4.0f, 8.0f, static_cast<float>(M_PI)};  // facing west
  const LaserScan urg = w.scan(LaserModel::urg04lx(), at.x, at.y, at.theta);
  // East is in the URG-04LX's 120 degree blind arc, though the corridor is open there.
  EXPECT_FALSE(straight_path_clear(urg, at, {7.0f, 8.0f}, kClearance));
  // Beyond the 4 m range less the clearance: a beam with no return proves nothing that far.
  SegmentWorld open;
  open.add(-20, -20, -20, 20);
  const LaserScan far = open.scan(LaserModel::urg04lx(), 0, 0, 0);
  EXPECT_TRUE(straight_path_clear(far, {0, 0, 0}, {3.5f, 0.0f}, kClearance));
  EXPECT_FALSE(straight_path_clear(far, {0, 0, 0}, {3.6f, 0.0f}, kClearance));
  // The corridor's edge directions must be in the field of view too: a target just inside
  // the fan's edge is not enough.
  const float edge = static_cast<float>(LaserModel::urg04lx().fov_rad / 2);
  EXPECT_FALSE(
      straight_path_clear(far, {0, 0, 0}, {2.0f * std::cos(edge - 0.05f), 2.0f * std::sin(edge - 0.05f)}, kClearance));
  EXPECT_TRUE(
      straight_path_clear(far, {0, 0, 0}, {2.0f * std::cos(edge - 0.3f), 2.0f * std::sin(edge - 0.3f)}, kClearance));
  // A scan of nothing but dropouts vouches for nothing; bad inputs are never clear.
  LaserScan codes = urg;
  for (uint16_t i = 0; i < codes.beam_count; ++i) codes.range_mm[i] = range_code::kDropout;
  EXPECT_FALSE(straight_path_clear(codes, at, {1.5f, 8.0f}, kClearance));
  EXPECT_FALSE(straight_path_clear(urg, at, {NAN, 8.0f}, kClearance));
  EXPECT_FALSE(straight_path_clear(urg, {NAN, 8.0f, 0.0f}, {1.5f, 8.0f}, kClearance));
  EXPECT_FALSE(straight_path_clear(urg, at, {1.5f, 8.0f}, 0.0f));
  EXPECT_FALSE(straight_path_clear(urg, at, {1.5f, 8.0f}, NAN));
  LaserScan empty;
  EXPECT_FALSE(straight_path_clear(empty, at, {1.5f, 8.0f}, kClearance));
  LaserScan no_range = urg;
  no_range.max_range_mm = 0;
  EXPECT_FALSE(straight_path_clear(no_range, at, {1.5f, 8.0f}, kClearance));
  // Regression (audit): a fan claiming more beams than a scan holds was read past its array.
  LaserScan too_many = urg;
  too_many.beam_count = kMaxBeams + 1;
  EXPECT_FALSE(straight_path_clear(too_many, at, {1.5f, 8.0f}, kClearance));
  LaserScan too_fine = urg;
  too_fine.angle_step_rad = 1e-12f;
  EXPECT_FALSE(straight_path_clear(too_fine, at, {1.5f, 8.0f}, kClearance));
}

// What every module asks of a fan before it indexes beams by angle (messages.hpp).
TEST(LaserScanFan, WellFormedOnlyWithinTheArrayOneTurnAndARealStep) {
  EXPECT_TRUE(fan_well_formed(682, -2.09f, 0.00614f, 4000));   // URG-04LX
  EXPECT_TRUE(fan_well_formed(1081, -2.36f, 0.00436f, 30000));  // UTM-30LX
  EXPECT_TRUE(fan_well_formed(682, 2.09f, -0.00614f, 4000));   // clockwise
  EXPECT_FALSE(fan_well_formed(0, 0.0f, 0.01f, 4000));
  EXPECT_FALSE(fan_well_formed(kMaxBeams + 1, 0.0f, 0.001f, 4000));
  EXPECT_FALSE(fan_well_formed(100, NAN, 0.01f, 4000));
  EXPECT_FALSE(fan_well_formed(100, 0.0f, INFINITY, 4000));
  EXPECT_FALSE(fan_well_formed(100, 0.0f, 0.0f, 4000));
  EXPECT_FALSE(fan_well_formed(100, 0.0f, 0.5f * kMinAngleStepRad, 4000));
  EXPECT_FALSE(fan_well_formed(1000, 0.0f, 0.01f, 4000));  // ten radians: it wraps onto itself
  EXPECT_FALSE(fan_well_formed(100, 0.0f, 0.01f, kMinValidRangeMm - 1));
}

// The beams the path runs along must have seen it: paper 000's mirror deflects the UTM-30LX's
// first 20 beams down (kDeflected), and a shortcut home along them crossed a wall (gt-building,
// seed 29: 18.7 m from the north-east room through the corridor's wall). Outside the path's own
// directions a code blocks nothing.
TEST(StraightPathClear, NotClearAlongBeamsThatSaidNothing) {
  SegmentWorld open;
  open.add(-40, -40, -40, 40);  // beyond the 30 m range: every beam reads kNoReturn
  LaserScan scan = open.scan(LaserModel::utm30lx(), 0, 0, 0);
  const auto along_beam = [&scan](std::size_t i, float r) {
    const float a = scan.angle_of(i);
    return Point2{r * std::cos(a), r * std::sin(a)};
  };
  const Point2 far_in_mirror_arc = along_beam(10, 18.0f);
  const Point2 near_in_mirror_arc = along_beam(18, 6.0f);
  const Point2 beside_mirror_arc = along_beam(60, 18.0f);  // 10 degrees from the arc's edge
  ASSERT_TRUE(straight_path_clear(scan, {0, 0, 0}, far_in_mirror_arc, kClearance));
  ASSERT_TRUE(straight_path_clear(scan, {0, 0, 0}, near_in_mirror_arc, kClearance));
  for (std::size_t i = 0; i < 20; ++i) scan.range_mm[i] = range_code::kDeflected;
  EXPECT_FALSE(straight_path_clear(scan, {0, 0, 0}, far_in_mirror_arc, kClearance));
  EXPECT_FALSE(straight_path_clear(scan, {0, 0, 0}, near_in_mirror_arc, kClearance));
  EXPECT_TRUE(straight_path_clear(scan, {0, 0, 0}, beside_mirror_arc, kClearance));
  // One dropout on the path's bearing: not vouched for; one a few degrees off it: clear.
  scan.range_mm[540] = range_code::kDropout;
  EXPECT_FALSE(straight_path_clear(scan, {0, 0, 0}, along_beam(540, 10.0f), kClearance));
  EXPECT_TRUE(straight_path_clear(scan, {0, 0, 0}, along_beam(560, 10.0f), kClearance));
  scan.range_mm[540] = range_code::kTooNear;
  EXPECT_FALSE(straight_path_clear(scan, {0, 0, 0}, along_beam(540, 10.0f), kClearance));
}

// The beam directions are rotated beam by beam: over the UTM-30LX's 1081 beams they must still
// point where angle_of says (a wall 0.5 m beside the path at the fan's far end is seen there).
TEST(StraightPathClear, TheLastBeamsOfAWideScanPointWhereTheyShould) {
  SegmentWorld w;
  const double a = 2.0;  // rad, near the UTM-30LX's +135 degree edge
  // A short wall across the path's end, 6 m out at bearing a.
  const double cx = 6.0 * std::cos(a), cy = 6.0 * std::sin(a);
  w.add(cx - 0.3 * std::sin(a), cy + 0.3 * std::cos(a), cx + 0.3 * std::sin(a), cy - 0.3 * std::cos(a));
  const LaserScan scan = w.scan(LaserModel::utm30lx(), 0, 0, 0);
  const auto at_range = [a](double r) {
    return Point2{static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a))};
  };
  EXPECT_FALSE(straight_path_clear(scan, {0, 0, 0}, at_range(5.9), 0.2f));  // 0.1 m short of the wall
  EXPECT_TRUE(straight_path_clear(scan, {0, 0, 0}, at_range(5.5), 0.2f));   // 0.5 m short
}

}  // namespace
}  // namespace kestrel
