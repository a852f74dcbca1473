#pragma once
// A planned path of cells made into a few straight legs for the vehicle to fly: from each
// corner, the leg runs to the farthest cell of the path that a straight line reaches over
// known free cells, none of them nearer an obstacle than the path itself came along the cells
// it replaces (so the shortcut never hugs a wall more than the planner's path did).
#include <cstdint>

#include "kestrel/core/se2.hpp"
#include "kestrel/core/static_vector.hpp"
#include "kestrel/planning/grid_search.hpp"

namespace kestrel::planning {

inline constexpr std::size_t kMaxPathPoints = 64;
using PathPoints = StaticVector<Point2, kMaxPathPoints>;

// Whether every cell on the straight line from a to b (both included) is free in `grid`, at
// least `min_distance` (chamfer units) from an obstacle and at most `max_distance`.
bool line_clear(const OccupancyGrid& grid, const ObstacleDistance& distance, Cell a, Cell b, uint8_t min_distance,
                uint8_t max_distance = ObstacleDistance::kFar);

// The corners of `cells` (start first) in the navigation frame: the first cell, each corner,
// the last cell. A path needing more than kMaxPathPoints corners keeps its first ones: it is
// flown towards its end and planned again before then. kNoData for an empty path. With
// `coastal` (a coastal search's `far`, non-zero), a shortcut also goes no farther from the walls
// than the path came, or than `coastal`, whichever is more: it keeps to the coast too.
Status simplify_path(const OccupancyGrid& grid, const ObstacleDistance& distance, const PathCells& cells,
                     PathPoints& out, uint8_t coastal = 0);

}  // namespace kestrel::planning
