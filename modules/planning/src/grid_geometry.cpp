#include "kestrel/planning/grid_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::planning {

void CellBox::include(int x, int y) {
  if (empty()) {
    x0 = x1 = x;
    y0 = y1 = y;
    return;
  }
  x0 = std::min(x0, x);
  x1 = std::max(x1, x);
  y0 = std::min(y0, y);
  y1 = std::max(y1, y);
}

CellBox CellBox::grown(int n) const {
  if (empty()) return *this;
  return {std::max(0, x0 - n), std::max(0, y0 - n), std::min(kGridSide - 1, x1 + n), std::min(kGridSide - 1, y1 + n)};
}

Result<GridGeometry> GridGeometry::around(Point2 centre, float cell_m) {
  if (!(cell_m >= 0.02f && cell_m <= 1.0f) || !std::isfinite(centre.x) || !std::isfinite(centre.y))
    return Status::kInvalidArgument;
  GridGeometry g;
  g.cell_m = cell_m;
  const float half = 0.5f * static_cast<float>(kGridSide) * cell_m;
  g.origin = {centre.x - half, centre.y - half};
  return g;
}

bool GridGeometry::to_cell(float x, float y, Cell& out) const {
  const float fx = (x - origin.x) / cell_m, fy = (y - origin.y) / cell_m;
  // Written so that NaN fails too.
  if (!(fx >= 0.0f && fy >= 0.0f && fx < static_cast<float>(kGridSide) && fy < static_cast<float>(kGridSide)))
    return false;
  out = {static_cast<int16_t>(fx), static_cast<int16_t>(fy)};
  return true;
}

}  // namespace kestrel::planning
