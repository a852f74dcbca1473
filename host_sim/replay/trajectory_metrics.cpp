#include "trajectory_metrics.hpp"

#include <cmath>

namespace kestrel::replay {

TrajectoryMetrics compute_metrics(const std::vector<Pose2d>& est, const std::vector<Pose2d>& ref) {
  TrajectoryMetrics m;
  const std::size_t n = std::min(est.size(), ref.size());
  double st = 0, st2 = 0, sr = 0, sr2 = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const Pose2d de = est[i - 1].between(est[i]), dr = ref[i - 1].between(ref[i]);
    const Pose2d err = dr.between(de);
    const double t = std::hypot(err.x, err.y), r = std::fabs(wrap_angle(err.theta)) * 180.0 / M_PI;
    st += t; st2 += t * t; sr += r; sr2 += r * r;
    m.rpe_trans_max_m = std::max(m.rpe_trans_max_m, t);
    m.rpe_rot_max_deg = std::max(m.rpe_rot_max_deg, r);
    if (t > 0.2 || r > 5.0) ++m.jumps;
    ++m.pairs;
  }
  if (m.pairs > 0) {
    const double k = m.pairs;
    m.rpe_trans_m = st / k;
    m.rpe_rot_deg = sr / k;
    m.rpe_trans_std_m = std::sqrt(std::max(0.0, st2 / k - m.rpe_trans_m * m.rpe_trans_m));
    m.rpe_rot_std_deg = std::sqrt(std::max(0.0, sr2 / k - m.rpe_rot_deg * m.rpe_rot_deg));
  }
  if (n == 0) return m;
  // Closed-form 2D rigid alignment of ref onto est (least squares, no scale).
  double mex = 0, mey = 0, mrx = 0, mry = 0;
  for (std::size_t i = 0; i < n; ++i) { mex += est[i].x; mey += est[i].y; mrx += ref[i].x; mry += ref[i].y; }
  mex /= n; mey /= n; mrx /= n; mry /= n;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double ax = ref[i].x - mrx, ay = ref[i].y - mry, bx = est[i].x - mex, by = est[i].y - mey;
    sxx += ax * bx + ay * by;
    sxy += ax * by - ay * bx;
  }
  const double th = std::atan2(sxy, sxx), c = std::cos(th), s = std::sin(th);
  m.alignment = {mex - (c * mrx - s * mry), mey - (s * mrx + c * mry), th};
  double se = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2d p = m.alignment.transform({ref[i].x, ref[i].y});
    se += (p.x - est[i].x) * (p.x - est[i].x) + (p.y - est[i].y) * (p.y - est[i].y);
  }
  m.ate_rmse_m = std::sqrt(se / n);
  return m;
}

}  // namespace kestrel::replay
