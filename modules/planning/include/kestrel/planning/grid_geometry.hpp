#pragma once
// The cells every planning grid shares: kGridSide x kGridSide square cells around home, in the
// navigation frame. 512 cells of 12 cm span 61 m, the compact SLAM's extent: a building up to
// 30 m from take-off in any direction.
#include <cstddef>
#include <cstdint>

#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::planning {

inline constexpr int kGridSide = 512;
inline constexpr std::size_t kGridCells = std::size_t{kGridSide} * kGridSide;

struct Cell {
  int16_t x = 0;
  int16_t y = 0;
  friend bool operator==(const Cell& a, const Cell& b) { return a.x == b.x && a.y == b.y; }
};

inline bool on_grid(int x, int y) { return x >= 0 && y >= 0 && x < kGridSide && y < kGridSide; }
inline std::size_t cell_index(int x, int y) {
  return static_cast<std::size_t>(y) * kGridSide + static_cast<std::size_t>(x);
}

// A rectangle of cells, corners included; empty while x0 > x1.
struct CellBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x0 > x1 || y0 > y1; }
  bool contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
  void include(int x, int y);
  // Grown by n cells on every side, clipped to the grid.
  CellBox grown(int n) const;
};

struct GridGeometry {
  float cell_m = 0.12f;
  Point2 origin;  // navigation-frame position of cell (0, 0)'s lower-left corner

  // Centred on `centre` (home); kInvalidArgument unless 0.02 <= cell_m <= 1 and both finite.
  static Result<GridGeometry> around(Point2 centre, float cell_m);
  // The cell holding a point; false for a point off the grid or not finite.
  bool to_cell(float x, float y, Cell& out) const;
  Point2 centre_of(Cell c) const {
    return {origin.x + (static_cast<float>(c.x) + 0.5f) * cell_m, origin.y + (static_cast<float>(c.y) + 0.5f) * cell_m};
  }
};

}  // namespace kestrel::planning
