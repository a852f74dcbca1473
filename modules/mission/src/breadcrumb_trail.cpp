#include "kestrel/mission/breadcrumb_trail.hpp"

#include <algorithm>

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
// Distance of p from the segment a-b, in the plane.
float deviation(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& p) {
  const Eigen::Vector2f ab = (b - a).head<2>(), ap = (p - a).head<2>();
  const float len2 = ab.squaredNorm();
  const float t = len2 > 0 ? std::clamp(ap.dot(ab) / len2, 0.0f, 1.0f) : 0.0f;
  return (ap - t * ab).norm();
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
  w = 0;
  for (std::size_t r = 0; r < points_.size(); r += 2) points_[w++] = points_[r];
  // Keep the newest point: the trail must end where the vehicle is.
  if (points_.size() % 2 == 0) points_[w++] = points_.back();
  while (points_.size() > w) points_.pop_back();
  spacing_m_ *= 2;
}

}  // namespace kestrel::mission
