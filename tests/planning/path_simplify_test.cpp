#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "grid_fixture.hpp"
#include "kestrel/planning/path_simplify.hpp"

namespace kestrel::planning {
namespace {

using test::blank_grid;
using test::kFreeCell;
using test::kWallCell;
using test::paint;

struct Fixture : test::SearchRig {
  PathCells cells;
  PathPoints points;
  Status plan(Cell from, Cell to) {
    if (Status s = search_from(from, SearchCosts{4, 12, 20}); s != Status::kOk) return s;
    if (Status s = search->path_to(to, cells); s != Status::kOk) return s;
    return simplify_path(*grid, *distance, cells, points);
  }
};

TEST(PathSimplify, AStraightRunIsOneLeg) {
  Fixture f;
  paint(*f.grid, 100, 100, 200, 200, kFreeCell);
  ASSERT_EQ(f.plan({120, 150}, {180, 150}), Status::kOk);
  ASSERT_EQ(f.points.size(), 2u);
  const Point2 end = f.grid->geometry().centre_of({180, 150});
  EXPECT_FLOAT_EQ(f.points[1].x, end.x);
  EXPECT_FLOAT_EQ(f.points[1].y, end.y);
}

// Round the end of a wall: a corner at the wall's end, and no leg through the wall.
TEST(PathSimplify, AroundAWallEveryLegStaysClear) {
  Fixture f;
  paint(*f.grid, 100, 100, 200, 200, kFreeCell);
  paint(*f.grid, 150, 100, 152, 170, kWallCell);
  ASSERT_EQ(f.plan({120, 120}, {180, 120}), Status::kOk);
  ASSERT_GE(f.points.size(), 3u);
  const GridGeometry& g = f.grid->geometry();
  for (std::size_t i = 1; i < f.points.size(); ++i) {
    Cell a, b;
    ASSERT_TRUE(g.to_cell(f.points[i - 1].x, f.points[i - 1].y, a));
    ASSERT_TRUE(g.to_cell(f.points[i].x, f.points[i].y, b));
    EXPECT_TRUE(line_clear(*f.grid, *f.distance, a, b, 1)) << "leg " << i;
  }
  EXPECT_FALSE(line_clear(*f.grid, *f.distance, {120, 120}, {180, 120}, 1));
}

TEST(PathSimplify, EmptyPathIsNoData) {
  Fixture f;
  PathCells none;
  EXPECT_EQ(simplify_path(*f.grid, *f.distance, none, f.points), Status::kNoData);
  EXPECT_TRUE(f.points.empty());
}

}  // namespace
}  // namespace kestrel::planning
