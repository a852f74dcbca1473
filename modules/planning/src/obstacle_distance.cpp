#include "kestrel/planning/obstacle_distance.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::planning {
namespace {

inline uint8_t plus(uint8_t d, int w) { return static_cast<uint8_t>(std::min<int>(ObstacleDistance::kFar, d + w)); }

}  // namespace

uint8_t ObstacleDistance::units_of(float metres, float cell_m) {
  if (!(metres > 0.0f) || !(cell_m > 0.0f)) return 0;
  // Up, but not for float noise: 0.36 m of 12 cm cells is 9 units, not 10.
  const float u = std::ceil(metres / cell_m * static_cast<float>(kPerCell) - 1e-4f);
  return u >= static_cast<float>(kFar) ? kFar : static_cast<uint8_t>(u);
}

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
  // Forward pass: neighbours above-left, above, above-right (y - 1) and left.
  for (int y = box_.y0; y <= box_.y1; ++y) {
    for (int x = box_.x0; x <= box_.x1; ++x) {
      uint8_t& d = d_[cell_index(x, y)];
      if (d == 0) continue;
      if (x > box_.x0) d = std::min(d, plus(d_[cell_index(x - 1, y)], 3));
      if (y > box_.y0) {
        const std::size_t up = cell_index(x, y - 1);
        d = std::min(d, plus(d_[up], 3));
        if (x > box_.x0) d = std::min(d, plus(d_[up - 1], 4));
        if (x < box_.x1) d = std::min(d, plus(d_[up + 1], 4));
      }
    }
  }
  // Backward pass: the mirror image.
  for (int y = box_.y1; y >= box_.y0; --y) {
    for (int x = box_.x1; x >= box_.x0; --x) {
      uint8_t& d = d_[cell_index(x, y)];
      if (d == 0) continue;
      if (x < box_.x1) d = std::min(d, plus(d_[cell_index(x + 1, y)], 3));
      if (y < box_.y1) {
        const std::size_t down = cell_index(x, y + 1);
        d = std::min(d, plus(d_[down], 3));
        if (x < box_.x1) d = std::min(d, plus(d_[down + 1], 4));
        if (x > box_.x0) d = std::min(d, plus(d_[down - 1], 4));
      }
    }
  }
}

}  // namespace kestrel::planning
