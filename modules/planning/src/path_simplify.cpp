#include "kestrel/planning/path_simplify.hpp"

#include <algorithm>
#include <cstdlib>

namespace kestrel::planning {

bool line_clear(const OccupancyGrid& grid, const ObstacleDistance& distance, Cell a, Cell b, uint8_t min_distance,
                uint8_t max_distance) {
  // Bresenham, every cell the line's samples fall in.
  int x = a.x, y = a.y;
  const int dx = std::abs(b.x - a.x), dy = -std::abs(b.y - a.y);
  const int sx = a.x < b.x ? 1 : -1, sy = a.y < b.y ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    if (!on_grid(x, y) || !occupancy::is_free(grid.at(x, y))) return false;
    const uint8_t d = distance.at(x, y);
    if (d < min_distance || d > max_distance) return false;
    if (x == b.x && y == b.y) return true;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y += sy;
    }
  }
}

Status simplify_path(const OccupancyGrid& grid, const ObstacleDistance& distance, const PathCells& cells,
                     PathPoints& out, uint8_t coastal) {
  out.clear();
  if (cells.empty()) return Status::kNoData;
  const GridGeometry& g = grid.geometry();
  std::size_t anchor = 0;
  (void)out.push_back(g.centre_of(cells[0]));
  while (anchor + 1 < cells.size() && !out.full()) {
    // The farthest cell reachable in a straight line; the next one always is (neighbours).
    std::size_t reach = anchor + 1;
    uint8_t along = distance.at(cells[anchor]), farthest = along;
    for (std::size_t j = anchor + 1; j < cells.size(); ++j) {
      along = std::min(along, distance.at(cells[j]));
      farthest = std::max(farthest, distance.at(cells[j]));
      const uint8_t max_d = coastal > 0 ? std::max(farthest, coastal) : ObstacleDistance::kFar;
      if (j > anchor + 1 && !line_clear(grid, distance, cells[anchor], cells[j], along, max_d)) break;
      reach = j;
    }
    (void)out.push_back(g.centre_of(cells[reach]));
    anchor = reach;
  }
  return Status::kOk;
}

}  // namespace kestrel::planning
