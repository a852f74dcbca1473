#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

#include "grid_fixture.hpp"
#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/planning/grid_search.hpp"
#include "kestrel/planning/path_simplify.hpp"

namespace kestrel::planning {
namespace {

using test::blank_grid;
using test::kFreeCell;
using test::kWallCell;
using test::paint;

using Planner = test::SearchRig;

// Without walls or penalties the cost is the octile distance: 10 a straight step, 14 a diagonal.
TEST(GridSearch, OpenSpaceCostsTheOctileDistance) {
  Planner p;
  paint(*p.grid, 100, 100, 200, 200, kFreeCell);
  ASSERT_EQ(p.search_from({150, 150}), Status::kOk);
  EXPECT_EQ(p.search->cost(Cell{150, 150}), 0);
  EXPECT_EQ(p.search->cost(Cell{160, 150}), 100);
  EXPECT_EQ(p.search->cost(Cell{160, 160}), 140);
  EXPECT_EQ(p.search->cost(Cell{153, 160}), 3 * 14 + 7 * 10);
  EXPECT_EQ(p.search->cost(Cell{99, 150}), GridSearch::kUnreached);  // outside the box
}

// A wall across the box with a door: the far side is reached through the door only, and a
// door narrower than twice the lethal distance is no door.
TEST(GridSearch, WallsAreGoneAroundAndNarrowGapsAreClosed) {
  Planner p;
  paint(*p.grid, 100, 100, 200, 200, kFreeCell);
  paint(*p.grid, 150, 100, 150, 200, kWallCell);
  paint(*p.grid, 150, 170, 150, 177, kFreeCell);  // an 8-cell (0.96 m) door
  const SearchCosts costs{8, 8, 0};                // lethal 0.3 m at 12 cm cells
  ASSERT_EQ(p.search_from({120, 120}, costs), Status::kOk);
  const uint16_t through = p.search->cost(Cell{180, 120});
  ASSERT_NE(through, GridSearch::kUnreached);
  EXPECT_GT(through, 1200);  // straight across would be 600; by the door 2 x (30 x 14 + 21 x 10)
  PathCells path;
  ASSERT_EQ(p.search->path_to({180, 120}, path), Status::kOk);
  const bool via_door =
      std::any_of(path.begin(), path.end(), [](Cell c) { return c.x == 150 && c.y >= 170 && c.y <= 177; });
  EXPECT_TRUE(via_door);
  // A 4-cell (0.48 m) door: closed.
  paint(*p.grid, 150, 170, 150, 177, kWallCell);
  paint(*p.grid, 150, 172, 150, 175, kFreeCell);
  ASSERT_EQ(p.search_from({120, 120}, costs), Status::kOk);
  EXPECT_EQ(p.search->cost(Cell{180, 120}), GridSearch::kUnreached);
}

TEST(GridSearch, UnknownCellsAreNotEnteredAndTheStartMayLeaveALethalCell) {
  Planner p;
  paint(*p.grid, 100, 100, 130, 200, kFreeCell);  // x > 130 unknown
  paint(*p.grid, 110, 100, 110, 200, kWallCell);
  const SearchCosts costs{8, 8, 0};
  // Start one cell from the wall (lethal): it may step away, not along or nearer.
  ASSERT_EQ(p.search_from({111, 150}, costs), Status::kOk);
  EXPECT_NE(p.search->cost(Cell{125, 150}), GridSearch::kUnreached);
  EXPECT_EQ(p.search->cost(Cell{140, 150}), GridSearch::kUnreached);
  EXPECT_EQ(p.search->cost(Cell{105, 150}), GridSearch::kUnreached);
}

// The penalty near walls draws the path to the middle of a corridor.
TEST(GridSearch, PenaltyKeepsPathsInTheMiddle) {
  Planner p;
  paint(*p.grid, 100, 100, 200, 200, kWallCell);
  paint(*p.grid, 101, 140, 199, 156, kFreeCell);  // a 17-cell (2 m) corridor along x, centre y = 148
  ASSERT_EQ(p.search_from({105, 142}, SearchCosts{8, 24, 30}), Status::kOk);
  PathCells path;
  ASSERT_EQ(p.search->path_to({195, 142}, path), Status::kOk);
  const Cell mid = path[path.size() / 2];
  EXPECT_GE(mid.y, 146);
  EXPECT_LE(mid.y, 150);
}

// Coastal navigation: with cells far from every wall dearer, the path across an open room
// goes round by the walls instead of straight across the middle.
TEST(GridSearch, CoastalPenaltyKeepsPathsNearWalls) {
  Planner p;
  paint(*p.grid, 100, 100, 160, 160, kWallCell);
  paint(*p.grid, 101, 101, 159, 159, kFreeCell);  // 59 cells (7 m) across
  const uint8_t far = 24;                         // 8 cells, 0.96 m
  ASSERT_EQ(p.search_from({104, 130}, SearchCosts{4, 8, 10, 0, 0}), Status::kOk);
  PathCells straight;
  ASSERT_EQ(p.search->path_to({156, 130}, straight), Status::kOk);
  EXPECT_GE(p.distance->at(straight[straight.size() / 2]), far);  // straight across the middle
  ASSERT_EQ(p.search_from({104, 130}, SearchCosts{4, 8, 10, far, 40}), Status::kOk);
  PathCells coastal;
  ASSERT_EQ(p.search->path_to({156, 130}, coastal), Status::kOk);
  for (const Cell& c : coastal) EXPECT_LT(p.distance->at(c), far + 3) << c.x << "," << c.y;
  EXPECT_GT(coastal.size(), straight.size());
  // The legs keep to the coast too: no shortcut across the middle.
  PathPoints legs;
  ASSERT_EQ(simplify_path(*p.grid, *p.distance, coastal, legs, far), Status::kOk);
  for (std::size_t i = 1; i < legs.size(); ++i) {
    Cell a, b;
    ASSERT_TRUE(p.grid->geometry().to_cell(legs[i - 1].x, legs[i - 1].y, a));
    ASSERT_TRUE(p.grid->geometry().to_cell(legs[i].x, legs[i].y, b));
    EXPECT_TRUE(line_clear(*p.grid, *p.distance, a, b, 0, far + 3)) << "leg " << i;
  }
  EXPECT_EQ(p.search_from({104, 130}, SearchCosts{4, 8, 10, 8, 40}), Status::kInvalidArgument);   // far inside soft
  EXPECT_EQ(p.search_from({104, 130}, SearchCosts{4, 8, 30, 24, 40}), Status::kInvalidArgument);  // penalties over 60
}

TEST(GridSearch, PathsRunFromTheStartToTheGoalInNeighbouringCells) {
  Planner p;
  paint(*p.grid, 100, 100, 200, 200, kFreeCell);
  paint(*p.grid, 140, 110, 142, 190, kWallCell);
  ASSERT_EQ(p.search_from({120, 150}, SearchCosts{4, 12, 20}), Status::kOk);
  PathCells path;
  ASSERT_EQ(p.search->path_to({170, 150}, path), Status::kOk);
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path[0], (Cell{120, 150}));
  EXPECT_EQ(path.back(), (Cell{170, 150}));
  for (std::size_t i = 1; i < path.size(); ++i) {
    EXPECT_LE(std::abs(path[i].x - path[i - 1].x), 1);
    EXPECT_LE(std::abs(path[i].y - path[i - 1].y), 1);
    EXPECT_LT(p.search->cost(path[i - 1]), p.search->cost(path[i]));
  }
  EXPECT_EQ(p.search->path_to({141, 150}, path), Status::kNotFound);  // in the wall
}

TEST(GridSearch, BadCostsAndStartsAreRefused) {
  Planner p;
  paint(*p.grid, 100, 100, 200, 200, kFreeCell);
  EXPECT_EQ(p.search_from({150, 150}, SearchCosts{10, 5, 0}), Status::kInvalidArgument);
  EXPECT_EQ(p.search_from({150, 150}, SearchCosts{5, 10, 61}), Status::kInvalidArgument);
  EXPECT_EQ(p.search_from({50, 150}), Status::kOutOfRange);
  EXPECT_EQ(p.search->cost(Cell{150, 150}), GridSearch::kUnreached);
}

TEST(GridSearch, SearchingDoesNotAllocate) {
  Planner p;
  paint(*p.grid, 100, 100, 200, 200, kFreeCell);
  p.distance->compute(*p.grid, p.box);
  PathCells path;
  alloc_guard::Scope guard;
  ASSERT_EQ(p.search->run(*p.grid, *p.distance, p.box, {150, 150}, SearchCosts{8, 20, 30}), Status::kOk);
  ASSERT_EQ(p.search->path_to({190, 110}, path), Status::kOk);
  EXPECT_EQ(guard.allocations(), 0u);
}

}  // namespace
}  // namespace kestrel::planning
