#pragma once
// The global planner of paper 003 (section 3.3, ROS navigation's Dijkstra): the cheapest path
// cost from the vehicle's cell to every cell it can reach, over the grid's free cells that are
// not within the lethal distance of an obstacle, 8-connected (a straight step costs 10, a
// diagonal 14), each step dearer by a penalty that grows towards the lethal distance, so paths
// keep to the middle of doors and corridors. One search answers "how far is every frontier".
//
// Dial's algorithm: the step costs are small integers, so the open cells wait in a ring of
// kBuckets cost buckets instead of a heap; an improved cell is queued again and its stale entry
// skipped. The entries live in a fixed pool (kMaxOpen): more open at once (a wave front longer
// than that) is kCapacityExceeded, never an allocation. Integer only.
//
// A vehicle that stands within the lethal distance (pushed there by a gust or an estimate's
// jump) may still leave: from a lethal cell, a step to a neighbour no nearer an obstacle is
// allowed.
#include <array>
#include <cstdint>

#include "kestrel/core/static_vector.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/planning/grid_geometry.hpp"
#include "kestrel/planning/obstacle_distance.hpp"
#include "kestrel/planning/occupancy_grid.hpp"

namespace kestrel::planning {

struct SearchCosts {
  uint8_t lethal = 0;        // obstacle distance (chamfer units) below which a cell is not entered
  uint8_t soft = 0;          // ... below which a step costs extra (>= lethal)
  uint8_t soft_penalty = 0;  // extra cost of a straight step at the lethal edge, falling linearly
                             // to 0 at soft (a diagonal's is 1.4 times); at most kMaxPenalty
  // Coastal navigation (Roy, Burgard, Fox and Thrun, ICRA 1999): a laser of short reach
  // localises only where it sees walls, so a cell at least `far` from every obstacle costs
  // far_penalty more per straight step (0: off; at most kMaxPenalty with soft_penalty).
  uint8_t far = 0;
  uint8_t far_penalty = 0;
  static constexpr uint8_t kMaxPenalty = 60;
  Status validate() const;
};

inline constexpr std::size_t kMaxPathCells = 2048;  // 245 m of 12 cm cells
using PathCells = StaticVector<Cell, kMaxPathCells>;

class GridSearch {
 public:
  static constexpr uint16_t kUnreached = 0xFFFF;
  static constexpr std::size_t kBuckets = 128;  // > the dearest step, 14 + 1.4 * kMaxPenalty
  static constexpr std::size_t kMaxOpen = 16384;

  // Costs from `start` to every reachable cell of `box` (others stay kUnreached). kInvalidArgument
  // for costs that fail validate(); kOutOfRange for a start outside the box; kCapacityExceeded
  // when the open pool overflows (the costs are then incomplete and must not be used).
  Status run(const OccupancyGrid& grid, const ObstacleDistance& distance, const CellBox& box, Cell start,
             const SearchCosts& costs);

  uint16_t cost(int x, int y) const { return box_.contains(x, y) ? cost_[cell_index(x, y)] : kUnreached; }
  uint16_t cost(Cell c) const { return cost(c.x, c.y); }
  bool reached(Cell c) const { return cost(c) != kUnreached; }
  Cell start() const { return start_; }
  const CellBox& box() const { return box_; }
  // The most entries open at once in the last run (the pool's high-water mark).
  std::size_t peak_open() const { return peak_open_; }

  // The cells of the cheapest path from the start to `goal`, start first, found by descending
  // the cost field (each step to the neighbour of least cost). kNotFound for a goal not reached;
  // kCapacityExceeded for a path of more than kMaxPathCells cells (out holds its first part).
  Status path_to(Cell goal, PathCells& out) const;

 private:
  bool push(uint32_t cell, uint16_t c);

  std::array<uint16_t, kGridCells> cost_{};
  std::array<uint32_t, kMaxOpen> entry_cell_{};
  std::array<uint16_t, kMaxOpen> entry_next_{};
  std::array<uint16_t, kBuckets> bucket_head_{};
  uint16_t free_head_ = 0;
  std::size_t open_ = 0;
  std::size_t peak_open_ = 0;
  CellBox box_{};
  Cell start_{};
};

}  // namespace kestrel::planning
