// ScanFreeSpace (scan_free_space.hpp): where one scan shows free space, on a small grid.
#include "kestrel/core/scan_free_space.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "synthetic_world.hpp"

namespace kestrel {
namespace {

using test::LaserModel;
using test::corridor_with_a_door;
using test::SegmentWorld;

ScanFreeSpace built(const SegmentWorld& w, const Pose2& at, const LaserModel& m = LaserModel::urg04lx()) {
  ScanFreeSpace f;
  EXPECT_EQ(f.build(w.scan(m, at.x, at.y, at.theta), at, 0.3f, 0.5f), Status::kOk);
  return f;
}

bool free(const ScanFreeSpace& f, Point2 p) { return f.at(f.cell_of(p)) != ScanFreeSpace::Clearance::kNotFree; }
bool free_wide(const ScanFreeSpace& f, Point2 p) { return f.at(f.cell_of(p)) == ScanFreeSpace::Clearance::kWide; }

TEST(ScanFreeSpace, FreeWhereRaysPassedClearOfTheReturns) {
  const Pose2 at{4.6f, 8.55f, static_cast<float>(M_PI / 2)};  // beside the door, facing north
  const ScanFreeSpace f = built(corridor_with_a_door(), at);
  EXPECT_TRUE(free(f, {3.0f, 8.0f}));        // the corridor, 1 m from both walls
  EXPECT_TRUE(free_wide(f, {3.0f, 8.0f}));
  EXPECT_TRUE(free(f, {5.6f, 9.6f}));        // through the door, in the room
  EXPECT_FALSE(free(f, {4.6f, 9.2f}));       // behind the wall it faces
  EXPECT_FALSE(free(f, {3.0f, 8.8f}));       // 0.2 m from the wall: within the near clearance
  EXPECT_TRUE(free(f, {3.0f, 8.6f}));        // 0.4 m: clear by the near one...
  EXPECT_FALSE(free_wide(f, {3.0f, 8.6f}));  // ...not by the wide one (a cell is 0.1 m)
  EXPECT_FALSE(free(f, {5.05f, 9.0f}));      // the jamb
  EXPECT_FALSE(free(f, {4.6f + 3.3f, 8.0f}));  // beyond the grid
}

// Behind the vehicle, where the URG-04LX's 240 degrees do not look, and in the directions of
// beams that said nothing, the scan vouches for nothing.
TEST(ScanFreeSpace, UnseenAndSilentDirectionsAreNotFree) {
  const SegmentWorld w = corridor_with_a_door();
  const Pose2 at{3.0f, 8.0f, 0.0f};  // facing east along the corridor
  EXPECT_FALSE(free(built(w, at), {1.5f, 8.0f}));  // straight behind: outside the field of view
  LaserScan scan = w.scan(LaserModel::urg04lx(), at.x, at.y, at.theta);
  ScanFreeSpace f;
  ASSERT_EQ(f.build(scan, at, 0.3f, 0.5f), Status::kOk);
  ASSERT_TRUE(free(f, {4.5f, 8.0f}));
  for (uint16_t i = 321; i <= 361; ++i) scan.range_mm[i] = range_code::kDeflected;  // +-7 degrees ahead
  ASSERT_EQ(f.build(scan, at, 0.3f, 0.5f), Status::kOk);
  EXPECT_FALSE(free(f, {4.5f, 8.0f}));
  EXPECT_TRUE(free(f, {4.0f, 7.6f}));  // beside the silent fan, seen by its neighbours
  // Nothing in range is open space.
  for (uint16_t i = 0; i < scan.beam_count; ++i) scan.range_mm[i] = range_code::kNoReturn;
  ASSERT_EQ(f.build(scan, at, 0.3f, 0.5f), Status::kOk);
  EXPECT_TRUE(free_wide(f, {5.5f, 8.0f}));
}

// GIVEN a round room (radius 2.5 m) centred on a laser that sees all round WHEN drawn at any
// heading THEN its free cells are centred on the laser: the rays do not lean. (A floored Q8 step
// leaned them towards -x and -y, the centroid a tenth of a cell off.)
TEST(ScanFreeSpace, ARoundRoomsFreeSpaceIsCentredOnTheLaser) {
  const Point2 centre{5.0f, -2.0f};
  SegmentWorld room;
  constexpr int kSides = 64;
  for (int k = 0; k < kSides; ++k) {
    const double a0 = 2.0 * M_PI * k / kSides, a1 = 2.0 * M_PI * (k + 1) / kSides;
    room.add(centre.x + 2.5 * std::cos(a0), centre.y + 2.5 * std::sin(a0), centre.x + 2.5 * std::cos(a1),
             centre.y + 2.5 * std::sin(a1));
  }
  const LaserModel all_round{1080, 2.0 * M_PI, 4000};
  for (const float heading : {0.0f, 0.3f, 1.0f, 2.5f, -2.0f}) {
    const ScanFreeSpace f = built(room, {centre.x, centre.y, heading}, all_round);
    constexpr int kLaser = ScanFreeSpace::kSide / 2;  // the laser at this cell's lower-left corner
    double sum_x = 0.0, sum_y = 0.0;
    int n = 0;
    for (int y = 0; y < ScanFreeSpace::kSide; ++y) {
      for (int x = 0; x < ScanFreeSpace::kSide; ++x) {
        if (f.at({x, y}) == ScanFreeSpace::Clearance::kNotFree) continue;
        sum_x += x - kLaser;
        sum_y += y - kLaser;
        ++n;
      }
    }
    ASSERT_GT(n, 1000) << heading;  // pi (2.5 - 0.3)^2 m^2 is about 1,500 cells
    EXPECT_NEAR(sum_x / n + 0.5, 0.0, 0.02) << heading;
    EXPECT_NEAR(sum_y / n + 0.5, 0.0, 0.02) << heading;
  }
}

TEST(ScanFreeSpace, BadInputsLeaveNothingFree) {
  const SegmentWorld w = corridor_with_a_door();
  const Pose2 at{3.0f, 8.0f, 0.0f};
  const LaserScan scan = w.scan(LaserModel::urg04lx(), at.x, at.y, at.theta);
  ScanFreeSpace f;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(f.build(scan, {nan, 8.0f, 0.0f}, 0.3f, 0.5f), Status::kInvalidArgument);
  EXPECT_FALSE(free(f, {4.0f, 8.0f}));
  EXPECT_EQ(f.build(scan, at, 0.0f, 0.5f), Status::kInvalidArgument);
  EXPECT_EQ(f.build(scan, at, 0.5f, 0.3f), Status::kInvalidArgument);  // wide below near
  EXPECT_EQ(f.build(scan, at, 0.3f, 1.5f), Status::kInvalidArgument);
  LaserScan empty = scan;
  empty.beam_count = 0;
  EXPECT_EQ(f.build(empty, at, 0.3f, 0.5f), Status::kInvalidArgument);
  LaserScan flat = scan;
  flat.angle_step_rad = 0.0f;
  EXPECT_EQ(f.build(flat, at, 0.3f, 0.5f), Status::kInvalidArgument);
  EXPECT_FALSE(free(f, {4.0f, 8.0f}));
  EXPECT_FALSE(free(f, {nan, 8.0f}));
}

}  // namespace
}  // namespace kestrel
