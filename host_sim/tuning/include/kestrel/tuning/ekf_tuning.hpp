#pragma once
// The host side of learning the EKF's noise parameters (paper 000 section 5.2, Figure 6b):
// turns recorded simulator flights into estimation::RecordedRun (the learning core's input),
// and replays a run through the filter to draw the estimated against the true velocity.
//
// API
//   RunData make_run_data(log)         owns the truth samples a RecordedRun points to
//   RecordedRun RunData::run() const
//   VelocityTrace trace_velocity(filter, params, run)
//   Status write_velocity_plot(path, truth trace, before trace, after trace)
//   EkfParams blend_log(from, to, lambda)
#include <string>
#include <vector>

#include "kestrel/estimation/noise_learning.hpp"
#include "kestrel/tuning/flight_log.hpp"

namespace kestrel::tuning {

struct RunData {
  const FlightLog* log = nullptr;
  std::vector<estimation::TruthSample> truth;  // every truth_period of the log, airborne only
  Duration latency;                            // median pose delivery delay
  estimation::RecordedRun run() const;
};

// truth_period: the scoring rate (the log holds every 1 ms physics step).
RunData make_run_data(const FlightLog& log, Duration truth_period = Duration::from_ms(10));

struct VelocityTrace {
  std::vector<double> t_s;
  std::vector<Eigen::Vector3d> velocity;  // filter estimate (or truth)
};

// The filter's velocity at every truth sample of `run`, replayed exactly as the learning
// core replays it (delivery order, measurement latency).
VelocityTrace trace_velocity(estimation::NavFilter& filter, const estimation::EkfParams& params,
                             const estimation::RecordedRun& run);
VelocityTrace truth_velocity(const estimation::RecordedRun& run);

// The learnable parameters moved a fraction `lambda` of the way from `from` to `to` in log
// space (lambda 1 = `to`, 0 = `from`); the others are taken from `from`. The replay objective
// sees the filter alone, not the closed loop, so the tool shrinks a learned step this way
// until the closed-loop hover accepts it.
estimation::EkfParams blend_log(const estimation::EkfParams& from, const estimation::EkfParams& to, double lambda);

// Figure 6b: one panel per horizontal axis (and z), truth, hand-chosen and learned estimates.
Status write_velocity_plot(const std::string& path, const VelocityTrace& truth, const VelocityTrace& before,
                           const VelocityTrace& after);

}  // namespace kestrel::tuning
