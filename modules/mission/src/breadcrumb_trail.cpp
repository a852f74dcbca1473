#include "kestrel/mission/breadcrumb_trail.hpp"

#include <cmath>

#include "kestrel/core/path_halving.hpp"
#include "kestrel/core/se2.hpp"

namespace kestrel::mission {

void BreadcrumbTrail::clear() {
  points_.clear();
  spacing_m_ = base_spacing_m_;
}

void BreadcrumbTrail::record(const Eigen::Vector3f& p, TimeUs stamp) {
  if (!p.allFinite()) return;
  // Back near an earlier point (not just the last few): the path in between was a loop. The
  // earlier point keeps its stamp: it was drawn, and is shifted, with the path before it.
  const float close = 0.5f * spacing_m_;
  for (std::size_t i = 0; i + 3 < points_.size(); ++i) {
    if ((p - points_[i].position_m).head<2>().norm() < close) {
      cut_loop_to(i);
      return;
    }
  }
  if (!points_.empty() && (p - points_.back().position_m).head<2>().norm() < spacing_m_) return;
  if (points_.full()) thin_out();
  (void)points_.push_back({p, stamp});
}

void BreadcrumbTrail::shift_since(TimeUs since, const Pose2& delta) {
  if (!delta.finite()) return;
  // Every point, not a search from the end: stamps are in order only while the estimate's
  // clock never stepped back.
  for (std::size_t i = 0; i < points_.size(); ++i) {
    Breadcrumb& b = points_[i];
    if (b.stamp < since) continue;
    const Point2 moved = delta.transform(Point2{b.position_m.x(), b.position_m.y()});
    b.position_m.x() = moved.x;
    b.position_m.y() = moved.y;
  }
}

void BreadcrumbTrail::cut_loop_to(std::size_t earlier_index) {
  while (points_.size() > earlier_index + 1) points_.pop_back();
}

void BreadcrumbTrail::move_points(std::size_t first, std::size_t last, Point2 offset) {
  if (!std::isfinite(offset.x) || !std::isfinite(offset.y)) return;
  for (std::size_t i = first; i <= last && i < points_.size(); ++i) {
    points_[i].position_m.x() += offset.x;
    points_[i].position_m.y() += offset.y;
  }
}

namespace {
// How far the leg a-b passes from p, in the plane.
template <class Crumb>
float deviation(const Crumb& ca, const Crumb& cb, const Crumb& cp) {
  const Eigen::Vector3f &a = ca.position_m, &b = cb.position_m, &p = cp.position_m;
  return distance_to_segment(Point2{a.x(), a.y()}, Point2{b.x(), b.y()}, Point2{p.x(), p.y()});
}
}  // namespace

void BreadcrumbTrail::thin_out() {
  // First drop points on straight stretches: removing them does not move the path. Corners
  // are kept, because cutting one could take the way home through a door frame.
  constexpr float kStraight = 0.05f;  // m
  std::size_t w = 1;
  for (std::size_t r = 1; r + 1 < points_.size(); ++r) {
    if (deviation(points_[w - 1], points_[r + 1], points_[r]) >= kStraight) points_[w++] = points_[r];
  }
  points_[w++] = points_.back();
  while (points_.size() > w) points_.pop_back();
  if (points_.size() < kCapacity - kCapacity / 4) return;
  // Still nearly full: the path is all corners; halve it and accept the coarser spacing.
  halve_keeping_ends(points_);
  spacing_m_ *= 2;
}

}  // namespace kestrel::mission
