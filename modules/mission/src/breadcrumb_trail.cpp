#include "kestrel/mission/breadcrumb_trail.hpp"

#include "kestrel/core/path_halving.hpp"
#include "kestrel/core/se2.hpp"

namespace kestrel::mission {

void BreadcrumbTrail::clear() {
  points_.clear();
  spacing_m_ = base_spacing_m_;
}

void BreadcrumbTrail::record(const Eigen::Vector3f& p) {
  if (!p.allFinite()) return;
  // Back near an earlier point (not just the last few): the path in between was a loop.
  const float close = 0.5f * spacing_m_;
  for (std::size_t i = 0; i + 3 < points_.size(); ++i) {
    if ((p - points_[i]).head<2>().norm() < close) {
      cut_loop_to(i);
      return;
    }
  }
  if (!points_.empty() && (p - points_.back()).head<2>().norm() < spacing_m_) return;
  if (points_.full()) thin_out();
  (void)points_.push_back(p);
}

void BreadcrumbTrail::cut_loop_to(std::size_t earlier_index) {
  while (points_.size() > earlier_index + 1) points_.pop_back();
}

namespace {
// How far the leg a-b passes from p, in the plane.
float deviation(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& p) {
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
