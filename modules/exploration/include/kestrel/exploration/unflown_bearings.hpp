#pragma once
// How much of the building the vehicle has not flown lies in each direction from a point, on
// VisitedGrid's 1 m cells: the global half of srt.steer_unflown (srt_star_planner.hpp).
//
// After section V's restarts a fresh SRT-Star tree knows only what it sees from where the
// vehicle is, and its random frontier choice, repeated node by node, keeps the vehicle near
// there: in gt-building's 30-minute UTM-30LX flights the trees that lost the west rooms lived in
// the east half (EXPERIMENTS.md, Not done). A frontier's own cell says little (VisitedGrid's
// prefer_unvisited: a frontier 3.5 m away is unflown in nearly every direction); the cells
// beyond it do. Counted here: the unflown cells within kReachCells of the node, inside the
// grid's extent (the bounding box of the cells flown and of the returns the planner widened it
// to: the building's outline as far as the laser has seen it; cells outside it are more often
// outside the walls than rooms), by bearing, in kBins bins. A box: in an L- or U-shaped
// building it takes in space outside the walls too, which then draws the steering.
//
// Each cell weighs kReachCells / its distance in cells, rounded (16 beside the node, 1 at the
// reach). Counted alike, a corridor's cone towards a far unflown end held more cells than a
// door into an unflown room beside the node, and a fresh tree at gt-building's start went east
// and left the south-west room for ever (missed on 10 of 30 steered UTM-30LX flights); the
// URG-04LX's steered flights crossed the corridor again and again (every room on 4 of 30).
// Weighted: 18 and 21 of 30 (main at 9be8eab; EXPERIMENTS.md).
//
// The retrace may count the coarse grid's frontier cells instead (RetraceTarget::kFrontier,
// VisitedGrid::frontier_cell), weighed alike.
//
// No trigonometry per cell: each cell offset's bin and weight are tabled once, at
// construction. 2.2 KB; a count is 37.4 k instructions on the Verdex (exploration/unflown_count;
// 37.1 k before the weights), 49 k at worst (every cell in reach unflown inside the extent:
// exploration/unflown_count_all_unflown), charged 544 units (work_units.hpp).
#include <array>
#include <cstdint>

#include "kestrel/core/se2.hpp"
#include "kestrel/exploration/params.hpp"
#include "kestrel/exploration/visited_grid.hpp"

namespace kestrel::exploration {

class UnflownBearings {
 public:
  static constexpr int kBins = 36;          // 10 degrees each, centred on multiples of 10
  static constexpr int kReachCells = 16;    // 16 m: across gt-building from either end's rooms
  static constexpr int kHalfConeBins = 3;   // a frontier's score: its bin and 3 either side,
                                            // a cone of +-35 degrees
  static constexpr uint8_t kBeyondReach = 0xFF;

  UnflownBearings();

  // Counts the unflown cells (or the frontier cells) around `from` by bearing. Returns the work
  // units it cost.
  uint32_t count(const VisitedGrid& grid, Point2 from, RetraceTarget what = RetraceTarget::kUnflown);
  // Weighted unflown cells within +-kHalfConeBins bins of `bearing_rad` (world frame) at the
  // last count; 0 for a non-finite bearing.
  uint32_t score(float bearing_rad) const;
  uint32_t total() const;  // every unflown cell counted, weighted

 private:
  static constexpr int kSide = 2 * kReachCells + 1;
  std::array<uint8_t, kSide * kSide> bin_of_offset_{};  // kBeyondReach outside the disc
  std::array<uint8_t, kSide * kSide> weight_of_offset_{};  // kReachCells / distance, rounded
  std::array<uint16_t, kBins> cells_{};
};

}  // namespace kestrel::exploration
