#include "kestrel/exploration/flown_history.hpp"

#include <cmath>

#include "kestrel/core/path_halving.hpp"

namespace kestrel::exploration {

void FlownHistory::clear() {
  points_.clear();
  spacing_m_ = kSpacingM;
}

void FlownHistory::record(Point2 p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
  if (!points_.empty() && distance(p, points_.back()) < spacing_m_) return;
  if (points_.full()) {
    halve_keeping_ends(points_);
    spacing_m_ *= 2;
    if (distance(p, points_.back()) < spacing_m_) return;
  }
  (void)points_.push_back(p);
}

void FlownHistory::keep_first(std::size_t n) {
  while (points_.size() > n) points_.pop_back();
}

std::size_t FlownHistory::earliest_near(std::size_t first, std::size_t last, Point2 p, float r) const {
  const float r2 = r * r;
  for (std::size_t i = first; i < last && i < points_.size(); ++i)
    if (squared_distance(points_[i], p) < r2) return i;
  return last;
}

}  // namespace kestrel::exploration
