#include "kestrel/metrics/ekf_error_stats.hpp"

namespace kestrel::metrics {

Status EkfErrorAccumulator::add(const StateSample& est, const StateSample& truth) {
  if (!est.position_m.allFinite() || !est.velocity_mps.allFinite() || !truth.position_m.allFinite() ||
      !truth.velocity_mps.allFinite()) {
    return Status::kNotFinite;
  }
  Eigen::Vector3d dp = est.position_m - truth.position_m;
  Eigen::Vector3d dv = est.velocity_mps - truth.velocity_mps;
  if (horizontal_only_) {
    dp.z() = 0;
    dv.z() = 0;
  }
  pos_.add(dp.norm());
  vel_.add(dv.norm());
  return Status::kOk;
}

Result<EkfErrorStats> ekf_error_stats(std::span<const StateSample> est, std::span<const StateSample> truth,
                                      Duration max_dt, bool horizontal_only) {
  if (est.size() != truth.size()) return Status::kInvalidArgument;
  if (est.empty()) return Status::kNoData;
  EkfErrorAccumulator acc(horizontal_only);
  for (std::size_t k = 0; k < est.size(); ++k) {
    const Duration dt = est[k].stamp - truth[k].stamp;
    if (dt > max_dt || Duration{} - dt > max_dt) return Status::kInvalidArgument;
    const Status s = acc.add(est[k], truth[k]);
    if (!ok(s)) return s;
  }
  return acc.stats();
}

}  // namespace kestrel::metrics
