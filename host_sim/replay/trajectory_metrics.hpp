#pragma once
// Relative pose error per consecutive pair (Kümmerle et al. 2009) and absolute trajectory error
// after the best SE(2) alignment, for kestrel-replay.
#include <vector>

#include "kestrel/core/se2.hpp"

namespace kestrel::replay {

struct TrajectoryMetrics {
  double rpe_trans_m = 0, rpe_trans_std_m = 0, rpe_rot_deg = 0, rpe_rot_std_deg = 0;
  double rpe_trans_max_m = 0, rpe_rot_max_deg = 0;
  double ate_rmse_m = 0;
  int pairs = 0;
  int jumps = 0;  // pairs with a translation error above 0.2 m or a rotation error above 5 degrees
  Pose2d alignment;  // maps reference poses onto the estimate's frame
};

TrajectoryMetrics compute_metrics(const std::vector<Pose2d>& est, const std::vector<Pose2d>& ref);

}  // namespace kestrel::replay
