#pragma once
// Grids painted cell by cell for the planner's tests: every cell of a box free, walls as
// occupied cells.
#include <memory>

#include "kestrel/planning/grid_search.hpp"
#include "kestrel/planning/obstacle_distance.hpp"
#include "kestrel/planning/occupancy_grid.hpp"
#include "synthetic_world.hpp"

namespace kestrel::planning::test {

inline constexpr uint8_t kFreeCell = occupancy::kEven - 40;
inline constexpr uint8_t kWallCell = occupancy::kEven + 80;

// A configured grid (12 cm cells around (0, 0), the URG-04LX's beams), all unknown.
inline std::unique_ptr<OccupancyGrid> blank_grid(GridParams p = {}) {
  const kestrel::test::LaserModel urg = kestrel::test::LaserModel::urg04lx();
  auto g = std::make_unique<OccupancyGrid>();
  (void)g->configure(p, {0, 0}, urg.beams, static_cast<float>(urg.first_angle()), static_cast<float>(urg.step()));
  return g;
}

inline void paint(OccupancyGrid& g, int x0, int y0, int x1, int y1, uint8_t v) {
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) g.set({static_cast<int16_t>(x), static_cast<int16_t>(y)}, v);
}

// A blank grid with the planner's two passes over a 101 x 101 box of it: the obstacle distance,
// then the search from `start`.
struct SearchRig {
  std::unique_ptr<OccupancyGrid> grid = blank_grid();
  std::unique_ptr<ObstacleDistance> distance = std::make_unique<ObstacleDistance>();
  std::unique_ptr<GridSearch> search = std::make_unique<GridSearch>();
  CellBox box{100, 100, 200, 200};
  Status search_from(Cell start, SearchCosts costs = {}) {
    distance->compute(*grid, box);
    return search->run(*grid, *distance, box, start, costs);
  }
};

}  // namespace kestrel::planning::test
