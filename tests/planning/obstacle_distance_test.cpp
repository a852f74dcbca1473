#include <gtest/gtest.h>

#include <array>
#include <memory>

#include "grid_fixture.hpp"
#include "kestrel/planning/obstacle_distance.hpp"

namespace kestrel::planning {
namespace {

using test::blank_grid;
using test::kFreeCell;
using test::kWallCell;
using test::paint;

// The 3-4 chamfer distance from one wall cell: 3 per straight step, 4 per diagonal.
TEST(ObstacleDistance, IsTheChamferDistanceFromTheNearestWall) {
  auto g = blank_grid();
  paint(*g, 100, 100, 140, 140, kFreeCell);
  paint(*g, 120, 120, 120, 120, kWallCell);
  auto d = std::make_unique<ObstacleDistance>();
  d->compute(*g, {100, 100, 140, 140});
  EXPECT_EQ(d->at(120, 120), 0);
  EXPECT_EQ(d->at(125, 120), 15);
  EXPECT_EQ(d->at(120, 113), 21);
  EXPECT_EQ(d->at(124, 124), 16);
  EXPECT_EQ(d->at(126, 123), 4 * 3 + 3 * 3);  // three diagonal steps, three straight
  // Outside the box: far.
  EXPECT_EQ(d->at(99, 120), ObstacleDistance::kFar);
}

TEST(ObstacleDistance, SaturatesFarFromAnyWallAndKeepOutBoxesAreWalls) {
  auto g = blank_grid();
  paint(*g, 0, 0, 199, 199, kFreeCell);
  auto d = std::make_unique<ObstacleDistance>();
  d->compute(*g, {0, 0, 199, 199});
  EXPECT_EQ(d->at(100, 100), ObstacleDistance::kFar);
  const std::array<CellBox, 1> keep_out{CellBox{50, 50, 60, 55}};
  d->compute(*g, {0, 0, 199, 199}, keep_out);
  EXPECT_EQ(d->at(55, 52), 0);
  EXPECT_EQ(d->at(55, 58), 9);
  EXPECT_EQ(d->at(45, 52), 15);
}

TEST(ObstacleDistance, UnitsOfMetresRoundUp) {
  EXPECT_EQ(ObstacleDistance::units_of(0.3f, 0.12f), 8);  // 7.5 -> 8
  EXPECT_EQ(ObstacleDistance::units_of(0.36f, 0.12f), 9);
  EXPECT_EQ(ObstacleDistance::units_of(0.0f, 0.12f), 0);
  EXPECT_EQ(ObstacleDistance::units_of(NAN, 0.12f), 0);
  EXPECT_EQ(ObstacleDistance::units_of(100.0f, 0.12f), ObstacleDistance::kFar);
}

}  // namespace
}  // namespace kestrel::planning
