#include <gtest/gtest.h>

#include "kestrel/sim/world_parser.hpp"

namespace kestrel::sim {
namespace {

WorldParseResult parse(const char* text) { return parse_world(text, "t.world"); }

TEST(WorldParser, ParsesEveryPrimitive) {
  const auto r = parse(
      "# a comment\n"
      "name lab\n"
      "start 1 2 0.5 90\n"
      "wall_height 3\n"
      "ceiling 3.1\n"
      "wall 0 0 10 0   # trailing comment\n"
      "wall 0 5 10 5 glass\n"
      "wall 0 0 0 5 z=0:1 railing=0.25\n"
      "box 5 2.5 2 1 yaw=90 z=0:0.75\n"
      "pillar 8 2 0.3\n"
      "poly 1 1 2 1 1.5 2\n"
      "room a 0 0 10 0 10 5 0 5\n");
  ASSERT_TRUE(r.ok) << r.error;
  const World& w = r.world;
  EXPECT_EQ(w.name, "lab");
  EXPECT_DOUBLE_EQ(w.start.x, 1);
  EXPECT_NEAR(w.start.yaw_rad, 1.5707963, 1e-6);
  EXPECT_DOUBLE_EQ(w.ceiling_m, 3.1);
  ASSERT_EQ(w.walls.size(), 3u);
  EXPECT_DOUBLE_EQ(w.walls[0].z_max, 3.0);  // wall_height applies
  EXPECT_EQ(w.walls[1].material, Material::kGlass);
  EXPECT_EQ(w.walls[2].material, Material::kRailing);
  EXPECT_DOUBLE_EQ(w.walls[2].return_probability, 0.25);
  EXPECT_DOUBLE_EQ(w.walls[2].z_max, 1.0);
  ASSERT_EQ(w.obstacles.size(), 3u);
  // The box turned by 90 degrees spans 1 m in x and 2 m in y.
  double minx = 1e9, maxx = -1e9, miny = 1e9, maxy = -1e9;
  for (const auto& p : w.obstacles[0].polygon) {
    minx = std::min(minx, p.x());
    maxx = std::max(maxx, p.x());
    miny = std::min(miny, p.y());
    maxy = std::max(maxy, p.y());
  }
  EXPECT_NEAR(maxx - minx, 1.0, 1e-9);
  EXPECT_NEAR(maxy - miny, 2.0, 1e-9);
  EXPECT_EQ(w.obstacles[1].polygon.size(), 16u);
  EXPECT_EQ(w.obstacles[2].line, 11);
  ASSERT_EQ(w.rooms.size(), 1u);
  EXPECT_EQ(w.room_at(5, 2), 0);
  EXPECT_EQ(w.room_at(11, 2), -1);
  // Segments: 3 walls + 4 + 16 + 3 obstacle edges, pieces numbered walls first.
  const auto segs = w.segments();
  EXPECT_EQ(segs.size(), 3u + 4 + 16 + 3);
  EXPECT_EQ(segs.back().piece, 5);
}

TEST(WorldParser, ClockwisePolygonsAreReordered) {
  const auto r = parse("start 0 0 0 0\npoly 0 0 0 1 1 1 1 0\n");
  ASSERT_TRUE(r.ok) << r.error;
  const auto& p = r.world.obstacles[0].polygon;
  const double area2 = (p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x();
  EXPECT_GT(area2, 0);
}

struct BadCase {
  const char* text;
  const char* expected;  // substring of the error, which always starts with t.world:LINE:
};

TEST(WorldParser, ErrorsNameTheLineAndTheReason) {
  const BadCase cases[] = {
      {"start 0 0 0 0\nwall 0 0 1\n", "t.world:2: wall needs 4 numbers"},
      {"start 0 0 0 0\nwall 0 0 1 x\n", "t.world:2: wall: 'x' is not a number"},
      {"start 0 0 0 0\n\n# c\nfloor 1\n", "t.world:4: unknown keyword 'floor'"},
      {"start 0 0 0 0\nwall 0 0 1 1 z=2:1\n", "t.world:2: z range"},
      {"start 0 0 0 0\nwall 0 0 1 1 railing=1.5\n", "t.world:2: railing=P needs a probability"},
      {"start 0 0 0 0\nwall 0 0 1 1 glass shiny\n", "t.world:2: unknown option 'shiny'"},
      {"start 0 0 0 0\nwall 1 1 1 1\n", "t.world:2: wall has zero length"},
      {"start 0 0 0 0\npoly 0 0 2 0 1 1 2 2 0 2\n", "t.world:2: poly is not a convex polygon"},
      {"start 0 0 0 0\npoly 0 0 1 0 1\n", "t.world:2: poly needs at least 3 points"},
      {"start 0 0 0 0\nbox 0 0 -1 1\n", "t.world:2: box sizes must be positive"},
      {"start 0 0 0 0\npillar 0 0 0\n", "t.world:2: pillar radius must be positive"},
      {"start 0 0\nwall 0 0 1 1\n", "t.world:1: start needs 4 numbers"},
      {"start 0 0 -1 0\nwall 0 0 1 1\n", "t.world:1: start height"},
      {"wall 0 0 1 1\n", "no 'start"},
      {"start 0 0 0 0\n", "no walls or obstacles"},
      {"start 0 0 0 0\nroom r 0 0 1 0\nwall 0 0 1 1\n", "t.world:2: room needs a NAME and at least 3 points"},
      {"start 0 0 0 0\nwall 0 0 1 nan\n", "t.world:2: wall: 'nan' is not a number"},
      {"start 0 0 0 0\nwall 0 0 1 1\nroom a 0 0 1 0 1 1\nroom a 0 0 2 0 2 2\n",
       "t.world:4: room: the name 'a' is already used"},
      {"start 0 0 0 0\nwall_height 0\nwall 0 0 1 1\n", "t.world:2: wall_height must be positive"},
  };
  for (const BadCase& c : cases) {
    const auto r = parse(c.text);
    EXPECT_FALSE(r.ok) << c.text;
    EXPECT_NE(r.error.find(c.expected), std::string::npos) << "got: " << r.error << "\nwanted: " << c.expected;
  }
}

TEST(WorldParser, MissingFileIsAnErrorNamingThePath) {
  const auto r = load_world_file("/nonexistent/dir/x.world");
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("/nonexistent/dir/x.world"), std::string::npos);
}

}  // namespace
}  // namespace kestrel::sim
