#include "kestrel/tuning/sysid.hpp"

#include <cmath>
#include <vector>

namespace kestrel::tuning {
namespace {

struct Row {
  Eigen::Vector4d u;     // pitch, roll, thrust, yaw-rate command applied
  Eigen::Vector4d rate;  // vx_b, vy_b, vz, 0
  Eigen::Vector4d resp;  // ax_b, ay_b, az, yaw rate
  bool use = false;
};

}  // namespace

SysidResult identify_vehicle(const FlightLog& log, const SysidOptions& options) {
  SysidResult r;
  if (log.truth.size() < 2) {
    r.status = Status::kInvalidArgument;
    return r;
  }
  const double dt = (log.truth[1].stamp - log.truth[0].stamp).seconds();
  std::vector<Row> rows(log.truth.size());
  for (std::size_t i = 0; i < log.truth.size(); ++i) {
    const TruthRecord& t = log.truth[i];
    Row& w = rows[i];
    w.u = {t.command.pitch_rad, t.command.roll_rad, t.command.thrust, t.command.yaw_rate_radps};
    const double c = std::cos(t.yaw_rad), s = std::sin(t.yaw_rad);
    w.rate = {c * t.velocity_mps.x() + s * t.velocity_mps.y(), -s * t.velocity_mps.x() + c * t.velocity_mps.y(),
              t.velocity_mps.z(), 0.0};
    w.resp = {c * t.accel_mps2.x() + s * t.accel_mps2.y(), -s * t.accel_mps2.x() + c * t.accel_mps2.y(),
              t.accel_mps2.z(), t.yaw_rate_radps};
    w.use = !t.on_ground && t.position_m.z() >= options.min_height_m && std::isfinite(w.u.sum()) &&
            i % static_cast<std::size_t>(std::max(1, options.decimation)) == 0;
  }
  // The lag grid, per axis: the lagged command is filtered over every step (used or not).
  const int n_tau = static_cast<int>(std::floor(options.max_lag_s / options.lag_step_s + 1e-9)) + 1;
  std::array<double, 4> best_rms, best_tau{};
  best_rms.fill(std::numeric_limits<double>::infinity());
  for (int k = 0; k < n_tau; ++k) {
    const double tau = k * options.lag_step_s;
    const double alpha = tau > 0 ? 1.0 - std::exp(-dt / tau) : 1.0;
    control::ModelFit fits[4];
    Eigen::Vector4d f = rows.front().u;
    for (const Row& w : rows) {
      f += (w.u - f) * alpha;
      if (!w.use) continue;
      for (int a = 0; a < 4; ++a) fits[a].add(f[a], w.rate[a], w.resp[a]);
    }
    for (int a = 0; a < 4; ++a) {
      const Result<control::UndampedFit> fr = fits[a].fit_undamped();
      if (!fr.ok()) continue;
      if (k == 0) r.rms_no_lag[a] = fr.value().rms;
      if (fr.value().rms < best_rms[a] - 1e-12) {
        best_rms[a] = fr.value().rms;
        best_tau[a] = tau;
      }
    }
  }
  // The final fit through the control module's own entry point, with each axis's lag applied.
  std::vector<control::ModelSample> samples;
  Eigen::Vector4d f = rows.front().u;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& w = rows[i];
    for (int a = 0; a < 4; ++a) {
      const double alpha = best_tau[a] > 0 ? 1.0 - std::exp(-dt / best_tau[a]) : 1.0;
      f[a] += (w.u[a] - f[a]) * alpha;
    }
    if (!w.use) continue;
    const TruthRecord& t = log.truth[i];
    control::ModelSample m;
    m.command.stamp = t.stamp;
    m.command.pitch_rad = static_cast<float>(f[0]);
    m.command.roll_rad = static_cast<float>(f[1]);
    m.command.thrust = static_cast<float>(f[2]);
    m.command.yaw_rate_radps = static_cast<float>(f[3]);
    m.velocity_mps = t.velocity_mps.cast<float>();
    m.accel_mps2 = t.accel_mps2.cast<float>();
    m.heading_rad = static_cast<float>(t.yaw_rad);
    m.yaw_rate_radps = static_cast<float>(t.yaw_rate_radps);
    samples.push_back(m);
  }
  r.samples = samples.size();
  const Result<control::VehicleModel> m = control::fit_vehicle_model(samples);
  if (!m.ok()) {
    r.status = m.status();
    return r;
  }
  r.model = m.value();
  r.lag_s = best_tau;
  r.rms = best_rms;
  return r;
}

std::string sysid_script_text() {
  // T_S PITCH_DEG ROLL_DEG THRUST YAW_RATE_DPS. Climb to about 1 m (0.6 then 0.4 thrust,
  // 0.7 s each), then doublets: each excursion is followed by its opposite so the vehicle
  // stops again and stays in the hallway (no landing: the recording ends in the air).
  return R"(# kestrel-sysid excitation flight (iarc-arena, start 2.0 7.5 heading 0)
0.0   0   0  0.60  0
0.7   0   0  0.40  0
1.4   0   0  0.50  0
2.0   4   0  0.50  0
3.0  -4   0  0.50  0
4.0   0   0  0.50  0
4.3  -3   0  0.52  0
5.1   3   0  0.48  0
5.9   0   0  0.50  0
6.1   0   4  0.50  0
6.7   0  -4  0.50  0
7.3   0   0  0.50  0
7.5   0  -3  0.50  20
8.1   0   3  0.50  -20
8.7   0   0  0.55  0
9.3   0   0  0.45  0
9.9   0   0  0.50  30
10.9  0   0  0.50  -30
11.9  2   2  0.50  0
12.7 -2  -2  0.50  0
13.5  0   0  0.50  0
)";
}

}  // namespace kestrel::tuning
