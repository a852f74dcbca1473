#pragma once
// The closed-loop missions of kestrel-sim: the autonomy stack (modules/autonomy) flies the
// simulated vehicle through the simulator's HAL drivers, exactly as kestrel-fw flies the
// real one. `hover` takes off, hovers at 1 m and lands; `waypoints` flies a list of
// waypoints; `explore` explores with the chosen explorer and flies home. The mission reads
// ground truth only to score the flight: hover error, estimate error, trajectories, plots.
//
// Options (--mission-arg KEY=VALUE, or the named CLI flags):
//   waypoints=FILE   one waypoint per line: x y z [heading_deg [hold_s]] (waypoints mission)
//   explorer=NAME    blend (default), wallfollow, srt or frontier (explore mission)
//   hover_s=S        time at the hover set-point (default 60)
//   explore_s=S      explore phase time limit (default 600)
//   delay_s=S        extra delivery delay of every scan (paper 000 Figure 3b)
//   history=on|off   apply scans at the time they were taken (on, default) or on arrival
//   ekf=FILE         EKF parameter file, loaded over the laser's defaults (estimation::load_ekf_params)
//   controller=FILE  controller parameter file (control::load_controller_params)
#include <array>
#include <memory>
#include <string>
#include <optional>
#include <vector>

#include "kestrel/autonomy/autonomy_stack.hpp"
#include "kestrel/flight/delayed_laser.hpp"
#include "kestrel/flight/scan_trace.hpp"
#include "kestrel/flight/slam_trace.hpp"
#include "kestrel/metrics/ekf_error_stats.hpp"
#include "kestrel/metrics/horizontal_drift.hpp"
#include "kestrel/metrics/runaway_counter.hpp"
#include "kestrel/sim/mission.hpp"
#include "kestrel/sim/mission_registry.hpp"

namespace kestrel::flight {

struct FlightOptions {
  mission::MissionKind kind = mission::MissionKind::kHover;
  autonomy::StackConfig stack;
  // start() gives the filter the defaults of the simulated laser (autonomy::vehicle_ekf_params)
  // and loads ekf_file (ekf=FILE) over them; false keeps stack.ekf as it is (the tuning tools).
  bool ekf_for_laser = true;
  std::string ekf_file;
  // The compact SLAM: on or off (slam=on|off|FILE), or, unset, as the simulated laser's
  // default (autonomy::vehicle_slam_enabled); stack.slam holds its parameters.
  std::optional<bool> slam_on;
  double delay_s = 0;
  bool use_measurement_time = true;
};

// Parses the options of mission `kind`; "" or the reason they are unusable.
std::string parse_flight_options(mission::MissionKind kind, const sim::MissionOptions& options, FlightOptions& out);
// Explore's keep-out boxes, "x_min,y_min,x_max,y_max[;...]" in metres of the navigation frame
// (the world frame: the estimate starts at the world's start pose), into srt.keep_out; "" or
// the reason the text is unusable.
std::string parse_keep_outs(const std::string& text, exploration::SrtParams& srt);
// Reads a waypoint file; "" or "FILE:LINE: reason".
std::string load_waypoints(const std::string& path, autonomy::StackConfig& stack);

// One sample of estimate against truth, taken at every scan.
struct EstimateSample {
  double t_s;
  Eigen::Vector3d est_pos, true_pos, est_vel, true_vel;
  double est_yaw, true_yaw;
};

// The estimate's error (estimate minus truth) of the newest sample at or before `t_s`, if that
// sample is at most `max_age_s` older: a contact the filter saw no scan near is not put on it.
// Samples are taken every scan (25-100 ms): half a second without one is several scans lost.
inline constexpr double kContactSampleMaxAgeS = 0.5;
std::optional<sim::EstimateError> estimate_error_at(const std::vector<EstimateSample>& samples, double t_s,
                                                    double max_age_s);

class AutonomyMission final : public sim::Mission {
 public:
  explicit AutonomyMission(FlightOptions options);
  ~AutonomyMission() override;

  const char* name() const override { return mission::to_string(options_.kind); }
  Status start(sim::Simulation& sim) override;
  sim::MissionState tick(sim::Simulation& sim) override;
  Duration tick_period() const override { return Duration::from_ms(1); }
  void metrics(sim::MissionMetrics& out) const override;
  // From the samples taken at every scan: the newest within kContactSampleMaxAgeS before `t`.
  std::optional<sim::EstimateError> estimate_error_at(TimeUs t) const override;
  std::string failure() const override { return failure_; }
  Status write_outputs(const std::string& out_dir) const override;
  // scan_trace.csv now; slam_trace.csv in start(), once the stack says whether the SLAM runs.
  Status open_traces(const std::string& out_dir) override;
  void draw(output::Canvas& canvas) const override;
  std::vector<LegendRow> legend() const override;

  const autonomy::AutonomyStack& stack() const { return *stack_; }
  const std::vector<EstimateSample>& samples() const { return samples_; }
  double hover_rms_m() const;

 private:
  void score(sim::Simulation& sim);
  void trace(sim::Simulation& sim);
  void trace_slam(sim::Simulation& sim);
  // write_outputs' files but the traces: trajectory_est.tum, the maps, the plots.
  Status write_flight_files(const std::string& dir) const;

  FlightOptions options_;
  class RealClock;
  std::unique_ptr<RealClock> exec_clock_;
  std::unique_ptr<DelayedLaser> delayed_;
  std::unique_ptr<autonomy::AutonomyStack> stack_;
  std::string failure_;
  uint64_t allocs_in_loop_ = 0;
  // Scores.
  std::vector<EstimateSample> samples_;
  double hover_sq_sum_ = 0;
  uint64_t hover_n_ = 0;
  metrics::EkfErrorAccumulator nav_error_;
  metrics::HorizontalDriftAccumulator drift_;
  metrics::RunawayCounter runaways_;  // estimate_runaways in metrics.json
  ScanTrace trace_;  // --trace-scans (scan_trace.hpp); closed unless asked for
  SlamTrace slam_trace_;  // --trace-scans with the compact SLAM (slam_trace.hpp)
  std::string traces_dir_;  // where --trace-scans writes; empty when not asked for
  uint32_t slam_steps_traced_ = 0;
};

}  // namespace kestrel::flight
