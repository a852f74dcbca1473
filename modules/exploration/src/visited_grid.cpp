#include "kestrel/exploration/visited_grid.hpp"

#include <bit>
#include <cmath>

namespace kestrel::exploration {

void VisitedGrid::clear() {
  bits_.fill(0);
  anchored_ = false;
}

bool VisitedGrid::cell_of(Point2 p, int& ix, int& iy) const {
  if (!anchored_ || !std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  const float fx = std::floor((p.x - origin_.x) / kCellM), fy = std::floor((p.y - origin_.y) / kCellM);
  if (!(fx >= 0.0f && fx < static_cast<float>(kSide) && fy >= 0.0f && fy < static_cast<float>(kSide))) return false;
  ix = static_cast<int>(fx);
  iy = static_cast<int>(fy);
  return true;
}

void VisitedGrid::set(int ix, int iy) {
  if (ix < 0 || iy < 0 || ix >= kSide || iy >= kSide) return;
  const std::size_t i = static_cast<std::size_t>(iy) * kSide + static_cast<std::size_t>(ix);
  bits_[i / 64] |= uint64_t{1} << (i % 64);
}

void VisitedGrid::mark(Point2 p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
  if (!anchored_) {
    constexpr float kHalf = 0.5f * kSide * kCellM;
    origin_ = {p.x - kHalf, p.y - kHalf};
    anchored_ = true;
  }
  int ix = 0, iy = 0;
  if (!cell_of(p, ix, iy)) return;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) set(ix + dx, iy + dy);
}

bool VisitedGrid::visited(Point2 p) const {
  int ix = 0, iy = 0;
  if (!cell_of(p, ix, iy)) return false;
  const std::size_t i = static_cast<std::size_t>(iy) * kSide + static_cast<std::size_t>(ix);
  return (bits_[i / 64] >> (i % 64)) & 1u;
}

std::size_t VisitedGrid::marked_cells() const {
  std::size_t n = 0;
  for (uint64_t w : bits_) n += static_cast<std::size_t>(std::popcount(w));
  return n;
}

}  // namespace kestrel::exploration
