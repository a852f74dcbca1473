#include "kestrel/control/model_fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>

namespace kestrel::control {
namespace {

// Solves the normal equations restricted to the regressors in `idx`; refuses an
// ill-conditioned system (a regressor that does not vary).
template <int N>
Status solve(const Eigen::Matrix3d& ata, const Eigen::Vector3d& aty, double yty, std::size_t n,
             const std::array<int, N>& idx, Eigen::Matrix<double, N, 1>& x, double& rms) {
  if (n < static_cast<std::size_t>(2 * N)) return Status::kInvalidArgument;
  Eigen::Matrix<double, N, N> m;
  Eigen::Matrix<double, N, 1> v;
  for (int i = 0; i < N; ++i) {
    v(i) = aty(idx[static_cast<std::size_t>(i)]);
    for (int j = 0; j < N; ++j) m(i, j) = ata(idx[static_cast<std::size_t>(i)], idx[static_cast<std::size_t>(j)]);
  }
  // Scale to unit diagonal so the conditioning test does not depend on the units.
  Eigen::Matrix<double, N, 1> d;
  for (int i = 0; i < N; ++i) {
    if (!(m(i, i) > 0.0)) return Status::kInvalidArgument;
    d(i) = 1.0 / std::sqrt(m(i, i));
  }
  const Eigen::Matrix<double, N, N> ms = d.asDiagonal() * m * d.asDiagonal();
  const Eigen::LDLT<Eigen::Matrix<double, N, N>> ldlt(ms);
  const auto diag = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || diag.minCoeff() < 1e-9 * diag.maxCoeff() || !(diag.minCoeff() > 0.0)) {
    return Status::kInvalidArgument;
  }
  x = d.asDiagonal() * ldlt.solve(d.asDiagonal() * v);
  // Residual sum of squares from the accumulated sums: y'y - 2 x'A'y + x'A'Ax.
  const double rss = yty - 2.0 * x.dot(v) + x.dot(m * x);
  rms = std::sqrt(std::max(0.0, rss) / static_cast<double>(n));
  return x.allFinite() ? Status::kOk : Status::kNotFinite;
}

}  // namespace

void ModelFit::add(double u, double rate, double response) {
  if (!std::isfinite(u) || !std::isfinite(rate) || !std::isfinite(response)) {
    ++skipped_;
    return;
  }
  const Eigen::Vector3d phi(u, rate, 1.0);
  ata_ += phi * phi.transpose();
  aty_ += phi * response;
  yty_ += response * response;
  ++n_;
}

Result<UndampedFit> ModelFit::fit_undamped() const {
  Eigen::Vector2d x;
  UndampedFit f;
  const Status s = solve<2>(ata_, aty_, yty_, n_, {0, 2}, x, f.rms);
  if (!ok(s)) return s;
  f.k = x(0);
  f.b = x(1);
  return f;
}

Result<DampedFit> ModelFit::fit_damped() const {
  Eigen::Vector3d x;
  DampedFit f;
  const Status s = solve<3>(ata_, aty_, yty_, n_, {0, 1, 2}, x, f.rms);
  if (!ok(s)) return s;
  f.k1 = x(0);
  f.k2 = x(1);
  f.b = x(2);
  return f;
}

Result<VehicleModel> fit_vehicle_model(std::span<const ModelSample> samples) {
  ModelFit fx, fy, fz, fyaw;
  for (const ModelSample& s : samples) {
    const float c = std::cos(s.heading_rad), sn = std::sin(s.heading_rad);
    // World to body (heading only: roll and pitch are the small commands themselves).
    const float ax = c * s.accel_mps2.x() + sn * s.accel_mps2.y();
    const float ay = -sn * s.accel_mps2.x() + c * s.accel_mps2.y();
    const float vx = c * s.velocity_mps.x() + sn * s.velocity_mps.y();
    const float vy = -sn * s.velocity_mps.x() + c * s.velocity_mps.y();
    fx.add(s.command.pitch_rad, vx, ax);
    fy.add(s.command.roll_rad, vy, ay);
    fz.add(s.command.thrust, s.velocity_mps.z(), s.accel_mps2.z());
    // Equation 1 for the heading is first order: the yaw rate is the response.
    fyaw.add(s.command.yaw_rate_radps, 0.0, s.yaw_rate_radps);
  }
  VehicleModel m;
  AxisModel* axes[4] = {&m.pitch, &m.roll, &m.thrust, &m.yaw};
  const ModelFit* fits[4] = {&fx, &fy, &fz, &fyaw};
  for (int i = 0; i < 4; ++i) {
    const Result<UndampedFit> r = fits[i]->fit_undamped();
    if (!r.ok()) return r.status();
    axes[i]->k = static_cast<float>(r.value().k);
    axes[i]->b = static_cast<float>(r.value().b);
  }
  const Status v = validate(m);
  if (!ok(v)) return v;
  return m;
}

}  // namespace kestrel::control
