#pragma once
// A mission is what flies the simulated vehicle in kestrel-sim: `manual` replays a command
// script; later missions (hover, waypoints, explore) run the autonomy stack. A mission sees
// the simulation through its HAL drivers (sim.clock(), sim.laser(), sim.imu(),
// sim.altimeter(), sim.flight_controller()) and may read ground truth only for metrics.
//
// To add a mission: implement this interface and add one row to the table in
// mission_registry.cpp (name, one-line summary, factory).
#include "kestrel/output/canvas.hpp"
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel::sim {

class Simulation;
class FlightRecorder;

enum class MissionState : uint8_t { kRunning, kDone, kFailed };

// Extra numbers a mission adds to metrics.json (name, value), e.g. {"hover_rms_m", 0.06}.
using MissionMetrics = std::vector<std::pair<std::string, double>>;

// The mission's horizontal position estimate minus the truth, in the world frame.
struct EstimateError {
  double x_m = 0;
  double y_m = 0;
};

class Mission {
 public:
  virtual ~Mission() = default;
  virtual const char* name() const = 0;
  // Called once at t = 0, before the first tick; an error aborts the run.
  virtual Status start(Simulation& sim) = 0;
  // Called at the start time and then every tick_period() of simulated time, each time after
  // the world has been stepped to now.
  virtual MissionState tick(Simulation& sim) = 0;
  virtual Duration tick_period() const { return Duration::from_ms(10); }
  // Mission-specific metrics, appended to the run's metrics.
  virtual void metrics(MissionMetrics& /*out*/) const {}
  // The estimate's error at `t`, for metrics.json's contacts: a contact with the estimate
  // metres off is the estimator's; one with it on the truth is not (the guidance's, or a
  // surface the simulated laser does not show). Nothing (the default) when the mission keeps
  // no estimate, or had none shortly before `t`.
  virtual std::optional<EstimateError> estimate_error_at(TimeUs /*t*/) const { return std::nullopt; }
  // A one-line reason after kFailed.
  virtual std::string failure() const { return {}; }
  // Per-scan traces (kestrel-sim --trace-scans): a mission that runs a scan matcher writes one
  // CSV row per scan it processed into out_dir/scan_trace.csv, opened here, before start(),
  // and closed with the run, and may write traces of its other stages beside it (the compact
  // SLAM's: slam_trace.csv). kUnsupported (the default) when the mission has no scan matcher.
  virtual Status open_traces(const std::string& /*out_dir*/) { return Status::kUnsupported; }
  // Files of the mission's own in --out DIR (an estimated trajectory, plots), after the run.
  virtual Status write_outputs(const std::string& /*out_dir*/) const { return Status::kOk; }
  // The mission's layer on render.png (estimated path, planner state), drawn over the true
  // path with the canvas's world view already set; and its legend rows.
  virtual void draw(output::Canvas& /*canvas*/) const {}
  struct LegendRow {
    const char* label;
    output::Rgb color;
  };
  virtual std::vector<LegendRow> legend() const { return {}; }
  // The tool's recorder of the flight (coverage and its history, rooms), set before start();
  // write_outputs may read it. Null when the tool records nothing.
  void set_recorder(const FlightRecorder* recorder) { recorder_ = recorder; }

 protected:
  const FlightRecorder* recorder() const { return recorder_; }

 private:
  const FlightRecorder* recorder_ = nullptr;
};

}  // namespace kestrel::sim
