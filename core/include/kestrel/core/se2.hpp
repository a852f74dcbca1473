#pragma once
// Rigid-body poses in the plane, SE(2): composition, inverse, relative pose and point
// transforms. The heading is kept wrapped to [-pi, pi). Also the point distances the planners
// and trails measure paths with.
#include <algorithm>
#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel {

template <class T>
struct Point2T {
  T x = 0;
  T y = 0;
};

template <class T>
T distance(const Point2T<T>& a, const Point2T<T>& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

// For comparing against a squared radius where no square root is wanted: the Verdex computes
// in software floating point, where hypot costs several times the rest of a point's test.
template <class T>
T squared_distance(const Point2T<T>& a, const Point2T<T>& b) {
  const T dx = a.x - b.x, dy = a.y - b.y;
  return dx * dx + dy * dy;
}

// Distance of p from the segment a-b: how far a straight leg a-b passes from a point of the
// path it replaces (the distance from a when a and b coincide).
template <class T>
T distance_to_segment(const Point2T<T>& a, const Point2T<T>& b, const Point2T<T>& p) {
  const T abx = b.x - a.x, aby = b.y - a.y, apx = p.x - a.x, apy = p.y - a.y;
  const T len2 = abx * abx + aby * aby;
  const T t = len2 > 0 ? std::clamp((apx * abx + apy * aby) / len2, T(0), T(1)) : T(0);
  return std::hypot(apx - t * abx, apy - t * aby);
}

template <class T>
struct Pose2T {
  T x = 0;      // m
  T y = 0;      // m
  T theta = 0;  // rad, wrapped to [-pi, pi)

  static Pose2T identity() { return {}; }

  // this ⊕ b: b expressed in this pose's frame, returned in the parent frame.
  Pose2T compose(const Pose2T& b) const {
    const T c = std::cos(theta), s = std::sin(theta);
    return {x + c * b.x - s * b.y, y + s * b.x + c * b.y, wrap_angle(theta + b.theta)};
  }
  Pose2T inverse() const {
    const T c = std::cos(theta), s = std::sin(theta);
    return {-(c * x + s * y), -(-s * x + c * y), wrap_angle(-theta)};
  }
  // The pose of b seen from this pose: this⁻¹ ⊕ b (the ⊖ of Kümmerle et al.).
  Pose2T between(const Pose2T& b) const { return inverse().compose(b); }

  Point2T<T> transform(const Point2T<T>& p) const {
    const T c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x - s * p.y, y + s * p.x + c * p.y};
  }
  bool finite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(theta); }

  template <class U>
  Pose2T<U> cast() const {
    return {static_cast<U>(x), static_cast<U>(y), static_cast<U>(theta)};
  }
};

using Pose2 = Pose2T<float>;
using Pose2d = Pose2T<double>;
using Point2 = Point2T<float>;
using Point2d = Point2T<double>;

}  // namespace kestrel
