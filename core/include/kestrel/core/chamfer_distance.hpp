#pragma once
// The 3-4 chamfer distance (Borgefors 1986: within 8 % of the Euclidean) over a box of any
// grid of cells: two raster passes, integer only, for the FPU-less Verdex. Used by the
// planner's clearance over its big occupancy grid (planning::ObstacleDistance) and by the
// small grid of one scan's free space (ScanFreeSpace), which keep their distances in
// different cells (a whole byte; seven bits beside a flag).
#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>

namespace kestrel::chamfer {

inline constexpr int kPerCell = 3;   // an orthogonal step, in chamfer units
inline constexpr int kDiagonal = 4;  // a diagonal step

// A distance in metres as chamfer units of cells of cell_m, rounded up (so that "at least this
// far" stays true) but not for float noise (0.36 m of 12 cm cells is 9 units, not 10),
// saturating at cap; at least 1 for any positive distance (a clearance is never met on a seed);
// 0 for a distance or cell that is not positive (or NaN).
inline uint8_t units_of(float metres, float cell_m, uint8_t cap) {
  if (!(metres > 0.0f) || !(cell_m > 0.0f)) return 0;
  const float u = std::ceil(metres / cell_m * static_cast<float>(kPerCell) - 1e-4f);
  if (!(u < static_cast<float>(cap))) return cap;  // also inf / inf
  return u < 1.0f ? 1 : static_cast<uint8_t>(u);
}

// What the passes read and write: a cell's distance, and a smaller one stored in its place.
template <class Cells>
concept DistanceCells = requires(Cells& c, const Cells& cc, int x, int y, int d) {
  { cc.distance(x, y) } -> std::convertible_to<int>;
  c.lower(x, y, d);
};

// Every cell of [x0, x1] x [y0, y1] (inclusive, non-empty) gets the chamfer distance to the
// nearest seed, a cell that reads 0; the others must read a cap on entry, which distances
// saturate at (lower() is called only with a distance below the cell's). Cells outside the box
// are neither read nor written.
template <DistanceCells Cells>
void propagate(Cells& cells, int x0, int y0, int x1, int y1) {
  // Forward pass: neighbours left, above-left, above and above-right (y - 1).
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const int was = cells.distance(x, y);
      if (was == 0) continue;
      int d = was;
      if (x > x0) d = std::min(d, cells.distance(x - 1, y) + kPerCell);
      if (y > y0) {
        d = std::min(d, cells.distance(x, y - 1) + kPerCell);
        if (x > x0) d = std::min(d, cells.distance(x - 1, y - 1) + kDiagonal);
        if (x < x1) d = std::min(d, cells.distance(x + 1, y - 1) + kDiagonal);
      }
      if (d < was) cells.lower(x, y, d);
    }
  }
  // Backward pass: the mirror image.
  for (int y = y1; y >= y0; --y) {
    for (int x = x1; x >= x0; --x) {
      const int was = cells.distance(x, y);
      if (was == 0) continue;
      int d = was;
      if (x < x1) d = std::min(d, cells.distance(x + 1, y) + kPerCell);
      if (y < y1) {
        d = std::min(d, cells.distance(x, y + 1) + kPerCell);
        if (x < x1) d = std::min(d, cells.distance(x + 1, y + 1) + kDiagonal);
        if (x > x0) d = std::min(d, cells.distance(x - 1, y + 1) + kDiagonal);
      }
      if (d < was) cells.lower(x, y, d);
    }
  }
}

}  // namespace kestrel::chamfer
