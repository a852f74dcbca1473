#include <gtest/gtest.h>

#include <cmath>

#include "kestrel/sim/builtin_worlds.hpp"
#include "kestrel/sim/free_space_map.hpp"

namespace kestrel::sim {
namespace {

TEST(BuiltinWorlds, AllFiveParseWithRoomsAndAReachableStart) {
  ASSERT_EQ(builtin_world_names().size(), 5u);
  for (std::string_view name : builtin_world_names()) {
    const auto r = load_builtin_world(name);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.world.name, name);
    EXPECT_FALSE(r.world.rooms.empty()) << name;
    EXPECT_GE(r.world.room_at(r.world.start.x, r.world.start.y), 0) << name;
    const FreeSpaceMap fs(r.world);
    EXPECT_GT(fs.reachable_area_m2(), 50.0) << name;
  }
}

TEST(BuiltinWorlds, GtBuildingsInnerRoomIsTheRoomInsideIt) {
  // The inner room lies inside the north-east room: a point in it is in the inner room.
  const auto r = load_builtin_world("gt-building");
  ASSERT_TRUE(r.ok) << r.error;
  const World& w = r.world;
  const int inner = w.room_at(18.0, 13.0);
  ASSERT_GE(inner, 0);
  EXPECT_EQ(w.rooms[static_cast<std::size_t>(inner)].name, "inner");
  const int outer = w.room_at(22.5, 14.0);
  ASSERT_GE(outer, 0);
  EXPECT_EQ(w.rooms[static_cast<std::size_t>(outer)].name, "north-east");
}

TEST(BuiltinWorlds, UnknownNameListsTheKnownOnes) {
  const auto r = load_world("nowhere");
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("unknown world 'nowhere'"), std::string::npos);
  EXPECT_NE(r.error.find("iarc-arena"), std::string::npos);
}

TEST(BuiltinWorlds, ArenaIsAbout30By15WithFiveRooms) {
  const auto r = load_builtin_world("iarc-arena");
  ASSERT_TRUE(r.ok);
  const Bounds2 b = r.world.bounds();
  EXPECT_NEAR(b.max.x() - b.min.x(), 30, 1);
  EXPECT_NEAR(b.max.y() - b.min.y(), 15, 1);
  EXPECT_EQ(r.world.rooms.size(), 5u);  // hallway + 4 rooms
}

TEST(BuiltinWorlds, GtInnerRoomIsReachableOnlyThroughTheNarrowGap) {
  auto r = load_builtin_world("gt-building");
  ASSERT_TRUE(r.ok);
  const FreeSpaceMap fs(r.world);
  int ix = 0, iy = 0;
  fs.cell_of(18.0, 14.0, ix, iy);  // inside the inner room
  EXPECT_TRUE(fs.reachable(ix, iy));
  // The gap in the inner room's west wall is between 0.9 and 1.0 m.
  double gap = -1;
  for (std::size_t i = 0; i < r.world.walls.size(); ++i)
    for (std::size_t j = 0; j < r.world.walls.size(); ++j) {
      const Wall& a = r.world.walls[i];
      const Wall& b = r.world.walls[j];
      if (a.a.x() == 16 && a.b.x() == 16 && b.a.x() == 16 && b.b.x() == 16 && a.b.y() > 13 && b.a.y() < 13)
        gap = a.b.y() - b.a.y();
    }
  EXPECT_GE(gap, 0.9);
  EXPECT_LE(gap, 1.0);
  // Close the gap: the inner room is no longer reachable.
  r.world.walls.push_back({{16, 12.4}, {16, 13.6}, 0, 2.7, Material::kOpaque, 1, 0});
  const FreeSpaceMap closed(r.world);
  EXPECT_FALSE(closed.reachable(ix, iy));
  EXPECT_LT(closed.reachable_area_m2(), fs.reachable_area_m2() - 15);
}

TEST(BuiltinWorlds, HallwayFreeAreaMatchesItsSize) {
  const auto r = load_builtin_world("hallway");
  ASSERT_TRUE(r.ok);
  const FreeSpaceMap fs(r.world, 0.1);
  // 60 x 2.4 m minus the cells the walls occupy (about one cell on each side).
  EXPECT_NEAR(fs.reachable_area_m2(), 60 * 2.4, 60 * 0.25);
}

TEST(BuiltinWorlds, LobbyWallsAreMostlyBeyondUrgRange) {
  const auto r = load_builtin_world("lobby");
  ASSERT_TRUE(r.ok);
  const Bounds2 b = r.world.bounds();
  EXPECT_GT(b.max.x() - b.min.x(), 8 * 2);
  EXPECT_GT(b.max.y() - b.min.y(), 8 * 2);
}

}  // namespace
}  // namespace kestrel::sim
