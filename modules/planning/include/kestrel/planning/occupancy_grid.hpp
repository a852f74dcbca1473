#pragma once
// The explored map of the grid frontier explorer (paper 003 section 3.2, after Yamauchi 1997):
// one byte a cell, unknown until a ray crosses it, then a count of hits against misses. Drawn
// from the laser at the filter's pose (the SLAM's corrections move that pose, and with it what
// is drawn next). Integer only, for the FPU-less Verdex: the beams' directions are tabled once
// per laser, and each ray walks its cells in Q8 fixed point.
//
// Which beams draw: a return within reach marks its cell occupied and frees the cells its ray
// crossed, but for the one just before the return, which it only makes known (a wall seen
// aslant would otherwise be worn away by its neighbours' rays, and left unknown that row
// would be a frontier along every wall); a return beyond reach frees its ray up to reach; a
// beam with nothing within the sensor's range (kNoReturn) frees its ray up to the range or
// reach, whichever is shorter, unless no_return_is_free is off (paper 004's modified CoreSLAM
// clears nothing there: glass and open space look alike; the operator's keep-out boxes tell
// the planner of glass); the other codes (too near, dropout, deflected) draw nothing. The
// vehicle's own disc (footprint_m) is free: the laser cannot see the cells under and behind
// it, and it stands there. A scan counts once per cell: however many of its beams pass
// through a cell, it is missed once, and hit once (the beams of one scan are one look; a wall's
// cell that rays graze on its far side, ten beams a scan at 2 m, would otherwise be cleared by
// the scan that also hits it).
#include <array>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/planning/grid_geometry.hpp"

namespace kestrel::planning {

namespace occupancy {
inline constexpr uint8_t kUnknown = 0;  // no ray has crossed it
inline constexpr uint8_t kEven = 128;   // a first observation starts here, then +hit / -miss
inline constexpr bool is_unknown(uint8_t v) { return v == kUnknown; }
inline constexpr bool is_occupied(uint8_t v) { return v > kEven; }
inline constexpr bool is_free(uint8_t v) { return v != kUnknown && v <= kEven; }
}  // namespace occupancy

struct GridParams {
  float cell_m = 0.12f;    // 512 cells: 61 m around home
  float reach_m = 4.0f;    // rays draw up to here (the URG-04LX's range); returns beyond are not walls
  uint8_t hit_step = 40;   // a hit outweighs five misses: a wall's cell survives the rays
  uint8_t miss_step = 8;   //   that graze it, and a wall drawn where the estimate had drifted
                           //   is cleared by the rays that later pass through it
  bool no_return_is_free = true;
  float footprint_m = 0.35f;  // radius of the disc around the sensor drawn free (0: none)

  // kInvalidArgument unless 0.02 <= cell_m <= 1, 0 < reach_m <= 60, both steps in 1..127 and
  // 0 <= footprint_m <= 2.
  Status validate() const;
};

class OccupancyGrid {
 public:
  // Checks the parameters and the laser's geometry (beam_count 1..kMaxBeams, a finite, non-zero
  // step), tables the beams' directions and forgets the map. The grid is centred on `home`.
  Status configure(const GridParams& params, Point2 home, uint16_t beam_count, float first_angle_rad,
                   float angle_step_rad);
  // Every cell unknown again; the configuration stays.
  void clear();

  // Draws one scan taken with the sensor at `pose` (navigation frame). kNotFound before
  // configure; kInvalidArgument for a scan of another geometry; kNotFinite for a non-finite
  // pose; kOutOfRange for a sensor off the grid. Rays are cut where they leave the grid.
  Status draw(const LaserScan& scan, const Pose2& pose);

  uint8_t at(int x, int y) const { return cells_[cell_index(x, y)]; }
  uint8_t at(Cell c) const { return at(c.x, c.y); }
  // Tests and tools: sets one cell.
  void set(Cell c, uint8_t v);

  const GridGeometry& geometry() const { return geometry_; }
  const GridParams& params() const { return params_; }
  bool configured() const { return configured_; }
  // The smallest box holding every cell ever drawn (empty before the first scan).
  const CellBox& drawn() const { return drawn_; }
  uint32_t scans_drawn() const { return scans_drawn_; }
  // Cells no longer unknown: what the laser has taught the grid (the explorer's progress).
  uint32_t known_cells() const { return known_cells_; }

 private:
  void free_cell(std::size_t i);
  void hit_cell(std::size_t i);
  // Once per scan each: the bits of this scan's look at cell i.
  bool first_look(std::size_t i, uint8_t bit);

  std::array<uint8_t, kGridCells> cells_{};
  // This scan's looks: bits 7..2 the scan's tag (1..63), bit 1 hit, bit 0 missed.
  std::array<uint8_t, kGridCells> looks_{};
  uint8_t tag_ = 0;
  std::array<int16_t, kMaxBeams> cos_q14_{}, sin_q14_{};
  GridParams params_{};
  GridGeometry geometry_{};
  uint16_t beam_count_ = 0;
  float first_angle_rad_ = 0, angle_step_rad_ = 0;
  int64_t mm_to_q8_q16_ = 0;  // range (mm) to cells in Q8, as a Q16 factor
  int32_t reach_mm_ = 0;
  int footprint_cells_ = 0;
  CellBox drawn_{};
  uint32_t scans_drawn_ = 0;
  uint32_t known_cells_ = 0;
  bool configured_ = false;
};

}  // namespace kestrel::planning
