#include "kestrel/estimation/noise_learning.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace kestrel::estimation {
namespace {

struct Accumulator {
  double sum_sq = 0, sum = 0, sum_pos = 0, sum_pos_sq = 0;
  std::size_t n = 0;
};

void replay(NavFilter& filter, const RecordedRun& run, Accumulator& acc) {
  replay_run(filter, run, [&](const TruthSample& truth, const NavState& s) {
    if (!s.valid || truth.stamp < run.truth.front().stamp + run.score_after) return;
    const float e = (s.velocity_mps - truth.velocity_mps).norm();
    if (!std::isfinite(e)) {
      acc.sum_sq = std::numeric_limits<double>::infinity();
      return;
    }
    const double ep = (s.position_m - truth.position_m).norm();
    acc.sum_sq += static_cast<double>(e) * e;
    acc.sum += e;
    acc.sum_pos += ep;
    acc.sum_pos_sq += std::isfinite(ep) ? ep * ep : std::numeric_limits<double>::infinity();
    ++acc.n;
  });
}

}  // namespace

VelocityError evaluate_velocity_error(NavFilter& filter, const EkfParams& params, std::span<const RecordedRun> runs,
                                      float position_time_s) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Accumulator acc;
  for (const RecordedRun& run : runs) {
    filter.reset();
    if (!ok(filter.set_params(params)) || !(position_time_s >= 0)) return VelocityError{kInf, kInf, 0, 0, 0, 0};
    replay(filter, run, acc);
  }
  VelocityError out;
  out.samples = acc.n;
  if (acc.n == 0) {
    out.objective = out.rms_mps = kInf;
    return out;
  }
  const double n = static_cast<double>(acc.n);
  out.rms_mps = std::sqrt(acc.sum_sq / n);
  const double tau = position_time_s;
  out.objective = tau > 0 ? std::sqrt((acc.sum_sq + acc.sum_pos_sq / (tau * tau)) / n) : out.rms_mps;
  out.mean_mps = acc.sum / n;
  out.std_mps = std::sqrt(std::max(0.0, acc.sum_sq / n - out.mean_mps * out.mean_mps));
  out.pos_mean_m = acc.sum_pos / n;
  return out;
}

LearningResult learn_noise_parameters(NavFilter& filter, const EkfParams& start, std::span<const RecordedRun> runs,
                                      const LearningOptions& options) {
  LearningResult r;
  r.params = start;
  r.before = evaluate_velocity_error(filter, start, runs, options.position_time_s);
  r.evaluations = 1;
  double best = r.before.objective;
  VelocityError best_err = r.before;
  float step = options.initial_log_step;
  auto fields = ekf_param_fields(r.params);
  while (step >= options.min_log_step && r.evaluations < options.max_evaluations) {
    bool improved = false;
    for (const char* key : kLearnableParams) {
      const params::ParamField* field = nullptr;
      for (const params::ParamField& f : fields) {
        if (std::strcmp(f.key, key) == 0) field = &f;
      }
      if (field == nullptr) continue;
      for (const float dir : {1.0f, -1.0f}) {
        if (r.evaluations >= options.max_evaluations) break;
        const float old = *field->value;
        const float candidate = std::clamp(old * std::exp(dir * step), field->min, field->max);
        if (candidate == old) continue;
        *field->value = candidate;
        const VelocityError e = evaluate_velocity_error(filter, r.params, runs, options.position_time_s);
        ++r.evaluations;
        if (e.objective < best) {
          best = e.objective;
          best_err = e;
          improved = true;
          break;  // keep it; next parameter
        }
        *field->value = old;
      }
    }
    if (!improved) step *= 0.5f;
  }
  r.after = best_err;
  return r;
}

}  // namespace kestrel::estimation
