#pragma once
// How far every cell is from the nearest occupied cell, for the planner's clearance: the 3-4
// chamfer distance (core/chamfer_distance.hpp) over a box of the grid. In units of a third of
// a cell, saturating at kFar (85 cells).
// Cells outside the box are not computed and read as kFar; unknown cells are not obstacles
// here (the planner never enters them anyway).
#include <array>
#include <cstdint>
#include <span>

#include "kestrel/core/chamfer_distance.hpp"

#include "kestrel/planning/grid_geometry.hpp"
#include "kestrel/planning/occupancy_grid.hpp"

namespace kestrel::planning {

class ObstacleDistance {
 public:
  static constexpr uint8_t kPerCell = chamfer::kPerCell;
  static constexpr uint8_t kFar = 255;

  // Seeds are the grid's occupied cells and every cell of the `blocked` boxes (operator
  // keep-outs, already in cells), within `box`.
  void compute(const OccupancyGrid& grid, const CellBox& box, std::span<const CellBox> blocked = {});
  uint8_t at(int x, int y) const { return box_.contains(x, y) ? d_[cell_index(x, y)] : kFar; }
  uint8_t at(Cell c) const { return at(c.x, c.y); }
  const CellBox& box() const { return box_; }
  // A distance in m as chamfer units, rounded up (so that "at least this far" stays true),
  // saturating at kFar.
  static uint8_t units_of(float metres, float cell_m);

 private:
  std::array<uint8_t, kGridCells> d_{};
  CellBox box_{};
};

}  // namespace kestrel::planning
