// Paper 003's frontiers on painted grids: which cells are frontier cells, how they group, which
// are accessible, and what a blacklisted goal takes away.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "kestrel/exploration/frontier_clusters.hpp"
#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using planning::Cell;
using planning::CellBox;

constexpr uint8_t kFree = planning::occupancy::kEven - 40;
constexpr uint8_t kWall = planning::occupancy::kEven + 80;

struct Fixture {
  std::unique_ptr<planning::OccupancyGrid> grid = std::make_unique<planning::OccupancyGrid>();
  std::unique_ptr<planning::ObstacleDistance> distance = std::make_unique<planning::ObstacleDistance>();
  std::unique_ptr<planning::GridSearch> search = std::make_unique<planning::GridSearch>();
  std::unique_ptr<FrontierClusterFinder> finder = std::make_unique<FrontierClusterFinder>();
  FrontierClusters out;
  CellBox box{90, 90, 210, 210};
  Fixture() {
    const test::LaserModel urg = test::LaserModel::urg04lx();
    EXPECT_EQ(
        grid->configure({}, {0, 0}, urg.beams, static_cast<float>(urg.first_angle()), static_cast<float>(urg.step())),
        Status::kOk);
  }
  void paint(int x0, int y0, int x1, int y1, uint8_t v) {
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) grid->set({static_cast<int16_t>(x), static_cast<int16_t>(y)}, v);
  }
  void find(Cell start, uint16_t min_cells = 4, std::vector<ExcludedDisc> excluded = {}) {
    distance->compute(*grid, box);
    ASSERT_EQ(search->run(*grid, *distance, box, start, planning::SearchCosts{4, 4, 0}), Status::kOk);
    finder->find(*grid, *search, box, min_cells, excluded, out);
  }
};

TEST(FrontierClusters, AFrontierCellIsFreeWithAnUnknownEdgeNeighbour) {
  Fixture f;
  f.paint(100, 100, 110, 110, kFree);
  f.paint(105, 105, 105, 105, kWall);
  EXPECT_TRUE(FrontierClusterFinder::is_frontier(*f.grid, 100, 105));   // unknown at x = 99
  EXPECT_FALSE(FrontierClusterFinder::is_frontier(*f.grid, 104, 105));  // beside a wall, not unknown
  EXPECT_FALSE(FrontierClusterFinder::is_frontier(*f.grid, 105, 105));  // a wall
  EXPECT_FALSE(FrontierClusterFinder::is_frontier(*f.grid, 99, 105));   // unknown itself
  // Unknown only diagonally: not a frontier cell.
  f.paint(111, 111, 111, 111, kWall);
  f.paint(111, 100, 111, 110, kWall);
  f.paint(100, 111, 110, 111, kWall);
  EXPECT_FALSE(FrontierClusterFinder::is_frontier(*f.grid, 110, 110));
}

// A walled room open on its east side: one frontier, as long as the opening, whose nearest cell
// is the one straight east of the start.
TEST(FrontierClusters, AnOpenSideIsOneFrontierReachedAtItsNearestCell) {
  Fixture f;
  f.paint(100, 100, 140, 140, kWall);
  f.paint(101, 101, 140, 139, kFree);  // x = 140 is the last known column: unknown beyond
  f.find({110, 120});
  ASSERT_EQ(f.out.size(), 1u);
  EXPECT_EQ(f.out[0].cells, 39);
  EXPECT_EQ(f.out[0].nearest, (Cell{140, 120}));
  EXPECT_EQ(f.out[0].cost, 300);
  const Point2 c = f.grid->geometry().centre_of({140, 120});
  EXPECT_NEAR(f.out[0].centroid.x, c.x, 1e-3f);
  EXPECT_NEAR(f.out[0].centroid.y, c.y, 1e-3f);
}

TEST(FrontierClusters, NarrowAndUnreachedFrontiersAreNotAccessible) {
  Fixture f;
  f.paint(100, 100, 140, 140, kWall);
  f.paint(101, 101, 139, 139, kFree);
  f.paint(140, 120, 140, 121, kFree);  // a 2-cell hole in the east wall
  f.paint(120, 101, 120, 139, kWall);  // a wall splitting the room; the west half is the start's
  f.paint(120, 130, 120, 139, kWall);
  f.paint(100, 110, 100, 115, kFree);  // a 6-cell opening in the west wall
  f.find({110, 120});
  ASSERT_EQ(f.out.size(), 1u);  // the hole is too narrow (4 cells needed), the east half unreached
  EXPECT_EQ(f.out[0].nearest.x, 100);
  f.find({110, 120}, 2);        // with 2 cells enough, the hole counts, but is still unreached
  EXPECT_EQ(f.out.size(), 1u);
}

// A blacklisted goal takes the frontier cells near it; the rest of the frontier stays, with a
// nearest cell of its own.
TEST(FrontierClusters, AnExcludedDiscTakesItsPartOfAFrontierOnly) {
  Fixture f;
  f.paint(100, 100, 140, 140, kWall);
  f.paint(101, 101, 140, 139, kFree);
  f.find({110, 120}, 4, {ExcludedDisc{{140, 120}, 5}});
  ASSERT_EQ(f.out.size(), 2u);  // split in two by the disc
  EXPECT_EQ(f.out[0].cells + f.out[1].cells, 39 - 11);
  for (const FrontierCluster& c : f.out) EXPECT_GT(std::abs(c.nearest.y - 120), 5);
}

// More frontiers than kMaxFrontierClusters: the cheapest are kept, the others counted.
TEST(FrontierClusters, BeyondCapacityTheCheapestAreKept) {
  Fixture f;
  f.box = {0, 0, 511, 511};
  f.paint(40, 40, 470, 470, kFree);
  std::size_t holes = 0;
  for (int y = 50; y < 460; y += 6)
    for (int x = 50; x < 460 && holes < kMaxFrontierClusters + 40; x += 6, ++holes)
      f.grid->set({static_cast<int16_t>(x), static_cast<int16_t>(y)}, 0);
  f.paint(40, 40, 470, 40, kWall);
  f.paint(40, 470, 470, 470, kWall);
  f.paint(40, 40, 40, 470, kWall);
  f.paint(470, 40, 470, 470, kWall);
  f.find({60, 48}, 1);
  EXPECT_EQ(f.out.size(), kMaxFrontierClusters);
  EXPECT_EQ(f.finder->dropped(), 40u);
  for (std::size_t i = 1; i < f.out.size(); ++i) EXPECT_LE(f.out[i - 1].cost, f.out[i].cost);
  // The hole beside the start is among them.
  EXPECT_LE(f.out[0].cost, 60);
}

}  // namespace
}  // namespace kestrel::exploration
