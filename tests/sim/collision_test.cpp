// Vehicle-world contacts with libccd: touching, near misses, inside, heights and tilt.
#include <gtest/gtest.h>

#include <cmath>

#include "kestrel/sim/collision_checker.hpp"
#include "kestrel/sim/world_parser.hpp"

namespace kestrel::sim {
namespace {

struct Fixture {
  World world;
  SegmentGrid grid;
  CollisionChecker checker;
  explicit Fixture(const char* text, double radius = 0.27, double height = 0.12)
      : world(parse_world(text, "c").world), grid(world.segments(), 1.0), checker(world, grid, radius, height) {}
};

VehicleState at(double x, double y, double z, double roll = 0) {
  VehicleState s;
  s.stamp = TimeUs{1234};
  s.position_m = {x, y, z};
  s.roll_rad = roll;
  return s;
}

// Wall along x = 2 (0.1 m thick: its face at x = 1.95); body radius 0.27 m.
constexpr const char* kWall = "start 0 0 1 0\nwall_thickness 0.1\nwall 2 -5 2 5\n";

TEST(Collision, TouchingCountsAndANearMissDoesNot) {
  Fixture f(kWall);
  Contact c;
  EXPECT_TRUE(f.checker.check(at(1.95 - 0.27 + 0.002, 0, 1), c));  // 2 mm overlap
  EXPECT_EQ(c.piece, 0);
  EXPECT_EQ(c.line, 3);
  EXPECT_EQ(c.stamp.us, 1234);
  EXPECT_NEAR(c.position_m.x(), 1.95, 0.01);
  EXPECT_NEAR(c.depth_m, 0.002, 0.001);
  EXPECT_FALSE(f.checker.check(at(1.95 - 0.27 - 0.01, 0, 1), c));  // 1 cm gap
  EXPECT_FALSE(f.checker.check(at(0, 0, 1), c));
  // Beyond the wall's end (y = 5, plus half a thickness): a miss.
  EXPECT_FALSE(f.checker.check(at(2, 5.05 + 0.27 + 0.01, 1), c));
  EXPECT_TRUE(f.checker.check(at(2, 5.05 + 0.27 - 0.01, 1), c));
}

TEST(Collision, TheCeilingIsAContactAndTheOpenSkyIsNot) {
  // Ceiling at 2.6 m: the body's top (0.06 m above its centre when level) meets it at 2.54 m;
  // tilted, its rim rises (0.27 m * sin 0.3 = 8 cm).
  Fixture f("start 0 0 1 0\nceiling 2.6\nwall 2 -5 2 5\n");
  Contact c;
  EXPECT_FALSE(f.checker.check(at(0, 0, 2.5), c));
  EXPECT_TRUE(f.checker.check(at(0, 0, 2.55), c));
  EXPECT_EQ(c.piece, kCeilingPiece);
  EXPECT_NEAR(c.position_m.z(), 2.6, 1e-9);
  EXPECT_NEAR(c.depth_m, 0.01, 1e-6);
  EXPECT_TRUE(f.checker.check(at(0, 0, 2.5, 0.3), c));
  EXPECT_TRUE(f.checker.check(at(0, 0, 1e4), c));  // far above: still the ceiling
  // Without a ceiling (open above) climbing over the walls touches nothing.
  Fixture open("start 0 0 1 0\nwall 2 -5 2 5\n");
  EXPECT_FALSE(open.checker.check(at(2, 0, 10), c));
}

TEST(Collision, InsideAnObstacleCounts) {
  Fixture f("start 0 0 1 0\nbox 5 5 3 3\n");
  Contact c;
  EXPECT_TRUE(f.checker.check(at(5, 5, 1), c));
  EXPECT_EQ(c.piece, 0);
  EXPECT_GT(c.depth_m, 0.5);
}

TEST(Collision, HeightRangesAreRespected) {
  // A desk 0.75 m high: the body (0.12 m tall) clears it at 1 m and hits it at 0.8 m.
  Fixture f("start 0 0 1 0\nbox 0 0 1 1 z=0:0.75\n");
  Contact c;
  EXPECT_FALSE(f.checker.check(at(0, 0, 1.0), c));
  EXPECT_TRUE(f.checker.check(at(0, 0, 0.8), c));
  // A hanging cabinet (1.4 - 2.2 m) is passed underneath at 1 m.
  Fixture g("start 0 0 1 0\nbox 0 0 1 1 z=1.4:2.2\n");
  EXPECT_FALSE(g.checker.check(at(0, 0, 1.0), c));
  EXPECT_TRUE(g.checker.check(at(0, 0, 1.4), c));
}

TEST(Collision, TiltMovesTheRotorDisc) {
  // Level at 0.9 m above a 0.75 m desk the body clears it (bottom at 0.84 m); rolled by
  // 0.3 rad the disc's low rim dips to 0.9 - 0.27 sin(0.3) - 0.06 cos(0.3) = 0.763 m... still
  // clear, and at 0.85 m it is not.
  Fixture f("start 0 0 1 0\nbox 0 0 2 2 z=0:0.75\n");
  Contact c;
  EXPECT_FALSE(f.checker.check(at(0.5, 0, 0.9, 0.0), c));
  EXPECT_FALSE(f.checker.check(at(0.5, 0, 0.9, 0.3), c));
  EXPECT_FALSE(f.checker.check(at(0.5, 0, 0.84, 0.0), c));
  EXPECT_TRUE(f.checker.check(at(0.5, 0, 0.84, 0.3), c));
}

TEST(Collision, BroadPhaseTestsOnlyNearbyPieces) {
  std::string text = "start 0 0 1 0\n";
  for (int i = 0; i < 50; ++i) text += "box " + std::to_string(i * 3) + " 10 1 1\n";
  Fixture f(text.c_str());
  Contact c;
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(f.checker.check(at(i * 1.5, 0, 1), c));
  EXPECT_EQ(f.checker.pieces_tested(), 0u);
  EXPECT_TRUE(f.checker.check(at(30, 10, 1), c));
  EXPECT_LE(f.checker.pieces_tested(), 3u);
}

}  // namespace
}  // namespace kestrel::sim
