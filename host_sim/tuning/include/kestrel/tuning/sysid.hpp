#pragma once
// The host side of model identification (paper 000 section 4): from a recorded flight, the
// set-points the autopilot applied and the true motion become control::ModelSample, and
// control::fit_vehicle_model fits equation 1 by least squares.
//
// The autopilot does not reach a commanded attitude at once (the simulator, like a real
// attitude loop, lags by a time constant). Fitting equation 1 to the raw command then
// underestimates k by roughly tau / (hold time). The tool identifies that lag too: for each
// axis it passes the command through a first-order lag of time constant tau, fits k and b by
// least squares, and keeps the tau of the smallest residual (a one-dimensional grid search
// around a linear fit). The fitted model is then the equation-1 gain of the lagged command.
//
// API
//   SysidResult identify_vehicle(log, options) -> fitted model, lags, residuals, sample count
#include <array>
#include <string>

#include "kestrel/control/model_fit.hpp"
#include "kestrel/tuning/flight_log.hpp"

namespace kestrel::tuning {

struct SysidOptions {
  double max_lag_s = 0.3;    // grid of tau: 0 .. max_lag_s
  double lag_step_s = 0.005;
  double min_height_m = 0.15;  // samples below this (take-off, ground effect, contact) are skipped
  int decimation = 5;          // use every n-th physics step
};

struct SysidResult {
  Status status = Status::kOk;
  control::VehicleModel model;
  std::array<double, 4> lag_s{};    // pitch, roll, thrust, yaw
  std::array<double, 4> rms{};      // residual of each axis at its lag
  std::array<double, 4> rms_no_lag{};
  std::size_t samples = 0;
};

SysidResult identify_vehicle(const FlightLog& log, const SysidOptions& options = {});

// The default excitation flight for kestrel-sysid: take-off, then pitch, roll, thrust and
// yaw-rate doublets held ~1 s each around the hover, in the iarc-arena hallway, and landing.
std::string sysid_script_text();

}  // namespace kestrel::tuning
