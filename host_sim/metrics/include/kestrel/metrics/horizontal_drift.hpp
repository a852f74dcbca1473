#pragma once
// How far the estimate drifted from the truth in the horizontal plane, for flights where an
// axis goes unobserved (a corridor longer than the laser's window: paper 000 section 5.1).
// A mean hides the drift; these are the figures issue 4 asks for: the worst error while
// airborne, the error where the vehicle was farthest from where it started (the far end of a
// corridor), and the error at the end. In metrics.json: `pos_err_xy_max_m`,
// `pos_err_xy_far_m` with `far_from_start_m`, `pos_err_xy_final_m`. Streams, no storage.
#include <Eigen/Core>

#include "kestrel/core/status.hpp"
#include "kestrel/metrics/error_stats.hpp"

namespace kestrel::metrics {

struct HorizontalDrift {
  ErrorStats airborne_m;        // |est - truth| in x, y over the airborne samples; .max is the worst
  double far_from_start_m = 0;  // the truth's largest horizontal distance from the first sample
  double far_error_m = 0;       // the error at that sample (the first one if it never moved)
  double final_error_m = 0;     // the error at the last sample
  std::size_t samples = 0;      // every sample taken, on the ground or not
};

class HorizontalDriftAccumulator {
 public:
  // kNotFinite (sample ignored) for a non-finite estimate or truth. The first accepted sample's
  // truth is the start.
  Status add(const Eigen::Vector2d& est, const Eigen::Vector2d& truth, bool airborne);
  HorizontalDrift result() const;

 private:
  Eigen::Vector2d start_ = Eigen::Vector2d::Zero();
  ErrorAccumulator airborne_;
  HorizontalDrift drift_;
};

}  // namespace kestrel::metrics
