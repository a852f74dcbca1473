#pragma once
// The compact SLAM's map (paper 004's modified CoreSLAM, after Steux and El Hamzaoui's
// tinySLAM): one byte per cell, kWall on a wall, kFree where the laser has cleared the space,
// kUnknown where it has not looked. Every return draws a V-shaped trough across its cell,
// wall at the bottom, so that a scan's mean cell value falls smoothly as the scan slides onto
// the walls: the search (scan_fit.hpp) follows that slope.
//
// Positions inside the map are integers in 1/256 of a cell (kSub), so the map's hot loops run
// in integer arithmetic on the FPU-less Verdex; the bilinear sample between four cells is
// paper 004's "resolution artificially increased via interpolation" (section V), which gave it
// better angular matching than the cell alone.
//
// Memory: kMapSide^2 bytes = 1 MiB, DESIGN.md's SLAM map budget. At the default 6 cm cells the
// map spans 61 m, centred on the pose the SLAM started at: a 30 m arena from any start in it.
#include <array>
#include <cstdint>

#include "kestrel/core/status.hpp"

namespace kestrel::slam {

inline constexpr int kMapSide = 1024;
inline constexpr int kSubBits = 8;
inline constexpr int32_t kSub = 1 << kSubBits;  // sub-cell units per cell
inline constexpr uint8_t kWall = 0;
inline constexpr uint8_t kFree = 255;
inline constexpr uint8_t kUnknown = 128;

// A position in the map, in 1/256 cell from its corner.
struct SubPoint {
  int32_t x = 0;
  int32_t y = 0;
};

class SlamMap {
 public:
  // Every cell unknown; the map's centre at (centre_x_m, centre_y_m) of the world.
  // kInvalidArgument for a cell size outside [1 cm, 50 cm] or a non-finite centre.
  Status reset(float cell_m, float centre_x_m, float centre_y_m);

  float cell_m() const { return cell_m_; }
  // World metres to map sub-cells. Once per pose, never per point.
  SubPoint to_sub(float x_m, float y_m) const;
  float sub_to_x_m(int32_t sx) const;
  float sub_to_y_m(int32_t sy) const;

  uint8_t at(int cx, int cy) const {
    return inside(cx, cy) ? cells_[static_cast<std::size_t>(cy) * kMapSide + static_cast<std::size_t>(cx)] : kUnknown;
  }
  static bool inside(int cx, int cy) { return cx >= 0 && cy >= 0 && cx < kMapSide && cy < kMapSide; }

  // The map's value under a sub-cell position, bilinear between the four cells around it, in
  // 1/256 of a level (0 .. 255 * 256). Off the map: unknown. A cell's value stands at its
  // centre, half a cell in from its corner, where draw_return puts each return it draws.
  uint32_t sample(SubPoint p) const {
    p.x -= kSub / 2;
    p.y -= kSub / 2;
    const int32_t cx = p.x >> kSubBits, cy = p.y >> kSubBits;
    if (cx < 0 || cy < 0 || cx >= kMapSide - 1 || cy >= kMapSide - 1) return uint32_t{kUnknown} << kSubBits;
    const uint32_t fx = static_cast<uint32_t>(p.x & (kSub - 1)), fy = static_cast<uint32_t>(p.y & (kSub - 1));
    const uint8_t* c = &cells_[static_cast<std::size_t>(cy) * kMapSide + static_cast<std::size_t>(cx)];
    const uint32_t top = c[0] * (kSub - fx) + c[1] * fx;
    const uint32_t bottom = c[kMapSide] * (kSub - fx) + c[kMapSide + 1] * fx;
    return (top * (kSub - fy) + bottom * fy) >> kSubBits;
  }

  // Draws one return: from `clear_sub` before the hit up to `hole_half_sub` before it, the
  // cells move towards kFree; within `hole_half_sub` either side of it, towards a V that is
  // kWall at the hit; each by `weight`/256 of the way. Cells off the map are skipped.
  void draw_return(SubPoint sensor, SubPoint hit, int32_t hole_half_sub, int32_t clear_sub, uint8_t weight);

  // How many cells the laser has touched (not kUnknown), for reports and tests.
  std::size_t known_cells() const;

  const std::array<uint8_t, static_cast<std::size_t>(kMapSide) * kMapSide>& cells() const { return cells_; }

 private:
  void blend(int cx, int cy, int32_t target, int32_t weight);

  std::array<uint8_t, static_cast<std::size_t>(kMapSide) * kMapSide> cells_{};
  float cell_m_ = 0.06f;
  float origin_x_m_ = 0;  // world position of the map's corner (cell 0, 0)
  float origin_y_m_ = 0;
};

}  // namespace kestrel::slam
