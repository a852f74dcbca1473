#include "kestrel/planning/obstacle_distance.hpp"

#include <algorithm>

namespace kestrel::planning {
namespace {

// The planner's distances for chamfer::propagate: a whole byte a cell.
struct GridDistances {
  std::array<uint8_t, kGridCells>& d;
  int distance(int x, int y) const { return d[cell_index(x, y)]; }
  void lower(int x, int y, int v) { d[cell_index(x, y)] = static_cast<uint8_t>(v); }
};

}  // namespace

uint8_t ObstacleDistance::units_of(float metres, float cell_m) { return chamfer::units_of(metres, cell_m, kFar); }

void ObstacleDistance::compute(const OccupancyGrid& grid, const CellBox& box, std::span<const CellBox> blocked) {
  box_ = box.empty() ? box : CellBox{std::max(0, box.x0), std::max(0, box.y0), std::min(kGridSide - 1, box.x1),
                                     std::min(kGridSide - 1, box.y1)};
  if (box_.empty()) return;
  for (int y = box_.y0; y <= box_.y1; ++y)
    for (int x = box_.x0; x <= box_.x1; ++x)
      d_[cell_index(x, y)] = occupancy::is_occupied(grid.at(x, y)) ? 0 : kFar;
  for (const CellBox& b : blocked) {
    for (int y = std::max(b.y0, box_.y0); y <= std::min(b.y1, box_.y1); ++y)
      for (int x = std::max(b.x0, box_.x0); x <= std::min(b.x1, box_.x1); ++x) d_[cell_index(x, y)] = 0;
  }
  GridDistances cells{d_};
  chamfer::propagate(cells, box_.x0, box_.y0, box_.x1, box_.y1);
}

}  // namespace kestrel::planning
