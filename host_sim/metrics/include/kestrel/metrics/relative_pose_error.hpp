#pragma once
// Relative pose error after Kümmerle et al., "On measuring the accuracy of SLAM algorithms"
// (Autonomous Robots 27(4), 2009), section 3: the error of a pose pair (i, j) compares the
// estimated motion δ_ij = est_i ⊖ est_j (est_j seen from est_i) with the reference motion
// δ*_ij = ref_i ⊖ ref_j, as the pose ε_ij = δ*_ij⁻¹ ⊕ δ_ij; its translation norm (m) and its
// wrapped rotation (degrees) are summarised separately by mean and standard deviation. It
// needs no global alignment and does not let an early error spoil every later pose.
// The translation norm does not depend on which side of ⊖ the estimate stands.
#include <cstddef>
#include <span>

#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/metrics/error_stats.hpp"

namespace kestrel::metrics {

struct PosePair {
  std::size_t i = 0;
  std::size_t j = 0;
};

struct RpeResult {
  ErrorStats trans_m;   // |translation of ε_ij|, m
  ErrorStats rot_deg;   // |rotation of ε_ij|, degrees
};

// Pose error of one pair (δ*⁻¹ ⊕ δ).
Pose2d relative_error(const Pose2d& est_i, const Pose2d& est_j, const Pose2d& ref_i, const Pose2d& ref_j);

// Over the pairs (k, k + delta) of two index-aligned trajectories (delta = 1: consecutive
// poses, the `rpe_*` figures of metrics.json). kInvalidArgument for different lengths or
// delta 0, kNoData for fewer than delta + 1 poses, kNotFinite for a non-finite pose.
Result<RpeResult> relative_pose_error(std::span<const Pose2d> est, std::span<const Pose2d> ref,
                                      std::size_t delta = 1);

// Over explicit pairs of indices into both trajectories; kOutOfRange for an index past the end.
Result<RpeResult> relative_pose_error(std::span<const Pose2d> est, std::span<const Pose2d> ref,
                                      std::span<const PosePair> pairs);

}  // namespace kestrel::metrics
