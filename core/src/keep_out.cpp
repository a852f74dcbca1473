#include "kestrel/core/keep_out.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace kestrel {

bool KeepOut::valid() const {
  return std::isfinite(x_min) && std::isfinite(y_min) && std::isfinite(x_max) && std::isfinite(y_max) &&
         x_min <= x_max && y_min <= y_max;
}

bool KeepOut::crossed_by(Point2 a, Point2 b, float grow) const {
  if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y)) return false;
  const float d[2] = {b.x - a.x, b.y - a.y};
  const float o[2] = {a.x, a.y};
  const float lo[2] = {x_min - grow, y_min - grow}, hi[2] = {x_max + grow, y_max + grow};
  // Slabs: the part of the segment (parameter 0..1) inside the box on both axes.
  float t0 = 0.0f, t1 = 1.0f;
  for (int axis = 0; axis < 2 && t0 <= t1; ++axis) {
    if (std::fabs(d[axis]) < 1e-9f) {
      if (o[axis] < lo[axis] || o[axis] > hi[axis]) t0 = 2.0f;  // parallel and outside
      continue;
    }
    float ta = (lo[axis] - o[axis]) / d[axis], tb = (hi[axis] - o[axis]) / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

KeepOut KeepOut::lengthened(float along) const {
  KeepOut k = *this;
  if (!(along > 0.0f)) return k;
  const float w = x_max - x_min, h = y_max - y_min;
  if (w >= 3.0f * h && w >= kMinStripLengthM) {
    k.x_min -= along;
    k.x_max += along;
  } else if (h >= 3.0f * w && h >= kMinStripLengthM) {
    k.y_min -= along;
    k.y_max += along;
  }
  return k;
}

}  // namespace kestrel
