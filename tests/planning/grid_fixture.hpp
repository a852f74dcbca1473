#pragma once
// Grids painted cell by cell for the planner's tests: every cell of a box free, walls as
// occupied cells.
#include <memory>

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

}  // namespace kestrel::planning::test
