#include "kestrel/metrics/relative_pose_error.hpp"

#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel::metrics {

Pose2d relative_error(const Pose2d& est_i, const Pose2d& est_j, const Pose2d& ref_i, const Pose2d& ref_j) {
  const Pose2d delta_est = est_i.between(est_j);
  const Pose2d delta_ref = ref_i.between(ref_j);
  return delta_ref.between(delta_est);
}

namespace {

Status check(std::span<const Pose2d> est, std::span<const Pose2d> ref) {
  if (est.size() != ref.size()) return Status::kInvalidArgument;
  for (std::size_t k = 0; k < est.size(); ++k) {
    if (!est[k].finite() || !ref[k].finite()) return Status::kNotFinite;
  }
  return Status::kOk;
}

void add_pair(const Pose2d& e, ErrorAccumulator& t, ErrorAccumulator& r) {
  t.add(std::hypot(e.x, e.y));
  r.add(std::fabs(rad_to_deg(wrap_angle(e.theta))));
}

}  // namespace

Result<RpeResult> relative_pose_error(std::span<const Pose2d> est, std::span<const Pose2d> ref, std::size_t delta) {
  const Status s = check(est, ref);
  if (!ok(s)) return s;
  if (delta == 0) return Status::kInvalidArgument;
  if (est.size() <= delta) return Status::kNoData;
  RpeResult out;
  ErrorAccumulator t, r;
  for (std::size_t k = 0; k + delta < est.size(); ++k) {
    add_pair(relative_error(est[k], est[k + delta], ref[k], ref[k + delta]), t, r);
  }
  out.trans_m = t.stats();
  out.rot_deg = r.stats();
  return out;
}

Result<RpeResult> relative_pose_error(std::span<const Pose2d> est, std::span<const Pose2d> ref,
                                      std::span<const PosePair> pairs) {
  const Status s = check(est, ref);
  if (!ok(s)) return s;
  if (pairs.empty()) return Status::kNoData;
  RpeResult out;
  ErrorAccumulator t, r;
  for (const PosePair& p : pairs) {
    if (p.i >= est.size() || p.j >= est.size()) return Status::kOutOfRange;
    add_pair(relative_error(est[p.i], est[p.j], ref[p.i], ref[p.j]), t, r);
  }
  out.trans_m = t.stats();
  out.rot_deg = r.stats();
  return out;
}

}  // namespace kestrel::metrics
