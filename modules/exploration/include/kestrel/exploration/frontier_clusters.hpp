#pragma once
// The frontiers of paper 003's grid exploration (section 3.2, after Yamauchi 1997): a frontier
// cell is a known free cell with an unknown cell beside it (sharing an edge); a frontier is a
// set of such cells touching each other (8-connected), accessible when it is at least as wide
// as the vehicle needs and the planner's search reached one of its cells. Each is reported with
// the cell the vehicle reaches cheapest: where the flight to it ends.
#include <array>
#include <cstdint>
#include <span>

#include "kestrel/core/static_vector.hpp"
#include "kestrel/planning/grid_search.hpp"
#include "kestrel/planning/obstacle_distance.hpp"
#include "kestrel/planning/occupancy_grid.hpp"

namespace kestrel::exploration {

inline constexpr std::size_t kMaxFrontierClusters = 128;
inline constexpr std::size_t kMaxFrontierQueue = 4096;  // cells of one frontier; a longer one is split

struct FrontierCluster {
  planning::Cell nearest;  // the cluster's cell of least path cost
  uint16_t cost = 0;       // its path cost (planning::GridSearch units: 10 per straight cell)
  uint16_t cells = 0;      // frontier cells in the cluster
  Point2 centroid;         // navigation frame, m
};
using FrontierClusters = StaticVector<FrontierCluster, kMaxFrontierClusters>;

// A disc of cells no frontier may use (a blacklisted goal): centre and radius in cells.
struct ExcludedDisc {
  planning::Cell centre;
  int radius_cells = 0;
  bool contains(int x, int y) const {
    const int dx = x - centre.x, dy = y - centre.y;
    return dx * dx + dy * dy <= radius_cells * radius_cells;
  }
};

class FrontierClusterFinder {
 public:
  // The accessible frontiers within `box` with at least min_cells cells, cheapest first; the
  // frontier cells inside an excluded disc are left out before the cells are grouped, so a
  // blacklisted goal takes its own part of a long frontier and not the rest. Frontiers beyond
  // kMaxFrontierClusters are dropped (the most expensive; counted in dropped()). Cells on the
  // grid's border have no unknown neighbour off the grid.
  void find(const planning::OccupancyGrid& grid, const planning::GridSearch& search, const planning::CellBox& box,
            uint16_t min_cells, std::span<const ExcludedDisc> excluded, FrontierClusters& out);
  // The same, and inaccessible() counts only the frontiers with a cell at least `open` (chamfer
  // units) from every obstacle: one the search could have entered, had anything led there.
  void find(const planning::OccupancyGrid& grid, const planning::GridSearch& search, const planning::CellBox& box,
            uint16_t min_cells, std::span<const ExcludedDisc> excluded, const planning::ObstacleDistance& distance,
            uint8_t open, FrontierClusters& out);
  // Whether a cell is a frontier cell (free, with an unknown 4-neighbour).
  static bool is_frontier(const planning::OccupancyGrid& grid, int x, int y);
  uint32_t dropped() const { return dropped_; }
  // Frontiers of the last find() long enough but not reached by the search, with a cell in the
  // open (see find): behind walls on the grid (in a drifted estimate's map, walls drawn where
  // there are none), not slots along walls or pockets beside a keep-out box.
  uint32_t inaccessible() const { return inaccessible_; }
  // Every frontier cell of the last find(), accessible or not (for pictures).
  bool was_frontier(int x, int y) const { return test(seen_, x, y); }

 private:
  using Bits = std::array<uint64_t, planning::kGridCells / 64>;
  static bool test(const Bits& b, int x, int y) {
    const std::size_t i = planning::cell_index(x, y);
    return (b[i >> 6] >> (i & 63)) & 1u;
  }
  static void set(Bits& b, int x, int y) {
    const std::size_t i = planning::cell_index(x, y);
    b[i >> 6] |= uint64_t{1} << (i & 63);
  }
  Bits seen_{};
  std::array<planning::Cell, kMaxFrontierQueue> queue_{};
  uint32_t dropped_ = 0;
  uint32_t inaccessible_ = 0;
  void find_impl(const planning::OccupancyGrid& grid, const planning::GridSearch& search, const planning::CellBox& box,
                 uint16_t min_cells, std::span<const ExcludedDisc> excluded, const planning::ObstacleDistance* distance,
                 uint8_t open, FrontierClusters& out);
};

}  // namespace kestrel::exploration
