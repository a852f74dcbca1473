#pragma once
// Where one scan shows free space around the laser, on a small grid: a cell is free when a ray
// of the scan crossed it (or a beam with nothing in range: open space) and no return lies
// within a clearance of it. Two clearances are asked for, so that a caller can prefer the
// middle of a door to its edge. Cells no ray crossed, behind a return, beyond the grid, or in
// the directions of beams that said nothing (deflected, dropped out, too near) are not free:
// the scan cannot vouch for them.
//
// For the flight home's stall (mission/trail_alignment.hpp): hundreds of points are asked
// about once, so the scan is drawn once and each point is a look-up, in whole cells where the
// caller can. Integer rays (Q8 fixed point, half a cell a step), one integer rotation per
// beam, and the 3-4 chamfer distance to the returns (core/chamfer_distance.hpp: within 8 % of
// the Euclidean, so a clearance may be met a few centimetres short), for the FPU-less Verdex.
#include <array>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel {

class ScanFreeSpace {
 public:
  static constexpr int kSide = 64;  // cells a side, the laser in the middle
  static constexpr float kCellM = 0.1f;
  static constexpr float kReachM = kCellM * (kSide / 2 - 1);  // rays are drawn this far

  struct Cell {
    int x = 0, y = 0;
  };
  enum class Clearance : uint8_t { kNotFree, kNear, kWide };

  // Draws `scan` taken from `laser` (world frame: beam i points along laser.theta +
  // scan.angle_of(i)). Clearances in metres, 0 < near_m <= wide_m <= 1. kInvalidArgument (and
  // nothing free) for a non-finite pose, bad clearances or a scan without beams or angle step.
  Status build(const LaserScan& scan, const Pose2& laser, float near_m, float wide_m);

  // The cell holding a world point; beyond the grid (or not finite) a cell outside it.
  Cell cell_of(Point2 world) const;
  // Seen by a ray and at least near_m (kNear) or wide_m too (kWide) from every return.
  Clearance at(Cell c) const;

 private:
  static constexpr uint8_t kSeen = 0x80;     // a ray crossed the cell
  static constexpr uint8_t kDistance = 0x7f; // chamfer units (a third of a cell) to a return, saturating

  void draw_ray(int32_t x_q8, int32_t y_q8, int32_t step_x_q8, int32_t step_y_q8, int steps, bool ends_at_return);
  void chamfer();
  uint8_t& cell(int x, int y) { return cells_[static_cast<std::size_t>(y * kSide + x)]; }

  std::array<uint8_t, kSide * kSide> cells_{};
  Point2 corner_;  // world position of cell (0, 0)'s lower-left corner
  uint8_t near_units_ = 0, wide_units_ = 0;
  bool built_ = false;
};

}  // namespace kestrel
