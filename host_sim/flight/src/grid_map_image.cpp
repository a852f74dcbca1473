#include "kestrel/flight/grid_map_image.hpp"

#include <algorithm>

namespace kestrel::flight {

output::GridImage grid_map_image(const planning::OccupancyGrid& grid) {
  output::GridImage g;
  if (grid.drawn().empty() || !grid.configured()) return g;
  const planning::GridGeometry& geo = grid.geometry();
  const planning::CellBox box = grid.drawn().grown(std::max(1, static_cast<int>(1.0f / geo.cell_m)));
  g.width = box.x1 - box.x0 + 1;
  g.height = box.y1 - box.y0 + 1;
  g.resolution_m = geo.cell_m;
  g.origin_x_m = geo.origin.x + static_cast<float>(box.x0) * geo.cell_m;
  g.origin_y_m = geo.origin.y + static_cast<float>(box.y0) * geo.cell_m;
  g.cells.resize(static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height));
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const uint8_t v = grid.at(box.x0 + x, box.y0 + y);
      uint8_t out = output::kPgmUnknown;
      if (planning::occupancy::is_occupied(v)) out = output::kPgmOccupied;
      if (planning::occupancy::is_free(v)) out = output::kPgmFree;
      g.cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(x)] = out;
    }
  }
  return g;
}

}  // namespace kestrel::flight
