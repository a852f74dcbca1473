#include "kestrel/exploration/unflown_bearings.hpp"

#include <cmath>
#include <numbers>

#include "kestrel/exploration/work_units.hpp"

namespace kestrel::exploration {
namespace {
// -1 for a non-finite bearing.
int bin_of(float bearing_rad) {
  if (!std::isfinite(bearing_rad)) return -1;
  constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;
  float a = std::fmod(bearing_rad, kTwoPi);
  if (a < 0.0f) a += kTwoPi;
  // Bins centred on multiples of 10 degrees: the walls' own bearings (0, 90, 180 degrees in
  // a building drawn on axes) fall in the middle of a bin, and a cone of +-3 bins is symmetric.
  const int b = static_cast<int>(a / kTwoPi * UnflownBearings::kBins + 0.5f);
  return b >= UnflownBearings::kBins ? b - UnflownBearings::kBins : b;
}
}  // namespace

UnflownBearings::UnflownBearings() {
  for (int dy = -kReachCells; dy <= kReachCells; ++dy) {
    for (int dx = -kReachCells; dx <= kReachCells; ++dx) {
      const std::size_t i = static_cast<std::size_t>((dy + kReachCells) * kSide + (dx + kReachCells));
      const bool inside = dx * dx + dy * dy <= kReachCells * kReachCells && (dx != 0 || dy != 0);
      bin_of_offset_[i] = inside
                              ? static_cast<uint8_t>(bin_of(std::atan2(static_cast<float>(dy), static_cast<float>(dx))))
                              : kBeyondReach;
      const float distance = std::hypot(static_cast<float>(dx), static_cast<float>(dy));
      weight_of_offset_[i] = inside ? static_cast<uint8_t>(std::lround(static_cast<float>(kReachCells) / distance)) : 0;
    }
  }
}

uint32_t UnflownBearings::count(const VisitedGrid& grid, Point2 from, RetraceTarget what) {
  const bool frontier = what == RetraceTarget::kFrontier;
  cells_.fill(0);
  int cx = 0, cy = 0;
  if (!grid.cell_of(from, cx, cy)) return 1;
  for (int dy = -kReachCells; dy <= kReachCells; ++dy) {
    for (int dx = -kReachCells; dx <= kReachCells; ++dx) {
      const std::size_t offset = static_cast<std::size_t>((dy + kReachCells) * kSide + (dx + kReachCells));
      const uint8_t bin = bin_of_offset_[offset];
      if (bin == kBeyondReach) continue;
      const int ix = cx + dx, iy = cy + dy;
      const bool counted =
          frontier ? grid.frontier_cell(ix, iy) : grid.in_extent(ix, iy) && !grid.visited_cell(ix, iy);
      if (counted) cells_[bin] = static_cast<uint16_t>(cells_[bin] + weight_of_offset_[offset]);
    }
  }
  return static_cast<uint32_t>(kSide * kSide / (frontier ? work::kFrontierCells : work::kGridCells));
}

uint32_t UnflownBearings::score(float bearing_rad) const {
  const int centre = bin_of(bearing_rad);
  if (centre < 0) return 0;
  uint32_t n = 0;
  for (int k = -kHalfConeBins; k <= kHalfConeBins; ++k)
    n += cells_[static_cast<std::size_t>((centre + k + kBins) % kBins)];
  return n;
}

uint32_t UnflownBearings::total() const {
  uint32_t n = 0;
  for (uint16_t c : cells_) n += c;
  return n;
}

}  // namespace kestrel::exploration
