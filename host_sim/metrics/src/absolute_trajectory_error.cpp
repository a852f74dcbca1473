#include "kestrel/metrics/absolute_trajectory_error.hpp"

#include <cmath>

namespace kestrel::metrics {

namespace {

template <class Get>
Result<Pose2d> align(std::size_t n_est, std::size_t n_ref, Get get) {
  if (n_est != n_ref) return Status::kInvalidArgument;
  if (n_est == 0) return Status::kNoData;
  const std::size_t n = n_est;
  double pex = 0, pey = 0, prx = 0, pry = 0;
  for (std::size_t k = 0; k < n; ++k) {
    Point2d e, r;
    get(k, e, r);
    if (!std::isfinite(e.x) || !std::isfinite(e.y) || !std::isfinite(r.x) || !std::isfinite(r.y)) {
      return Status::kNotFinite;
    }
    pex += e.x;
    pey += e.y;
    prx += r.x;
    pry += r.y;
  }
  const double inv = 1.0 / static_cast<double>(n);
  pex *= inv;
  pey *= inv;
  prx *= inv;
  pry *= inv;
  double s_cos = 0, s_sin = 0;
  for (std::size_t k = 0; k < n; ++k) {
    Point2d e, r;
    get(k, e, r);
    const double ax = e.x - pex, ay = e.y - pey, bx = r.x - prx, by = r.y - pry;
    s_cos += ax * bx + ay * by;
    s_sin += ax * by - ay * bx;
  }
  const double theta = (s_cos == 0 && s_sin == 0) ? 0.0 : std::atan2(s_sin, s_cos);
  const double c = std::cos(theta), s = std::sin(theta);
  return Pose2d{prx - (c * pex - s * pey), pry - (s * pex + c * pey), wrap_angle(theta)};
}

}  // namespace

Result<Pose2d> align_se2(std::span<const Point2d> est, std::span<const Point2d> ref) {
  return align(est.size(), ref.size(), [&](std::size_t k, Point2d& e, Point2d& r) {
    e = est[k];
    r = ref[k];
  });
}

Result<AteResult> absolute_trajectory_error(std::span<const Pose2d> est, std::span<const Pose2d> ref) {
  const Result<Pose2d> t = align(est.size(), ref.size(), [&](std::size_t k, Point2d& e, Point2d& r) {
    e = {est[k].x, est[k].y};
    r = {ref[k].x, ref[k].y};
  });
  if (!t.ok()) return t.status();
  AteResult out;
  out.alignment = t.value();
  ErrorAccumulator acc;
  for (std::size_t k = 0; k < est.size(); ++k) {
    const Point2d p = out.alignment.transform({est[k].x, est[k].y});
    acc.add(std::hypot(p.x - ref[k].x, p.y - ref[k].y));
  }
  out.trans_m = acc.stats();
  return out;
}

}  // namespace kestrel::metrics
