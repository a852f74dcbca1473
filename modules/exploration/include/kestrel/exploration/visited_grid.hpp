#pragma once
// Where the vehicle has flown, on a coarse bit grid that outlives the SRT-Star tree. Section
// V's time limit erases the tree and the new root knows nothing of the rooms already explored:
// its random frontier choice sends the vehicle back through them as often as on into rooms it
// has never entered, and over 30 minutes that choice is what decides whether the last rooms
// are reached (EXPERIMENTS.md, Not done). With this memory the planner draws first among the
// frontiers that lie where the vehicle has not been (SrtParams::prefer_unvisited).
//
// kSide x kSide cells of kCellM, centred on the first pose marked (64 m x 64 m: every built-in
// world from its start); a mark sets the cell under the pose and its eight neighbours, so a
// frontier counts as visited within about a cell and a half of the path flown. Outside the
// grid nothing is marked and everything is unvisited.
//
// Two more layers hold what the laser showed, for srt.retrace_target = frontier: the cells a
// node's beams crossed (seen free) and the cells its returns fell in (walls; a wall stays one
// when a later beam crosses the cell, since 1 m cells hold both the wall and the free space in
// front of it). A frontier cell is one never flown, seen or walled, with a 4-neighbour seen free
// and not a wall: unexplored space next to explored space, where the cells behind a wall, whose
// neighbours on the near side are walls, are not. 1.5 KiB, no heap.
#include <array>
#include <cstddef>
#include <cstdint>

#include "kestrel/core/se2.hpp"

namespace kestrel::exploration {

class VisitedGrid {
 public:
  static constexpr int kSide = 64;
  static constexpr float kCellM = 1.0f;

  void clear();
  // Marks the neighbourhood of (x, y), world frame; the first mark after clear() fixes the
  // grid's centre. Non-finite positions are ignored. A place counted as flown without having
  // been flown (a waypoint the time limit gave up, and its frontier) does not widen the extent,
  // which stands for the building's outline as far as the vehicle has been.
  enum class Extent : uint8_t { kWiden, kKeep };
  void mark(Point2 p, Extent extent = Extent::kWiden);
  // Widens the extent to p's cell without marking it: a laser return, so the building reaches
  // at least there. Ignored before the first mark, off the grid, or for a non-finite p.
  void widen_extent(Point2 p);
  bool visited(Point2 p) const;
  std::size_t marked_cells() const;

  // The laser's layers. Ignored before the first mark(), off the grid, or for a non-finite p;
  // neither widens the extent.
  void mark_seen(Point2 p);
  void mark_wall(Point2 p);
  bool seen_cell(int ix, int iy) const;  // false outside the grid
  bool wall_cell(int ix, int iy) const;  // false outside the grid
  // Never flown, seen or walled, and beside (sharing an edge) a cell seen free that is not a
  // wall. Not bounded by the extent: the free space seen through a door, beyond every return,
  // is inside the building all the same, and the adjacency already keeps to what was seen.
  bool frontier_cell(int ix, int iy) const;

  // Cell of p, or false outside the grid (or before the first mark).
  bool cell_of(Point2 p, int& ix, int& iy) const;
  bool visited_cell(int ix, int iy) const;  // false outside the grid
  // Inside the extent: the bounding box of the marked cells and the returns it was widened to
  // (false before the first mark).
  bool in_extent(int ix, int iy) const;

 private:
  void set(int ix, int iy, Extent extent);
  void include(int ix, int iy);  // widens the extent to a cell inside the grid

  using Layer = std::array<uint64_t, kSide * kSide / 64>;
  static bool bit(const Layer& layer, int ix, int iy);
  void set_bit(Layer& layer, Point2 p) const;
  bool open_cell(int ix, int iy) const { return seen_cell(ix, iy) && !wall_cell(ix, iy); }

  Layer bits_{};  // flown
  Layer seen_{};
  Layer wall_{};
  Point2 origin_{};  // world position of cell (0, 0)'s corner
  int min_ix_ = kSide, min_iy_ = kSide, max_ix_ = -1, max_iy_ = -1;  // of the marked cells
  bool anchored_ = false;
};

}  // namespace kestrel::exploration
