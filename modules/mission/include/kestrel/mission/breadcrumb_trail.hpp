#pragma once
// The path flown so far, as points at least `spacing` apart, kept so the vehicle can fly home
// without a map: retracing its own path is collision-free by construction. When the path
// crosses itself, the loop between the two visits is cut, so the way home is no longer than
// needed. Fixed capacity; when full, every other point is dropped (the spacing doubles).
#include <cstddef>

#include "kestrel/core/static_vector.hpp"
#include "kestrel/core/status.hpp"
#include <Eigen/Core>

namespace kestrel::mission {

class BreadcrumbTrail {
 public:
  static constexpr std::size_t kCapacity = 1024;

  explicit BreadcrumbTrail(float spacing_m = 0.5f) : spacing_m_(spacing_m), base_spacing_m_(spacing_m) {}

  void clear();
  // Records the vehicle's position; non-finite positions are ignored.
  void record(const Eigen::Vector3f& position_m);
  std::size_t size() const { return points_.size(); }
  const Eigen::Vector3f& point(std::size_t i) const { return points_[i]; }
  float spacing_m() const { return spacing_m_; }

 private:
  void cut_loop_to(std::size_t earlier_index);
  void thin_out();

  StaticVector<Eigen::Vector3f, kCapacity> points_;
  float spacing_m_;
  float base_spacing_m_;
};

}  // namespace kestrel::mission
