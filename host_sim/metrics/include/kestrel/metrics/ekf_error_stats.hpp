#pragma once
// The state estimator against the simulator's truth: position and velocity error magnitudes
// (`pos_err_mean_m`, `vel_err_mean_mps`, `vel_err_std_mps` in metrics.json). Streams sample by
// sample, so a closed-loop run needs no trajectory storage.
#include <Eigen/Core>
#include <span>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"
#include "kestrel/metrics/error_stats.hpp"

namespace kestrel::metrics {

struct StateSample {
  TimeUs stamp;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();

  static StateSample from(const NavState& s) {
    return {s.stamp, s.position_m.cast<double>(), s.velocity_mps.cast<double>()};
  }
};

struct EkfErrorStats {
  ErrorStats position_m;     // |est - truth| of the position; .mean is pos_err_mean_m
  ErrorStats velocity_mps;   // |est - truth| of the velocity; .mean, .std are vel_err_*_mps
};

class EkfErrorAccumulator {
 public:
  // horizontal_only: compare x and y alone (a 2D estimator, or a separate altitude filter).
  explicit EkfErrorAccumulator(bool horizontal_only = false) : horizontal_only_(horizontal_only) {}

  // kNotFinite (sample ignored) for a non-finite estimate or truth.
  Status add(const StateSample& est, const StateSample& truth);
  EkfErrorStats stats() const { return {pos_.stats(), vel_.stats()}; }

 private:
  bool horizontal_only_;
  ErrorAccumulator pos_;
  ErrorAccumulator vel_;
};

// Index-aligned sequences whose stamps agree within `max_dt`: kInvalidArgument for different
// lengths or a stamp mismatch, kNoData when empty, kNotFinite for a non-finite sample.
Result<EkfErrorStats> ekf_error_stats(std::span<const StateSample> est, std::span<const StateSample> truth,
                                      Duration max_dt = {}, bool horizontal_only = false);

}  // namespace kestrel::metrics
