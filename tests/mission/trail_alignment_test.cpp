// find_trail_offset (trail_alignment.hpp): the trail ahead laid back onto the scan's free space.
#include "kestrel/mission/trail_alignment.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "synthetic_world.hpp"

namespace kestrel::mission {
namespace {

using test::LaserModel;
using test::SegmentWorld;

// gt-building's corridor (test::corridor_with_a_door). The vehicle is held 0.45 m off the
// corridor's north wall, west of the door: the trail it follows was drawn where the estimate
// stood 0.8 m further east than now, so it runs north through the wall 0.2 m beside the door's
// jamb (gt-building seed 59: 0.12 m), not through it.
struct StalledBesideADoor {
  SegmentWorld world = test::corridor_with_a_door();
  Pose2 at{4.6f, 8.55f, static_cast<float>(M_PI / 2)};
  ScanFreeSpace free_space;
  StalledBesideADoor() {
    EXPECT_EQ(free_space.build(world.scan(LaserModel::urg04lx(), at.x, at.y, at.theta), at, 0.3f, 0.5f), Status::kOk);
  }
};

constexpr std::array<Point2, 4> kTrailThroughTheWall{{{4.8f, 8.9f}, {4.8f, 9.3f}, {4.8f, 9.7f}, {4.7f, 10.1f}}};

TEST(TrailAlignment, MovesATrailThroughTheWallIntoTheDoorBesideIt) {
  const StalledBesideADoor s;
  Point2 offset{0, 0};
  ASSERT_TRUE(find_trail_offset(s.free_space, kTrailThroughTheWall, 0.8f, {}, 0.45f, offset));
  // East into the door, towards its middle (x 5.6), not back into the corridor.
  EXPECT_GE(offset.x, 0.5f);
  EXPECT_LE(offset.x, 0.8f);
  EXPECT_NEAR(offset.y, 0.0f, 0.201f);
  // Free, but for the last, which the wall hides from where the vehicle is, moved or not.
  for (std::size_t i = 0; i + 1 < kTrailThroughTheWall.size(); ++i) {
    const Point2 b = kTrailThroughTheWall[i];
    const ScanFreeSpace::Cell moved = s.free_space.cell_of({b.x + offset.x, b.y + offset.y});
    EXPECT_NE(s.free_space.at(moved), ScanFreeSpace::Clearance::kNotFree) << i;
  }
  // Allowed only 0.2 m, nothing is better than the trail as it lies.
  EXPECT_FALSE(find_trail_offset(s.free_space, kTrailThroughTheWall, 0.2f, {}, 0.45f, offset));
}

TEST(TrailAlignment, LeavesATrailThatLiesInFreeSpace) {
  const StalledBesideADoor s;
  constexpr std::array<Point2, 3> through_the_door{{{5.6f, 8.6f}, {5.6f, 9.0f}, {5.6f, 9.4f}}};
  Point2 offset{9, 9};
  EXPECT_FALSE(find_trail_offset(s.free_space, through_the_door, 0.8f, {}, 0.45f, offset));
  EXPECT_EQ(offset.x, 9.0f);  // untouched
  EXPECT_FALSE(find_trail_offset(s.free_space, {}, 0.8f, {}, 0.45f, offset));
  EXPECT_FALSE(find_trail_offset(s.free_space, kTrailThroughTheWall, 0.0f, {}, 0.45f, offset));
}

// An operator's box across the door (glass: the laser sees through it, the vehicle must not):
// the trail is not moved into it.
TEST(TrailAlignment, NeverMovesTheTrailIntoAKeepOutBox) {
  const StalledBesideADoor s;
  const std::array<KeepOut, 1> glass{{{5.0f, 8.8f, 6.2f, 10.5f}}};
  Point2 offset{0, 0};
  EXPECT_FALSE(find_trail_offset(s.free_space, kTrailThroughTheWall, 0.8f, glass, 0.45f, offset));
}

}  // namespace
}  // namespace kestrel::mission
