#pragma once
// The path flown so far, as points at least `spacing` apart, kept so the vehicle can fly home
// without a map: retracing its own path is collision-free by construction. When the path
// crosses itself, the loop between the two visits is cut, so the way home is no longer than
// needed. Fixed capacity; when full, every other point is dropped (the spacing doubles).
//
// Each point keeps the estimate's time it was recorded at. A late correction of the estimate
// (NavFilter::apply_correction: the SLAM's, the home re-localisation's) moves the estimated
// path from its stamp on; shift_since() moves the points recorded since with it, so the trail
// stays where the vehicle flew in the frame it now flies in (gt-building, URG-04LX: a trail left
// where the estimate had been put the way home through a door's jamb 0.5 m into the wall).
#include <cstddef>

#include "kestrel/core/se2.hpp"
#include "kestrel/core/static_vector.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"
#include <Eigen/Core>

namespace kestrel::mission {

class BreadcrumbTrail {
 public:
  static constexpr std::size_t kCapacity = 1024;

  explicit BreadcrumbTrail(float spacing_m = 0.5f) : spacing_m_(spacing_m), base_spacing_m_(spacing_m) {}

  void clear();
  // Records the vehicle's position, estimated for `stamp`; non-finite positions are ignored.
  void record(const Eigen::Vector3f& position_m, TimeUs stamp);
  // The estimated path from `since` on moved by `delta` (new = delta * old, in the plane):
  // every point recorded at or after `since` moves with it. A non-finite delta is ignored.
  void shift_since(TimeUs since, const Pose2& delta);
  // Moves points first..last (inclusive, clipped to the trail) by `offset`; a non-finite
  // offset is ignored.
  void move_points(std::size_t first, std::size_t last, Point2 offset);
  std::size_t size() const { return points_.size(); }
  const Eigen::Vector3f& point(std::size_t i) const { return points_[i].position_m; }
  TimeUs stamp(std::size_t i) const { return points_[i].stamp; }
  float spacing_m() const { return spacing_m_; }

 private:
  struct Breadcrumb {
    Eigen::Vector3f position_m;
    TimeUs stamp;
  };
  void cut_loop_to(std::size_t earlier_index);
  void thin_out();

  StaticVector<Breadcrumb, kCapacity> points_;
  float spacing_m_;
  float base_spacing_m_;
};

}  // namespace kestrel::mission
