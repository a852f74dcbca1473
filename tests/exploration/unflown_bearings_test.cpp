// Where the building has not been flown, by bearing (unflown_bearings.hpp), and the frontier
// draw that steers a fresh tree towards it (draw_toward_unflown, SrtParams::steer_unflown).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <memory>

#include "corridor_node.hpp"
#include "kestrel/exploration/srt_star_planner.hpp"
#include "kestrel/exploration/unflown_bearings.hpp"
#include "kestrel/exploration/visited_grid.hpp"
#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using test::LaserModel;
using test::SegmentWorld;

constexpr float kWest = static_cast<float>(M_PI), kEast = 0.0f, kNorth = static_cast<float>(M_PI / 2);

// A corridor flown from x = 0 to 12 along y = 0, and the outline's corners touched at (0, +-7):
// the rooms either side of the corridor's west half are inside the extent and never flown.
VisitedGrid corridor_flown_west_rooms_not() {
  VisitedGrid g;
  for (float x = 0.0f; x <= 12.0f; x += 0.5f) g.mark({x, 0});
  g.mark({0, 7});
  g.mark({0, -7});
  return g;
}

TEST(VisitedGrid, ExtentIsTheBoundingBoxOfTheMarkedCells) {
  VisitedGrid g;
  int ix = 0, iy = 0;
  EXPECT_FALSE(g.cell_of({0, 0}, ix, iy));  // no grid before the first mark
  g.mark({0.5f, 0.5f});
  ASSERT_TRUE(g.cell_of({0.5f, 0.5f}, ix, iy));
  EXPECT_TRUE(g.in_extent(ix - 1, iy + 1));
  EXPECT_FALSE(g.in_extent(ix - 2, iy));
  g.mark({5.5f, 0.5f});
  EXPECT_TRUE(g.in_extent(ix + 6, iy));
  EXPECT_FALSE(g.in_extent(ix + 7, iy));
  EXPECT_TRUE(g.in_extent(ix + 3, iy - 1));  // inside the box, never marked
  EXPECT_FALSE(g.visited_cell(ix + 3, iy - 1));
  EXPECT_TRUE(g.visited_cell(ix + 4, iy - 1));  // a neighbour of the second mark
  EXPECT_FALSE(g.visited_cell(-1, 0));
  EXPECT_FALSE(g.visited_cell(VisitedGrid::kSide, 0));
  g.clear();
  EXPECT_FALSE(g.in_extent(ix, iy));
}

TEST(UnflownBearings, CountsTheUnflownCellsInsideTheExtentByBearing) {
  const VisitedGrid g = corridor_flown_west_rooms_not();
  UnflownBearings b;
  EXPECT_GT(b.count(g, {12.0f, 0}), 0u);
  // From the corridor's east end: the unflown rooms lie west; east of x = 13 is outside the
  // extent (never flown, so as likely outside the walls as a room).
  EXPECT_GT(b.score(kWest), 40u);
  EXPECT_EQ(b.score(kEast), 0u);
  EXPECT_GT(b.score(kWest), b.score(kNorth));
  // The same bearing, a turn apart, is the same bin (3.0 rad is inside a bin, not on an edge).
  EXPECT_EQ(b.score(3.0f), b.score(3.0f + 2.0f * static_cast<float>(M_PI)));
  EXPECT_EQ(b.score(3.0f), b.score(3.0f - 2.0f * static_cast<float>(M_PI)));
}

// A flown square but for a 3 x 3 patch of cells centred `dist` cells north of (0, 0) (marks
// are 3 x 3, on integer positions: cell centres, the first mark fixes the grid).
VisitedGrid flown_but_a_patch(int dist) {
  VisitedGrid g;
  for (int y = -2; y <= 18; ++y)
    for (int x = -10; x <= 10; ++x)
      if (std::max(std::abs(x), std::abs(y - dist)) > 2) g.mark({static_cast<float>(x), static_cast<float>(y)});
  return g;
}

// The same nine unflown cells weigh about five times as much 3 m away as 12 m away: a door into
// an unflown room beside the node outweighs a corridor's far end.
TEST(UnflownBearings, NearerUnflownCellsWeighMore) {
  UnflownBearings b;
  b.count(flown_but_a_patch(3), {0, 0});
  const uint32_t near = b.score(kNorth);
  EXPECT_EQ(b.score(kWest), 0u);
  b.count(flown_but_a_patch(12), {0, 0});
  const uint32_t far = b.score(kNorth);
  EXPECT_GT(far, 0u);
  EXPECT_GE(near, 4 * far);
}

// Against a count by angle, cell by cell, in a scene with no symmetry: a bearing on a multiple
// of 10 degrees scores the unflown cells within +-35 degrees of it (those on the cone's edges
// either way), each weighing 16 / its distance in cells, rounded.
TEST(UnflownBearings, AScoreIsTheWeightedUnflownCellsWithin35DegreesUpTo16Cells) {
  VisitedGrid g;
  for (float x = 0.0f; x <= 12.0f; x += 0.5f) g.mark({x, 0.3f * x});
  g.mark({1.0f, 9.0f});
  g.mark({-3.0f, -5.0f});
  const Point2 from{6.2f, 1.5f};
  UnflownBearings b;
  b.count(g, from);
  int cx = 0, cy = 0;
  ASSERT_TRUE(g.cell_of(from, cx, cy));
  for (int k = 0; k < UnflownBearings::kBins; ++k) {
    const double bearing = k * 2.0 * M_PI / UnflownBearings::kBins;
    uint32_t inside = 0, edge = 0;
    for (int dy = -16; dy <= 16; ++dy) {
      for (int dx = -16; dx <= 16; ++dx) {
        if ((dx == 0 && dy == 0) || dx * dx + dy * dy > 256) continue;
        if (!g.in_extent(cx + dx, cy + dy) || g.visited_cell(cx + dx, cy + dy)) continue;
        const double off = std::fabs(std::remainder(std::atan2(dy, dx) - bearing, 2.0 * M_PI)) * 180.0 / M_PI;
        const auto weight = static_cast<uint32_t>(std::lround(16.0 / std::hypot(dx, dy)));
        inside += off < 34.99 ? weight : 0;
        edge += off >= 34.99 && off <= 35.01 ? weight : 0;
      }
    }
    SCOPED_TRACE(::testing::Message() << "bearing " << k * 10 << " degrees");
    EXPECT_GE(b.score(static_cast<float>(bearing)), inside);
    EXPECT_LE(b.score(static_cast<float>(bearing)), inside + edge);
  }
}

TEST(UnflownBearings, NothingCountedOffTheGridOrFromANonFinitePoint) {
  UnflownBearings b;
  const VisitedGrid empty;
  b.count(empty, {0, 0});
  EXPECT_EQ(b.total(), 0u);
  const VisitedGrid g = corridor_flown_west_rooms_not();
  // Each count starts afresh: a count from off the grid after one from inside it is empty.
  b.count(g, {12.0f, 0});
  EXPECT_GT(b.total(), 0u);
  b.count(g, {1000.0f, 0});
  EXPECT_EQ(b.total(), 0u);
  b.count(g, {12.0f, 0});
  b.count(g, {std::nanf(""), 0});
  EXPECT_EQ(b.total(), 0u);
  b.count(g, {12.0f, 0});
  EXPECT_EQ(b.score(std::nanf("")), 0u);
  EXPECT_EQ(b.score(INFINITY), 0u);
}

// A fresh tree at the east end of the flown corridor (as after section V's restart): its
// frontiers face both ways along it; steered, every draw goes west, where the unflown rooms
// are; unsteered, both ends come up.
TEST(DrawTowardUnflown, AFreshTreeAtTheCorridorsEastEndHeadsBackWest) {
  test_scenes::CorridorNode scene;
  ASSERT_EQ(test_scenes::corridor_node(-20, 40, 12.0f, scene), Status::kOk);
  SrtStarTree* tree = scene.tree.get();
  const uint16_t id = scene.id;
  const Pose2 node = scene.pose;
  const std::size_t live = tree->frontier_count_of(id);
  UnflownBearings b;
  b.count(corridor_flown_west_rooms_not(), {node.x, node.y});
  int west = 0, east_unsteered = 0;
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    Prng prng(seed);
    const std::size_t i = draw_toward_unflown(*tree, id, b, prng);
    ASSERT_LT(i, tree->frontiers().size());
    EXPECT_EQ(tree->frontier(i).node, id);
    west += tree->frontier(i).position.x < node.x ? 1 : 0;
    Prng plain(seed);
    east_unsteered += tree->frontier(draw_frontier(*tree, id, live, nullptr, plain)).position.x > node.x ? 1 : 0;
  }
  EXPECT_EQ(west, 40);
  EXPECT_GT(east_unsteered, 0);
  EXPECT_LT(east_unsteered, 40);
  // Nothing unflown in any frontier's direction: no steered draw (the caller draws as before).
  UnflownBearings none;
  Prng prng(7);
  EXPECT_EQ(draw_toward_unflown(*tree, id, none, prng), tree->frontiers().size());
  EXPECT_EQ(draw_toward_unflown(*tree, kNoNode, b, prng), tree->frontiers().size());
}

SegmentWorld long_corridor() { return test_scenes::corridor(-20, 40); }

constexpr Pose2 kEastEnd{12.0f, 0, kNorth};  // facing a wall: both ends at +-90 degrees

// A planner that flew the corridor west to east without reaching its waypoint (the outline
// touched first), and whose time limit has just erased the tree at the east end.
std::unique_ptr<SrtStarPlanner> restarted_at_the_east_end(SteerUnflown steering, uint32_t seed) {
  auto planner = std::make_unique<SrtStarPlanner>();
  SrtParams srt;
  srt.arrival_work_per_cycle = 0;
  srt.steer = steering;
  srt.seed = seed;
  GuidanceParams g;
  g.waypoint_time_limit_s = 30.0f;
  EXPECT_EQ(planner->configure(srt, g), Status::kOk);
  const SegmentWorld corridor = long_corridor();
  const LaserModel urg = LaserModel::urg04lx();
  bool fresh = false;
  EXPECT_EQ(planner->update({0, 0, kNorth}, corridor.scan(urg, 0, 0, kNorth), TimeUs{}, fresh), Status::kOk);
  const Pose2 corners[] = {{0, 7, 0}, {0, -7, 0}};
  for (const Pose2& p : corners)
    EXPECT_EQ(planner->update(p, corridor.scan(urg, 0, 0, 0), TimeUs{}, fresh), Status::kOk);
  for (float x = 0.0f; x <= 12.0f; x += 0.5f)
    EXPECT_EQ(planner->update({x, 0.8f, 0}, corridor.scan(urg, 0, 0, 0), TimeUs{}, fresh), Status::kOk);
  EXPECT_EQ(planner->restarts(), 0u);
  if (steering == SteerUnflown::kAfterRestart) {
    EXPECT_EQ(planner->steered_draws(), 0u);  // the first tree draws as paper 002 does
  }
  EXPECT_EQ(
      planner->update(kEastEnd, corridor.scan(urg, kEastEnd.x, kEastEnd.y, kEastEnd.theta), TimeUs{31000000}, fresh),
      Status::kOk);
  EXPECT_EQ(planner->restarts(), 1u);
  EXPECT_EQ(planner->mode(), PlannerMode::kForward);
  return planner;
}

// Over seeds 1-80, the vehicle arrives at the fresh tree's first waypoint, near the corridor's
// east end: how many of the new nodes own frontiers both ways (a node east of the root has its
// west ones inside the root's safe region), and how many of those drew their next waypoint west.
struct NextWaypoints {
  int both_ways = 0;
  int west = 0;
};

NextWaypoints next_waypoints_at_the_east_end(SteerUnflown steering) {
  const SegmentWorld corridor = long_corridor();
  const LaserModel urg = LaserModel::urg04lx();
  NextWaypoints out;
  for (uint32_t seed = 1; seed <= 80; ++seed) {
    const auto planner = restarted_at_the_east_end(steering, seed);
    const uint32_t steered = planner->steered_draws();
    if (steering != SteerUnflown::kNever) {
      // The first tree's root, at least; after a restart only, the fresh tree's root.
      EXPECT_GE(steered, 1u) << "seed " << seed;
    }
    const Point2 w = planner->waypoint();
    bool fresh = false;
    EXPECT_EQ(planner->update({w.x, w.y, kNorth}, corridor.scan(urg, w.x, w.y, kNorth), TimeUs{32000000}, fresh),
              Status::kOk);
    EXPECT_TRUE(fresh);
    EXPECT_EQ(planner->mode(), PlannerMode::kForward);
    EXPECT_FALSE(planner->steer_paused());
    // Reaching a waypoint resumes steering, which from the root only no longer applies.
    if (steering == SteerUnflown::kFromRootOnly) {
      EXPECT_EQ(planner->steered_draws(), steered) << "seed " << seed;
    }
    bool has_west = false, has_east = false;
    for (const Frontier& f : planner->tree().frontiers()) {
      if (f.node != planner->current_node()) continue;
      has_west |= f.position.x < w.x;
      has_east |= f.position.x > w.x;
    }
    if (!has_west || !has_east) continue;
    ++out.both_ways;
    out.west += planner->waypoint().x < w.x ? 1 : 0;
  }
  std::printf("steered %s: %d of %d nodes with frontiers both ways went west\n", to_string(steering), out.west,
              out.both_ways);
  return out;
}

// Steered, the next waypoint from a node with frontiers both ways is west, towards the unflown
// rooms, on every seed; unsteered, either way.
TEST(SrtStarPlanner, SteeredTheNextWaypointHeadsForTheUnflownSideOfTheBuilding) {
  const NextWaypoints steered = next_waypoints_at_the_east_end(SteerUnflown::kEveryNode);
  EXPECT_GE(steered.both_ways, 8);
  EXPECT_EQ(steered.west, steered.both_ways);
  const NextWaypoints unsteered = next_waypoints_at_the_east_end(SteerUnflown::kNever);
  EXPECT_GE(unsteered.both_ways, 8);
  EXPECT_GT(unsteered.west, 0);
  EXPECT_LT(unsteered.west, unsteered.both_ways);
}

// Steered from the root only, the fresh tree's root draws steered (the corridor's first tree:
// its root's draw) and every later node draws as paper 002 does: at the node near the east end
// the next waypoint goes either way, and no draw there counts as steered.
TEST(SrtStarPlanner, SteeredFromTheRootOnlyLaterNodesDrawAsPaper002Does) {
  const NextWaypoints n = next_waypoints_at_the_east_end(SteerUnflown::kFromRootOnly);
  EXPECT_GE(n.both_ways, 8);
  EXPECT_GT(n.west, 0);
  EXPECT_LT(n.west, n.both_ways);
}

// Steered after a restart only, the first tree draws as paper 002 does (checked in
// restarted_at_the_east_end: no steered draw before the time limit) and the fresh tree is
// steered from its root on: every node near the east end with frontiers both ways goes west.
TEST(SrtStarPlanner, SteeredAfterARestartOnlyTheFreshTreeHeadsForTheUnflownSide) {
  const NextWaypoints n = next_waypoints_at_the_east_end(SteerUnflown::kAfterRestart);
  EXPECT_GE(n.both_ways, 8);
  EXPECT_EQ(n.west, n.both_ways);
}

// srt.steer by name (kestrel-sim's srt_steer=...); anything else is refused. Every listed mode
// configures the planner and a value outside the list is refused.
TEST(SrtStarPlanner, SteeringModesRoundTripByNameAndOthersAreRefused) {
  for (const SteerUnflown s : kSteerUnflownModes) EXPECT_EQ(parse_steer_unflown(to_string(s)).value(), s);
  EXPECT_EQ(parse_steer_unflown("on").status(), Status::kInvalidArgument);
  EXPECT_EQ(parse_steer_unflown(nullptr).status(), Status::kInvalidArgument);
  SrtStarPlanner planner;
  SrtParams srt;
  EXPECT_EQ(srt.steer, SteerUnflown::kAfterRestart);
  for (const SteerUnflown s : kSteerUnflownModes) {
    srt.steer = s;
    EXPECT_EQ(planner.configure(srt, GuidanceParams{}), Status::kOk) << to_string(s);
  }
  srt.steer = static_cast<SteerUnflown>(4);
  EXPECT_EQ(planner.configure(srt, GuidanceParams{}), Status::kInvalidArgument);
}

// A steered waypoint the time limit gives up would be steered to again by the next tree, restart
// after restart (gt-building's strip beside the inner room): the next choices are unsteered
// until a waypoint is reached. (The first tree's waypoint was steered: the returns of the root's
// scan reach beyond where the vehicle had flown.)
TEST(SrtStarPlanner, ASteeredWaypointNotReachedPausesSteeringUntilAWaypointIsReached) {
  const SegmentWorld corridor = long_corridor();
  const LaserModel urg = LaserModel::urg04lx();
  int west = 0;
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    const auto planner = restarted_at_the_east_end(SteerUnflown::kEveryNode, seed);
    EXPECT_TRUE(planner->steer_paused());
    EXPECT_EQ(planner->steer_pauses(), 1u);
    west += planner->waypoint().x < kEastEnd.x ? 1 : 0;
    // Reached: steering again.
    const Point2 w = planner->waypoint();
    bool fresh = false;
    ASSERT_EQ(planner->update({w.x, w.y, kNorth}, corridor.scan(urg, w.x, w.y, kNorth), TimeUs{32000000}, fresh),
              Status::kOk);
    EXPECT_FALSE(planner->steer_paused());
    EXPECT_EQ(planner->steer_pauses(), 1u);
  }
  EXPECT_GT(west, 0);  // drawn as paper 002 draws: either way
  EXPECT_LT(west, 20);
}

// A time-out while paused is not a second pause (nor does it resume steering), and reset()
// forgets the pause, the counts and the flown grid.
TEST(SrtStarPlanner, ATimeOutWhilePausedStaysOnePauseAndResetForgetsIt) {
  const SegmentWorld corridor = long_corridor();
  const LaserModel urg = LaserModel::urg04lx();
  const auto planner = restarted_at_the_east_end(SteerUnflown::kEveryNode, 5);
  ASSERT_TRUE(planner->steer_paused());
  const uint32_t steered = planner->steered_draws();
  EXPECT_GE(steered, 1u);
  bool fresh = false;
  const LaserScan scan = corridor.scan(urg, kEastEnd.x, kEastEnd.y, kEastEnd.theta);
  ASSERT_EQ(planner->update(kEastEnd, scan, TimeUs{62000000}, fresh), Status::kOk);
  ASSERT_EQ(planner->update(kEastEnd, scan, TimeUs{93000000}, fresh), Status::kOk);
  EXPECT_EQ(planner->restarts(RestartReason::kTimeout), 3u);
  EXPECT_EQ(planner->restarts(), 3u);
  EXPECT_TRUE(planner->steer_paused());
  EXPECT_EQ(planner->steer_pauses(), 1u);
  EXPECT_EQ(planner->steered_draws(), steered);  // none while paused
  planner->reset();
  EXPECT_FALSE(planner->steer_paused());
  EXPECT_EQ(planner->steer_pauses(), 0u);
  EXPECT_EQ(planner->steered_draws(), 0u);
  EXPECT_EQ(planner->restarts(), 0u);
  EXPECT_EQ(planner->restarts(RestartReason::kTimeout), 0u);
  EXPECT_EQ(planner->visited().marked_cells(), 0u);
}

}  // namespace
}  // namespace kestrel::exploration
