// The metrics on the real logs, against the motion statistics of ../shared/data/README.md:
// an estimate that never moves has, per consecutive pair, exactly the reference motion as its
// relative pose error (freiburg-079: 0.09 m / 0.06 rad mean; intel: 0.55 m / 0.31 rad).
#include <gtest/gtest.h>

#include <vector>

#include "kestrel/logs/carmen_reader.hpp"
#include "kestrel/metrics/absolute_trajectory_error.hpp"
#include "kestrel/metrics/relative_pose_error.hpp"
#include "kestrel_test_paths.hpp"

namespace kestrel::metrics {
namespace {

std::vector<Pose2d> reference_poses(const char* rel) {
  logs::CarmenReaderOptions opt;
  opt.time_order = logs::TimeOrder::kAccept;
  logs::CarmenReader reader(opt);
  std::vector<Pose2d> poses;
  if (!ok(reader.open(test::shared_data_path(rel).c_str()))) return poses;
  logs::LogRecord rec;
  while (ok(reader.next(rec))) {
    if (rec.kind == logs::LogRecord::Kind::kLaser && rec.has_pose) poses.push_back(rec.pose);
  }
  return poses;
}

void check_no_motion_estimate(const char* rel, std::size_t scans, double trans_mean, double rot_mean_rad) {
  const auto ref = reference_poses(rel);
  ASSERT_EQ(ref.size(), scans);
  const std::vector<Pose2d> still(ref.size(), ref.front());
  const auto rpe = relative_pose_error(still, ref);
  ASSERT_TRUE(rpe.ok());
  EXPECT_NEAR(rpe.value().trans_m.mean, trans_mean, 0.005) << rel;
  EXPECT_NEAR(rpe.value().rot_deg.mean, rad_to_deg(rot_mean_rad), rad_to_deg(0.005)) << rel;
  // The reference against itself, after any rigid motion: zero by both measures.
  std::vector<Pose2d> moved;
  for (const Pose2d& p : ref) moved.push_back(Pose2d{1, 2, 0.5}.compose(p));
  const auto same = relative_pose_error(moved, ref);
  const auto ate = absolute_trajectory_error(moved, ref);
  ASSERT_TRUE(same.ok());
  ASSERT_TRUE(ate.ok());
  EXPECT_LT(same.value().trans_m.max, 1e-9);
  EXPECT_LT(ate.value().trans_m.rmse, 1e-9);
}

TEST(MetricsRealData, Freiburg079MotionStatistics) {
  check_no_motion_estimate("carmen/freiburg-079.log.gz", 4791, 0.09, 0.06);
}

TEST(MetricsRealData, IntelMotionStatistics) { check_no_motion_estimate("carmen/intel.log.gz", 910, 0.55, 0.31); }

}  // namespace
}  // namespace kestrel::metrics
