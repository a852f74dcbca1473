#include "kestrel/slam/slam_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace kestrel::slam {
namespace {

// Integer square root (floor): once per return, without the Verdex's software sqrt.
uint32_t isqrt(uint64_t v) {
  uint64_t r = 0, bit = uint64_t{1} << 62;
  while (bit > v) bit >>= 2;
  while (bit != 0) {
    if (v >= r + bit) {
      v -= r + bit;
      r = (r >> 1) + bit;
    } else {
      r >>= 1;
    }
    bit >>= 2;
  }
  return static_cast<uint32_t>(r);
}

}  // namespace

Status SlamMap::reset(float cell_m, float centre_x_m, float centre_y_m) {
  if (!(cell_m >= 0.01f && cell_m <= 0.5f) || !std::isfinite(centre_x_m) || !std::isfinite(centre_y_m)) {
    return Status::kInvalidArgument;
  }
  cells_.fill(kUnknown);
  cell_m_ = cell_m;
  origin_x_m_ = centre_x_m - 0.5f * kMapSide * cell_m;
  origin_y_m_ = centre_y_m - 0.5f * kMapSide * cell_m;
  return Status::kOk;
}

SubPoint SlamMap::to_sub(float x_m, float y_m) const {
  // Clamped well outside the map, so that a wild pose samples unknown cells instead of
  // overflowing the sub-cell arithmetic.
  constexpr float kLimit = 4.0f * kMapSide * kSub;
  const float sx = std::clamp((x_m - origin_x_m_) / cell_m_ * kSub, -kLimit, kLimit);
  const float sy = std::clamp((y_m - origin_y_m_) / cell_m_ * kSub, -kLimit, kLimit);
  return {static_cast<int32_t>(std::lround(std::isfinite(sx) ? sx : -kLimit)),
          static_cast<int32_t>(std::lround(std::isfinite(sy) ? sy : -kLimit))};
}

float SlamMap::sub_to_x_m(int32_t sx) const { return origin_x_m_ + static_cast<float>(sx) / kSub * cell_m_; }
float SlamMap::sub_to_y_m(int32_t sy) const { return origin_y_m_ + static_cast<float>(sy) / kSub * cell_m_; }

void SlamMap::blend(int cx, int cy, int32_t target, int32_t weight) {
  if (!inside(cx, cy)) return;
  uint8_t& c = cells_[static_cast<std::size_t>(cy) * kMapSide + static_cast<std::size_t>(cx)];
  c = static_cast<uint8_t>(std::clamp<int32_t>(c + (((target - c) * weight + 128) >> 8), kWall, kFree));
}

void SlamMap::draw_return(SubPoint sensor, SubPoint hit, int32_t hole_half_sub, int32_t clear_sub, uint8_t weight) {
  if (hole_half_sub <= 0 || weight == 0) return;
  const int64_t dx = hit.x - sensor.x, dy = hit.y - sensor.y;
  const int32_t d = static_cast<int32_t>(isqrt(static_cast<uint64_t>(dx * dx + dy * dy)));
  if (d < kSub / 4) return;  // a return inside the sensor's own cell says nothing
  // Walk the ray one cell at a time, positions in 1/65536 cell (kSub^2) so that the steps
  // add up without drifting off the line.
  constexpr int64_t kFine = int64_t{kSub} * kSub;
  const int32_t t_begin = std::max<int32_t>(0, d - std::max(clear_sub, hole_half_sub));
  const int32_t t_end = d + hole_half_sub;
  int64_t x = int64_t{sensor.x} * kSub + dx * kSub * t_begin / d;
  int64_t y = int64_t{sensor.y} * kSub + dy * kSub * t_begin / d;
  const int64_t step_x = dx * kFine / d, step_y = dy * kFine / d;
  // The V's walls: kFree at hole_half_sub from the hit, kWall at it. Each cell takes the value
  // of its centre's distance from the hit along the ray, not of the step that landed in it:
  // a wall that runs along a cell boundary would otherwise be drawn half a cell to one side.
  const int32_t slope = (int32_t{kFree - kWall} << 16) / hole_half_sub;
  for (int32_t t = t_begin; t <= t_end; t += kSub, x += step_x, y += step_y) {
    const int cx = static_cast<int>(x >> (2 * kSubBits)), cy = static_cast<int>(y >> (2 * kSubBits));
    const int64_t ex = int64_t{cx} * kSub + kSub / 2 - hit.x, ey = int64_t{cy} * kSub + kSub / 2 - hit.y;
    const int64_t along = (ex * step_x + ey * step_y) / kFine;  // sub-cells, signed
    const int64_t off = along < 0 ? -along : along;
    const int32_t target = off >= hole_half_sub ? kFree : kWall + static_cast<int32_t>((off * slope) >> 16);
    blend(cx, cy, target, weight);
  }
}

std::size_t SlamMap::known_cells() const {
  return static_cast<std::size_t>(std::count_if(cells_.begin(), cells_.end(), [](uint8_t c) { return c != kUnknown; }));
}

}  // namespace kestrel::slam
