#include "kestrel/exploration/frontier_clusters.hpp"

#include <algorithm>

namespace kestrel::exploration {

using planning::Cell;
using planning::CellBox;
using planning::GridSearch;
using planning::OccupancyGrid;

bool FrontierClusterFinder::is_frontier(const OccupancyGrid& grid, int x, int y) {
  if (!planning::on_grid(x, y) || !planning::occupancy::is_free(grid.at(x, y))) return false;
  constexpr int kN[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (const auto& d : kN) {
    const int nx = x + d[0], ny = y + d[1];
    if (planning::on_grid(nx, ny) && planning::occupancy::is_unknown(grid.at(nx, ny))) return true;
  }
  return false;
}

void FrontierClusterFinder::find(const OccupancyGrid& grid, const GridSearch& search, const CellBox& box,
                                 uint16_t min_cells, std::span<const ExcludedDisc> excluded, FrontierClusters& out) {
  find_impl(grid, search, box, min_cells, excluded, nullptr, 0, out);
}

void FrontierClusterFinder::find(const OccupancyGrid& grid, const GridSearch& search, const CellBox& box,
                                 uint16_t min_cells, std::span<const ExcludedDisc> excluded,
                                 const planning::ObstacleDistance& distance, uint8_t open, FrontierClusters& out) {
  find_impl(grid, search, box, min_cells, excluded, &distance, open, out);
}

void FrontierClusterFinder::find_impl(const OccupancyGrid& grid, const GridSearch& search, const CellBox& box,
                                      uint16_t min_cells, std::span<const ExcludedDisc> excluded,
                                      const planning::ObstacleDistance* distance, uint8_t open, FrontierClusters& out) {
  const auto usable = [&](int x, int y) {
    if (!is_frontier(grid, x, y)) return false;
    for (const ExcludedDisc& d : excluded)
      if (d.contains(x, y)) return false;
    return true;
  };
  out.clear();
  dropped_ = 0;
  inaccessible_ = 0;
  const CellBox b = box.grown(0);  // clipped to the grid
  seen_.fill(0);  // 32 KiB
  if (b.empty()) return;
  for (int y = b.y0; y <= b.y1; ++y) {
    for (int x = b.x0; x <= b.x1; ++x) {
      if (test(seen_, x, y) || !usable(x, y)) continue;
      // One frontier, breadth first over 8-neighbours that are frontier cells.
      std::size_t head = 0, tail = 0;
      queue_[tail++] = {static_cast<int16_t>(x), static_cast<int16_t>(y)};
      set(seen_, x, y);
      FrontierCluster c;
      c.cost = GridSearch::kUnreached;
      bool in_the_open = distance == nullptr;
      float sx = 0, sy = 0;
      uint32_t n = 0;
      while (head < tail) {
        const Cell q = queue_[head++];
        ++n;
        const Point2 p = grid.geometry().centre_of(q);
        sx += p.x;
        sy += p.y;
        if (!in_the_open && distance->at(q) >= open) in_the_open = true;
        const uint16_t k = search.cost(q);
        if (k < c.cost) {
          c.cost = k;
          c.nearest = q;
        }
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = q.x + dx, ny = q.y + dy;
            if ((dx == 0 && dy == 0) || !b.contains(nx, ny) || test(seen_, nx, ny) || !usable(nx, ny)) continue;
            if (tail == kMaxFrontierQueue) continue;  // split: the rest starts frontiers of its own
            set(seen_, nx, ny);
            queue_[tail++] = {static_cast<int16_t>(nx), static_cast<int16_t>(ny)};
          }
        }
      }
      c.cells = static_cast<uint16_t>(std::min<uint32_t>(n, 0xFFFF));
      c.centroid = {sx / static_cast<float>(n), sy / static_cast<float>(n)};
      if (c.cells < min_cells) continue;
      if (c.cost == GridSearch::kUnreached) {
        if (in_the_open) ++inaccessible_;
        continue;
      }
      if (out.full()) {
        // Keep the cheapest: replace the dearest if this one is cheaper.
        auto worst = std::max_element(out.begin(), out.end(), [](const FrontierCluster& a, const FrontierCluster& b2) {
          return a.cost < b2.cost;
        });
        ++dropped_;
        if (c.cost < worst->cost) *worst = c;
        continue;
      }
      (void)out.push_back(c);
    }
  }
  std::sort(out.begin(), out.end(), [](const FrontierCluster& a, const FrontierCluster& b2) {
    return a.cost != b2.cost ? a.cost < b2.cost : a.cells > b2.cells;
  });
}

}  // namespace kestrel::exploration
