#pragma once
// The grid frontier explorer's occupancy grid as map.pgm / map.yaml (DESIGN.md's outputs, the
// ROS map_server convention) for a flight without the compact SLAM: the drawn part of the grid
// with a metre of margin, in map_server's trinary mode (occupied, free, unknown as the grid
// classes them).
#include "kestrel/output/pgm_map.hpp"
#include "kestrel/planning/occupancy_grid.hpp"

namespace kestrel::flight {

// An empty image (width 0) when nothing has been drawn.
output::GridImage grid_map_image(const planning::OccupancyGrid& grid);

}  // namespace kestrel::flight
