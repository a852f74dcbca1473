#pragma once
// The path flown, in order, as points about kSpacingM apart: srt.retrace's way back to a place
// flown before (srt_star_planner.hpp). Unlike the mission's breadcrumb trail, loops are kept:
// a run-out on the root comes after SRT-Star has backtracked to it, where the loop-cut trail
// is the few points of the start, while the rooms still unflown lie beside places the vehicle
// passed on its way out. The way back cuts loops as it goes (earliest_near). Fixed capacity;
// when full, every other point is dropped and the spacing doubles.
#include <cstddef>

#include "kestrel/core/se2.hpp"
#include "kestrel/core/static_vector.hpp"

namespace kestrel::exploration {

class FlownHistory {
 public:
  static constexpr std::size_t kCapacity = 1024;
  // Half a metre: the chord between two points cuts a right-angled turn by under 0.18 m, little
  // enough to keep a leg back through a 0.95 m door off its jambs. 512 m before the first
  // thinning (a 30-minute flight is about 600 m), after which a chord can cut 0.35 m.
  static constexpr float kSpacingM = 0.5f;

  void clear();
  // Records a position; non-finite ones are ignored.
  void record(Point2 p);
  std::size_t size() const { return points_.size(); }
  Point2 point(std::size_t i) const { return points_[i]; }
  float spacing_m() const { return spacing_m_; }
  // Keeps the first n points: the vehicle is back at point n - 1 by another way than the one
  // recorded after it, which must not be flown as if it joined on.
  void keep_first(std::size_t n);
  // The smallest index in [first, last] whose point is within r of p (last if none is).
  std::size_t earliest_near(std::size_t first, std::size_t last, Point2 p, float r) const;

 private:
  StaticVector<Point2, kCapacity> points_;
  float spacing_m_ = kSpacingM;
};

}  // namespace kestrel::exploration
