#include "kestrel/tuning/ekf_tuning.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "kestrel/output/plot.hpp"
#include "kestrel/output/png_writer.hpp"

namespace kestrel::tuning {

estimation::RecordedRun RunData::run() const {
  estimation::RecordedRun r;
  r.imu = log->imu;
  r.attitude = log->attitude;
  r.poses = log->poses;
  r.altitude = log->altitude;
  r.truth = truth;
  r.measurement_latency = latency;
  return r;
}

RunData make_run_data(const FlightLog& log, Duration truth_period) {
  RunData d;
  d.log = &log;
  TimeUs next{std::numeric_limits<int64_t>::min()};
  for (const TruthRecord& t : log.truth) {
    // On the floor the vehicle is held still by contact the IMU model does not see: score the
    // flight only.
    if (t.on_ground || t.stamp < next) continue;
    estimation::TruthSample s;
    s.stamp = t.stamp;
    s.position_m = t.position_m.cast<float>();
    s.velocity_mps = t.velocity_mps.cast<float>();
    d.truth.push_back(s);
    next = t.stamp + truth_period;
  }
  std::vector<int64_t> lat = log.pose_delivery_us;
  if (!lat.empty()) {
    std::nth_element(lat.begin(), lat.begin() + static_cast<std::ptrdiff_t>(lat.size() / 2), lat.end());
    d.latency = Duration{lat[lat.size() / 2]};
  }
  return d;
}

VelocityTrace trace_velocity(estimation::NavFilter& filter, const estimation::EkfParams& params,
                             const estimation::RecordedRun& run) {
  VelocityTrace out;
  filter.reset();
  if (!ok(filter.set_params(params))) return out;
  estimation::replay_run(filter, run, [&](const estimation::TruthSample& truth, const NavState& s) {
    if (!s.valid) return;
    out.t_s.push_back((truth.stamp - run.truth.front().stamp).seconds());
    out.velocity.push_back(s.velocity_mps.cast<double>());
  });
  return out;
}

VelocityTrace truth_velocity(const estimation::RecordedRun& run) {
  VelocityTrace out;
  for (const estimation::TruthSample& t : run.truth) {
    out.t_s.push_back((t.stamp - run.truth.front().stamp).seconds());
    out.velocity.push_back(t.velocity_mps.cast<double>());
  }
  return out;
}

estimation::EkfParams blend_log(const estimation::EkfParams& from, const estimation::EkfParams& to, double lambda) {
  estimation::EkfParams out = from, target = to;
  auto fo = estimation::ekf_param_fields(out);
  auto ft = estimation::ekf_param_fields(target);
  for (std::size_t i = 0; i < fo.size(); ++i) {
    bool learnable = false;
    for (const char* k : estimation::kLearnableParams) learnable = learnable || std::strcmp(k, fo[i].key) == 0;
    if (!learnable || !(*fo[i].value > 0) || !(*ft[i].value > 0)) continue;
    const double v = std::exp((1 - lambda) * std::log(*fo[i].value) + lambda * std::log(*ft[i].value));
    *fo[i].value = std::clamp(static_cast<float>(v), fo[i].min, fo[i].max);
  }
  return out;
}

Status write_velocity_plot(const std::string& path, const VelocityTrace& truth, const VelocityTrace& before,
                           const VelocityTrace& after) {
  const char* axis_name[3] = {"x", "y", "z"};
  std::vector<output::Panel> panels;
  auto series = [](const VelocityTrace& tr, int axis, const char* label, output::Rgb color) {
    output::Series s{label, color, tr.t_s, {}};
    s.y.reserve(tr.velocity.size());
    for (const Eigen::Vector3d& v : tr.velocity) s.y.push_back(v[axis]);
    return s;
  };
  for (int a = 0; a < 3; ++a) {
    output::Panel p;
    p.title = std::string("velocity ") + axis_name[a] + ": truth vs EKF estimate";
    p.y_label = "m/s";
    p.series.push_back(series(truth, a, "truth", output::colors::kBlack));
    p.series.push_back(series(before, a, "hand-chosen parameters", output::colors::kRed));
    p.series.push_back(series(after, a, "learned parameters", output::colors::kBlue));
    panels.push_back(std::move(p));
  }
  return output::write_png(path, output::plot_panels(panels, "time (s)"));
}

}  // namespace kestrel::tuning
