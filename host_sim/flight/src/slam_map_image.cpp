#include "kestrel/flight/slam_map_image.hpp"

#include <algorithm>

namespace kestrel::flight {

output::GridImage slam_map_image(const slam::SlamMap& map) {
  output::GridImage g;
  int x0 = slam::kMapSide, y0 = slam::kMapSide, x1 = -1, y1 = -1;
  for (int cy = 0; cy < slam::kMapSide; ++cy) {
    for (int cx = 0; cx < slam::kMapSide; ++cx) {
      if (map.at(cx, cy) == slam::kUnknown) continue;
      x0 = std::min(x0, cx);
      x1 = std::max(x1, cx);
      y0 = std::min(y0, cy);
      y1 = std::max(y1, cy);
    }
  }
  if (x1 < 0) return g;
  const int margin = std::max(1, static_cast<int>(1.0f / map.cell_m()));
  x0 = std::max(0, x0 - margin);
  y0 = std::max(0, y0 - margin);
  x1 = std::min(slam::kMapSide - 1, x1 + margin);
  y1 = std::min(slam::kMapSide - 1, y1 + margin);
  g.width = x1 - x0 + 1;
  g.height = y1 - y0 + 1;
  g.resolution_m = map.cell_m();
  // The corner of cell (x0, y0): a sub-cell position of whole cells, in the world.
  g.origin_x_m = map.sub_to_x_m(x0 * slam::kSub);
  g.origin_y_m = map.sub_to_y_m(y0 * slam::kSub);
  g.cells.resize(static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height));
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const uint8_t v = map.at(x0 + x, y0 + y);
      uint8_t out = output::kPgmUnknown;
      if (v <= kSlamWallLevel) out = output::kPgmOccupied;
      if (v >= kSlamFreeLevel) out = output::kPgmFree;
      g.cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(x)] = out;
    }
  }
  return g;
}

}  // namespace kestrel::flight
