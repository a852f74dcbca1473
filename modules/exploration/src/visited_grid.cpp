#include "kestrel/exploration/visited_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace kestrel::exploration {

void VisitedGrid::clear() {
  bits_.fill(0);
  seen_.fill(0);
  wall_.fill(0);
  anchored_ = false;
  min_ix_ = min_iy_ = kSide;
  max_ix_ = max_iy_ = -1;
}

bool VisitedGrid::cell_of(Point2 p, int& ix, int& iy) const {
  if (!anchored_ || !std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  const float fx = std::floor((p.x - origin_.x) / kCellM), fy = std::floor((p.y - origin_.y) / kCellM);
  if (!(fx >= 0.0f && fx < static_cast<float>(kSide) && fy >= 0.0f && fy < static_cast<float>(kSide))) return false;
  ix = static_cast<int>(fx);
  iy = static_cast<int>(fy);
  return true;
}

void VisitedGrid::set(int ix, int iy, Extent extent) {
  if (ix < 0 || iy < 0 || ix >= kSide || iy >= kSide) return;
  const std::size_t i = static_cast<std::size_t>(iy) * kSide + static_cast<std::size_t>(ix);
  bits_[i / 64] |= uint64_t{1} << (i % 64);
  if (extent == Extent::kWiden) include(ix, iy);
}

void VisitedGrid::include(int ix, int iy) {
  min_ix_ = std::min(min_ix_, ix);
  min_iy_ = std::min(min_iy_, iy);
  max_ix_ = std::max(max_ix_, ix);
  max_iy_ = std::max(max_iy_, iy);
}

void VisitedGrid::mark(Point2 p, Extent extent) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
  if (!anchored_) {
    constexpr float kHalf = 0.5f * kSide * kCellM;
    origin_ = {p.x - kHalf, p.y - kHalf};
    anchored_ = true;
  }
  int ix = 0, iy = 0;
  if (!cell_of(p, ix, iy)) return;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) set(ix + dx, iy + dy, extent);
}

void VisitedGrid::widen_extent(Point2 p) {
  int ix = 0, iy = 0;
  if (cell_of(p, ix, iy)) include(ix, iy);
}

bool VisitedGrid::visited(Point2 p) const {
  int ix = 0, iy = 0;
  return cell_of(p, ix, iy) && visited_cell(ix, iy);
}

bool VisitedGrid::bit(const Layer& layer, int ix, int iy) {
  if (ix < 0 || iy < 0 || ix >= kSide || iy >= kSide) return false;
  const std::size_t i = static_cast<std::size_t>(iy) * kSide + static_cast<std::size_t>(ix);
  return (layer[i / 64] >> (i % 64)) & 1u;
}

void VisitedGrid::set_bit(Layer& layer, Point2 p) const {
  int ix = 0, iy = 0;
  if (!cell_of(p, ix, iy)) return;
  const std::size_t i = static_cast<std::size_t>(iy) * kSide + static_cast<std::size_t>(ix);
  layer[i / 64] |= uint64_t{1} << (i % 64);
}

bool VisitedGrid::visited_cell(int ix, int iy) const { return bit(bits_, ix, iy); }

void VisitedGrid::mark_seen(Point2 p) { set_bit(seen_, p); }

void VisitedGrid::mark_wall(Point2 p) { set_bit(wall_, p); }

bool VisitedGrid::seen_cell(int ix, int iy) const { return bit(seen_, ix, iy); }

bool VisitedGrid::wall_cell(int ix, int iy) const { return bit(wall_, ix, iy); }

bool VisitedGrid::frontier_cell(int ix, int iy) const {
  if (ix < 0 || iy < 0 || ix >= kSide || iy >= kSide) return false;
  if (visited_cell(ix, iy) || seen_cell(ix, iy) || wall_cell(ix, iy)) return false;
  return open_cell(ix - 1, iy) || open_cell(ix + 1, iy) || open_cell(ix, iy - 1) || open_cell(ix, iy + 1);
}

bool VisitedGrid::in_extent(int ix, int iy) const {
  return ix >= min_ix_ && ix <= max_ix_ && iy >= min_iy_ && iy <= max_iy_;
}

std::size_t VisitedGrid::marked_cells() const {
  std::size_t n = 0;
  for (uint64_t w : bits_) n += static_cast<std::size_t>(std::popcount(w));
  return n;
}

}  // namespace kestrel::exploration
