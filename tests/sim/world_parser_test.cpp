#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>

#include "kestrel/sim/free_space_map.hpp"
#include "kestrel/sim/ray_caster.hpp"
#include "kestrel/sim/world_parser.hpp"
#include "text_mutation.hpp"

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
  EXPECT_EQ(r.error, "cannot open '/nonexistent/dir/x.world'");  // the parameter files' words
}

// Regression: a directory opened as a stream and read as empty text.
TEST(WorldParser, ADirectoryIsNotAWorldFile) {
  const auto r = load_world_file(testing::TempDir());
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error, "cannot read '" + testing::TempDir() + "' (is a directory)");
}

// Regression: coordinates were only checked to be finite, so a world with a mistyped 1e12 parsed,
// and building the free-space map over it threw (a vector beyond max_size(), from an int cast of
// an overflowing cell count) instead of the file being refused with its line.
TEST(WorldParser, PointsBeyondTheIndoorExtentAreRejected) {
  const BadCase cases[] = {
      {"start 0 0 0 0\nwall 0 0 1e12 0\n", "t.world:2: wall: point (1e+12, 0) lies outside +-500 m"},
      {"start 0 0 0 0\nwall 0 0 1 0\nwall -501 0 1 0\n", "t.world:3: wall: point"},
      {"start 0 0 0 0\npillar 0 0 1e9\n", "t.world:2: pillar: point"},
      {"start 0 0 0 0\nbox 499 0 4 1\n", "t.world:2: box: point"},
      {"start 0 0 0 0\npoly 0 0 1 0 0 1e300\n", "t.world:2: poly: point"},
      {"start 0 0 0 0\nwall 0 0 1 0\nroom r 0 0 1 0 0 -501\n", "t.world:3: room: point"},
      {"start 0 501 0 0\nwall 0 0 1 0\n", "t.world:1: start: point"},
      {"start 0 0 0 0\nwall_thickness 1e300\nwall 0 0 1 0\n", "t.world:2: wall_thickness must be at most 10 m"},
  };
  for (const BadCase& c : cases) {
    const auto r = parse(c.text);
    EXPECT_FALSE(r.ok) << c.text;
    EXPECT_NE(r.error.find(c.expected), std::string::npos) << "got: " << r.error << "\nwanted: " << c.expected;
  }
  // The corners of the extent are still a world, and the simulator's grids build over it.
  const auto r = parse("start -500 -500 0 0\nwall -500 500 500 -500\nwall_thickness 10\n");
  ASSERT_TRUE(r.ok) << r.error;
  const FreeSpaceMap map(r.world, 1.0);  // 10^6 cells (at the simulator's 0.1 m, 10^8: too slow here)
  EXPECT_GT(map.reachable_cells(), 0u);
}

// Regression: a yaw of 1e308 degrees overflowed to inf radians, the box's corners became NaN, and
// NaN passed the extent and convexity checks (every comparison with NaN is false), so kestrel-sim
// hung rendering the world; a start yaw of 1e308 flew NaN trajectories.
TEST(WorldParser, HugeAnglesAreRejectedWithTheirLine) {
  const BadCase cases[] = {
      {"start 0 0 0 0\nbox 3 3 1 1 yaw=1e308\n", "t.world:2: yaw=1e308 lies outside +-360 deg"},
      {"start 0 0 0 0\nbox 3 3 1 1 yaw=-361\n", "t.world:2: yaw=-361 lies outside +-360 deg"},
      {"start 5 5 0 1e308\nwall 0 0 1 0\n", "t.world:1: start: YAW_DEG 1e308 lies outside +-360 deg"},
      {"start 5 5 1e308 0\nwall 0 0 1 0\n", "t.world:1: start height Z must be at most 500 m"},
      {"start 0 0 0 0\nbox 0 0 1e308 1e308\n", "t.world:2: box: point"},
  };
  for (const BadCase& c : cases) {
    const auto r = parse(c.text);
    EXPECT_FALSE(r.ok) << c.text;
    EXPECT_NE(r.error.find(c.expected), std::string::npos) << "got: " << r.error << "\nwanted: " << c.expected;
  }
  // A full turn either way is still a yaw.
  const auto r = parse("start 0 0 0 -360\nbox 3 3 1 1 yaw=360\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_NEAR(r.world.start.yaw_rad, -2 * std::numbers::pi, 1e-9);
}

TEST(WorldParser, RandomlyMutatedWorldsAreRefusedOrSound) {
  const std::string base =
      "# a comment\n"
      "name lab\n"
      "start 1 2 0.5 90\n"
      "wall_height 3\n"
      "wall_thickness 0.2\n"
      "ceiling 3.1\n"
      "wall 0 0 10 0   # trailing comment\n"
      "wall 0 5 10 5 glass\n"
      "wall 0 0 0 5 z=0:1 railing=0.25\n"
      "box 5 2.5 2 1 yaw=90 z=0:0.75\n"
      "pillar 8 2 0.3\n"
      "poly 1 1 2 1 1.5 2\n"
      "room a 0 0 10 0 10 5 0 5\n";
  ASSERT_TRUE(parse_world(base, "t.world").ok);
  std::mt19937 rng(17);
  const char alphabet[] = "0123456789 .-+e:=#\n\txnaz";
  int errors = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::string text = test::mutate_text(base, alphabet, rng);
    const auto r = parse_world(text, "t.world");
    if (!r.ok) {
      ++errors;
      // "t.world:LINE: reason", LINE within the text (0 for the whole-world checks).
      ASSERT_EQ(r.error.rfind("t.world:", 0), 0u) << r.error;
      const int line = std::atoi(r.error.c_str() + 8);
      const int lines = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
      EXPECT_GE(line, 0) << r.error;
      EXPECT_LE(line, lines) << r.error;
      EXPECT_GT(r.error.size(), r.error.find(": ", 8) + 2) << r.error;
      continue;
    }
    // An accepted world holds what the simulator relies on.
    const World& w = r.world;
    auto sound = [](const Eigen::Vector2d& p) {
      return std::isfinite(p.x()) && std::isfinite(p.y()) && std::fabs(p.x()) <= 500 && std::fabs(p.y()) <= 500;
    };
    ASSERT_TRUE(sound({w.start.x, w.start.y}) && std::isfinite(w.start.yaw_rad) && w.start.z >= 0) << text;
    ASSERT_TRUE(w.wall_thickness_m > 0 && w.wall_thickness_m <= 10) << text;
    ASSERT_TRUE(w.ceiling_m >= 0 && std::isfinite(w.ceiling_m)) << text;
    ASSERT_FALSE(w.walls.empty() && w.obstacles.empty()) << text;
    for (const Wall& wall : w.walls) {
      ASSERT_TRUE(sound(wall.a) && sound(wall.b) && (wall.a - wall.b).norm() >= 1e-6) << text;
      ASSERT_LT(wall.z_min, wall.z_max) << text;
      ASSERT_TRUE(wall.return_probability >= 0 && wall.return_probability <= 1) << text;
    }
    for (const Obstacle& o : w.obstacles) {
      ASSERT_GE(o.polygon.size(), 3u) << text;
      for (const auto& p : o.polygon) ASSERT_TRUE(sound(p)) << text;
      ASSERT_GT(polygon_signed_area(o.polygon), 0) << text;  // counter-clockwise
      ASSERT_LT(o.z_min, o.z_max) << text;
      ASSERT_TRUE(o.return_probability >= 0 && o.return_probability <= 1) << text;
    }
    for (const Room& room : w.rooms) {
      ASSERT_GE(room.polygon.size(), 3u) << text;
      for (const auto& p : room.polygon) ASSERT_TRUE(sound(p)) << text;
    }
    // And the simulator's grids build over it, and a ray from the start ends.
    const FreeSpaceMap map(w, 0.5);
    RayCaster caster(w, 0.5, WallSurfaces::kBoxOutlines);
    for (int k = 0; k < 8; ++k) {
      const double a = k * std::numbers::pi / 4;
      const RayHit hit = caster.cast({w.start.x, w.start.y, w.start.z + 0.5}, {std::cos(a), std::sin(a), 0}, 30);
      if (hit.kind != RayHit::Kind::kNone) {
        ASSERT_TRUE(hit.range_m >= 0 && hit.range_m <= 30) << text;
      }
    }
  }
  // Most mutations must be caught; the rest changed a number into another valid number, a comment
  // or a separator.
  EXPECT_GT(errors, 230);
}

}  // namespace
}  // namespace kestrel::sim
