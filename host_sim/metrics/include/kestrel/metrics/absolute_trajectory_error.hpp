#pragma once
// Absolute trajectory error (Sturm et al., "A benchmark for the evaluation of RGB-D SLAM
// systems", IROS 2012, section VI-B), in the plane: the estimated positions are first moved
// by the rigid SE(2) transform that best fits them to the reference in the least-squares
// sense, then the RMSE of the remaining position differences is reported (`ate_rmse_m`).
// The best transform has a closed form (Horn 1987; Umeyama 1991 without scale), which in 2D
// reduces to one angle: with both point sets centred on their centroids,
//   theta = atan2(sum(a x b), sum(a . b)),   t = mean(ref) - R(theta) mean(est).
#include <span>

#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/metrics/error_stats.hpp"

namespace kestrel::metrics {

// The SE(2) transform T minimising sum |T(est_k) - ref_k|^2 over index-aligned points.
// kInvalidArgument for different lengths, kNoData when empty, kNotFinite for a bad point.
// When the points do not fix the angle (all on one spot) it is 0.
Result<Pose2d> align_se2(std::span<const Point2d> est, std::span<const Point2d> ref);

struct AteResult {
  ErrorStats trans_m;    // position error after alignment; trans_m.rmse is ate_rmse_m
  Pose2d alignment;      // the transform applied to the estimate
};

// Over index-aligned trajectories (positions only; headings do not enter the ATE).
Result<AteResult> absolute_trajectory_error(std::span<const Pose2d> est, std::span<const Pose2d> ref);

}  // namespace kestrel::metrics
