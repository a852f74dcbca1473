#pragma once
#include <cstdint>
// Learning the filter's noise parameters from flights with ground truth (paper 000 section
// 5.2, after Abbeel, Coates, Montemerlo, Ng and Thrun, "Discriminative training of Kalman
// filters", RSS 2005): instead of the likelihood of the measurements, minimise the error that
// matters to the controller, the velocity error against ground truth, over the variance
// parameters. Steps:
//   1. replay the recorded sensor streams through the filter in delivery order (measurements
//      arrive `measurement_latency` after they were taken, as on the vehicle);
//   2. at every ground-truth sample (after the start-up transient) compare the filter's velocity
//      with the true velocity; the paper's objective is the mean squared norm of the difference.
//      Ours adds the position error over a time constant tau (|dv|^2 + |dp|^2 / tau^2): the
//      controller acts on both (its LQR gains weigh a centimetre about as much as a centimetre
//      per second, so tau = 1 s), and variances learned on velocity alone let the position
//      wander -- flown in closed loop they made the hover diverge. tau = 0 is the paper's;
//   3. coordinate descent in log-variance space over the learnable parameters (noise
//      densities and measurement-covariance scales; variances stay positive and the step is
//      a factor), halving the step when a full sweep does not improve, within each
//      parameter's valid range.
// Deterministic (no sampling), so a tuning run is reproducible. This is the core of the host
// tool; it allocates nothing and takes the filter as a workspace.
//
// API
//   VelocityError evaluate_velocity_error(filter, params, runs, tau)
//   LearningResult learn_noise_parameters(filter, start, runs, options)
#include <array>
#include <span>

#include "kestrel/core/messages.hpp"
#include "kestrel/estimation/ekf_params.hpp"
#include "kestrel/estimation/nav_filter.hpp"

namespace kestrel::estimation {

struct TruthSample {
  TimeUs stamp;
  Eigen::Vector3f position_m = Eigen::Vector3f::Zero();
  Eigen::Vector3f velocity_mps = Eigen::Vector3f::Zero();
};

// One recorded flight. Every stream is sorted by stamp; attitude and altitude may be empty.
struct RecordedRun {
  std::span<const ImuSample> imu;
  std::span<const FlightStatus> attitude;
  std::span<const PoseMeasurement2> poses;
  std::span<const AltimeterSample> altitude;
  std::span<const TruthSample> truth;
  Duration measurement_latency;  // poses and altitude are delivered this long after their stamp
  // Truth samples earlier than this after the run's first one are not scored: the filter's
  // start-up transient (velocity initialised at zero) says nothing about the noise parameters.
  Duration score_after = Duration::from_s(2.0);
};

// Feeds a recorded run to the filter in delivery order (attitude, then IMU, then the
// measurements, each `measurement_latency` after its stamp; on ties the autopilot's attitude is
// current when its IMU sample arrives) and calls on_truth(truth, filter.state()) at every truth
// sample once everything due by then has been delivered. The learning objective and the
// tuning tool's plots both replay runs through this one loop.
template <class OnTruth>
void replay_run(NavFilter& filter, const RecordedRun& run, OnTruth&& on_truth) {
  std::size_t i_imu = 0, i_att = 0, i_pose = 0, i_alt = 0;
  const Duration lat = run.measurement_latency;
  const TimeUs never{INT64_MAX};
  for (const TruthSample& truth : run.truth) {
    for (;;) {
      const TimeUs t_att = i_att < run.attitude.size() ? run.attitude[i_att].stamp : never;
      const TimeUs t_imu = i_imu < run.imu.size() ? run.imu[i_imu].stamp : never;
      const TimeUs t_pose = i_pose < run.poses.size() ? run.poses[i_pose].stamp + lat : never;
      const TimeUs t_alt = i_alt < run.altitude.size() ? run.altitude[i_alt].stamp + lat : never;
      TimeUs next = t_att;
      int which = 0;
      if (t_imu < next) { next = t_imu; which = 1; }
      if (t_pose < next) { next = t_pose; which = 2; }
      if (t_alt < next) { next = t_alt; which = 3; }
      if (next > truth.stamp) break;
      switch (which) {
        case 0: filter.set_attitude(run.attitude[i_att++]); break;
        case 1: (void)filter.predict(run.imu[i_imu++]); break;
        case 2: (void)filter.update_pose(run.poses[i_pose++]); break;
        default: (void)filter.update_altitude(run.altitude[i_alt++]); break;
      }
    }
    on_truth(truth, filter.state());
  }
}

struct VelocityError {
  double objective = 0; // sqrt of the mean of |dv|^2 + |dp|^2 / tau^2: what learning minimises
  double rms_mps = 0;   // sqrt of the mean of |dv|^2
  double mean_mps = 0;  // mean norm of the velocity error
  double std_mps = 0;   // standard deviation of that norm
  double pos_mean_m = 0;
  std::size_t samples = 0;
};

// Parameters the learning varies (the rest, gates and initial variances, stay as given).
inline constexpr std::array<const char*, 8> kLearnableParams = {
    "accel_noise_xy", "accel_noise_z", "accel_bias_walk", "gyro_noise",
    "gyro_bias_walk", "pose_cov_scale", "heading_cov_scale", "altimeter_var_scale"};

struct LearningOptions {
  int max_evaluations = 300;
  float position_time_s = 0.0f;   // tau of the objective; 0: velocity error only (paper 000)
  float initial_log_step = 1.5f;  // first step: a factor e^1.5 = 4.5
  float min_log_step = 0.1f;      // stop when the step is below a factor 1.1
};

struct LearningResult {
  EkfParams params;
  VelocityError before;
  VelocityError after;
  int evaluations = 0;
};

VelocityError evaluate_velocity_error(NavFilter& filter, const EkfParams& params, std::span<const RecordedRun> runs,
                                      float position_time_s = 0.0f);
LearningResult learn_noise_parameters(NavFilter& filter, const EkfParams& start, std::span<const RecordedRun> runs,
                                      const LearningOptions& options = {});

}  // namespace kestrel::estimation
