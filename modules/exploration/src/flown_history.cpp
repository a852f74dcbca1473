#include "kestrel/exploration/flown_history.hpp"

#include <cmath>

namespace kestrel::exploration {
namespace {
float apart(Point2 a, Point2 b) { return std::hypot(a.x - b.x, a.y - b.y); }
}  // namespace

void FlownHistory::clear() {
  points_.clear();
  spacing_m_ = kSpacingM;
}

void FlownHistory::record(Point2 p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
  if (!points_.empty() && apart(p, points_.back()) < spacing_m_) return;
  if (points_.full()) {
    // Every other point, the newest kept: the history still ends where the vehicle was.
    std::size_t w = 0;
    for (std::size_t r = 0; r < points_.size(); r += 2) points_[w++] = points_[r];
    if (points_.size() % 2 == 0) points_[w++] = points_.back();
    while (points_.size() > w) points_.pop_back();
    spacing_m_ *= 2;
    if (apart(p, points_.back()) < spacing_m_) return;
  }
  (void)points_.push_back(p);
}

void FlownHistory::keep_first(std::size_t n) {
  while (points_.size() > n) points_.pop_back();
}

std::size_t FlownHistory::earliest_near(std::size_t first, std::size_t last, Point2 p, float r) const {
  for (std::size_t i = first; i < last && i < points_.size(); ++i)
    if (apart(points_[i], p) < r) return i;
  return last;
}

}  // namespace kestrel::exploration
