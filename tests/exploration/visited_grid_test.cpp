// The explorer's memory of where it has flown (visited_grid.hpp) and the frontier draw that
// prefers the rest (draw_frontier, SrtParams::prefer_unvisited).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "kestrel/exploration/srt_star_planner.hpp"
#include "corridor_node.hpp"
#include "kestrel/exploration/visited_grid.hpp"
#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using test::LaserModel;
using test::SegmentWorld;

TEST(VisitedGrid, MarksTheCellUnderThePoseAndItsNeighbours) {
  VisitedGrid g;
  EXPECT_FALSE(g.visited({0, 0}));  // nothing before the first mark
  g.mark({10.2f, 5.3f});
  EXPECT_EQ(g.marked_cells(), 9u);
  EXPECT_TRUE(g.visited({10.2f, 5.3f}));
  EXPECT_TRUE(g.visited({11.0f, 6.2f}));   // a neighbouring cell
  EXPECT_FALSE(g.visited({12.9f, 5.3f}));  // two cells on
  EXPECT_FALSE(g.visited({10.2f, 2.5f}));
  // Marking again changes nothing; a pose a cell on adds a column of three.
  g.mark({10.2f, 5.3f});
  EXPECT_EQ(g.marked_cells(), 9u);
  g.mark({11.2f, 5.3f});
  EXPECT_EQ(g.marked_cells(), 12u);
}

TEST(VisitedGrid, OutsideTheGridAndNonFinitePositionsAreNeverVisited) {
  VisitedGrid g;
  g.mark({std::nanf(""), 0});  // ignored: does not anchor the grid either
  EXPECT_EQ(g.marked_cells(), 0u);
  g.mark({0, 0});
  const float half = 0.5f * VisitedGrid::kSide * VisitedGrid::kCellM;
  g.mark({half + 5, 0});  // beyond the grid's edge: not marked
  EXPECT_EQ(g.marked_cells(), 9u);
  EXPECT_FALSE(g.visited({half + 5, 0}));
  EXPECT_FALSE(g.visited({0, std::nanf("")}));
  EXPECT_FALSE(g.visited({-INFINITY, 0}));
  // The last cells inside are markable, their neighbours outside are skipped.
  g.mark({half - 0.1f, half - 0.1f});
  EXPECT_EQ(g.marked_cells(), 9u + 4u);
  g.clear();
  EXPECT_EQ(g.marked_cells(), 0u);
  EXPECT_FALSE(g.visited({0, 0}));
}

// A node with frontiers east and west along a corridor: with the east end visited, every draw
// goes west; without the grid both ends come up.
TEST(DrawFrontier, PrefersFrontiersWhereTheVehicleHasNotFlown) {
  test_scenes::CorridorNode scene;
  ASSERT_EQ(test_scenes::corridor_node(-20, 20, 0, scene), Status::kOk);
  SrtStarTree* tree = scene.tree.get();
  const uint16_t id = scene.id;
  const std::size_t live = tree->frontier_count_of(id);
  bool any_east = false, any_west = false;
  for (const Frontier& f : tree->frontiers()) {
    any_east |= f.position.x > 2;
    any_west |= f.position.x < -2;
  }
  ASSERT_TRUE(any_east && any_west) << live << " frontiers";
  VisitedGrid east_flown;
  for (float x = 0.5f; x <= 6.0f; x += 0.5f) east_flown.mark({x, 0});
  int east = 0, west = 0, east_without = 0;
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    Prng prng(seed);
    const std::size_t i = draw_frontier(*tree, id, live, &east_flown, prng);
    ASSERT_LT(i, tree->frontiers().size());
    EXPECT_EQ(tree->frontier(i).node, id);
    (tree->frontier(i).position.x > 0 ? east : west) += 1;
    Prng plain(seed);
    east_without += tree->frontier(draw_frontier(*tree, id, live, nullptr, plain)).position.x > 0 ? 1 : 0;
  }
  EXPECT_EQ(east, 0);
  EXPECT_EQ(west, 40);
  EXPECT_GT(east_without, 0);
  EXPECT_LT(east_without, 40);
  // Every frontier visited: the draw falls back to all of them.
  VisitedGrid everywhere;
  for (float x = -6.0f; x <= 6.0f; x += 0.5f) everywhere.mark({x, 0});
  Prng prng(3);
  EXPECT_LT(draw_frontier(*tree, id, live, &everywhere, prng), tree->frontiers().size());
  // No live frontier: the end of the list.
  EXPECT_EQ(draw_frontier(*tree, id, 0, &east_flown, prng), tree->frontiers().size());
}

// The memory outlives section V's restart (that is its purpose) and goes with reset().
TEST(SrtStarPlanner, VisitedGridSurvivesRestartsAndGoesWithReset) {
  auto planner = std::make_unique<SrtStarPlanner>();
  SrtParams srt;
  srt.arrival_work_per_cycle = 0;
  srt.prefer_unvisited = true;
  GuidanceParams g;
  g.waypoint_time_limit_s = 5.0f;
  ASSERT_EQ(planner->configure(srt, g), Status::kOk);
  SegmentWorld room;
  room.add_box(-3, -3, 9, 3);
  const LaserModel urg = LaserModel::urg04lx();
  bool fresh = false;
  ASSERT_EQ(planner->update({0, 0, 0}, room.scan(urg, 0, 0, 0), TimeUs{}, fresh), Status::kOk);
  EXPECT_TRUE(planner->visited().visited({0, 0}));
  ASSERT_EQ(planner->mode(), PlannerMode::kForward);
  const Point2 given_up = planner->waypoint();
  ASSERT_GT(std::hypot(given_up.x, given_up.y), 1.6f);  // beyond the marks around the root
  EXPECT_FALSE(planner->visited().visited(given_up));
  // Stuck 0.1 m from the root past the time limit: the tree is erased, the memory is not, and
  // the waypoint it gave up counts as visited (else the next tree would draw it first again).
  const Pose2 stuck{0.1f, 0, 0};
  ASSERT_EQ(planner->update(stuck, room.scan(urg, 0.1, 0, 0), TimeUs{6000000}, fresh), Status::kOk);
  ASSERT_EQ(planner->restarts(), 1u);
  EXPECT_TRUE(planner->visited().visited({0, 0}));
  EXPECT_TRUE(planner->visited().visited(given_up));
  planner->reset();
  EXPECT_FALSE(planner->visited().visited({0, 0}));
}

}  // namespace
}  // namespace kestrel::exploration
