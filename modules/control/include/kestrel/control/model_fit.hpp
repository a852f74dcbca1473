#pragma once
// Identification of paper 000 equations 1 and 2 by linear least squares, from logged commands
// and motion (the paper flew in a motion-capture room and fitted the data the same way).
//   equation 1: s'' = k u + b               regressors [u, 1]
//   equation 2: s'' = k1 u + k2 s' + b      regressors [u, s', 1]; k2 ~ 0 means undamped
// ModelFit accumulates the normal equations of one axis (constant memory, any log length) and
// solves them with a pivoted Cholesky factorisation in double precision. A fit whose regressors
// do not excite the model (constant command, too few samples) is refused with
// kInvalidArgument; non-finite samples are skipped and counted.
//
// fit_vehicle_model() fits all four axes of VehicleModel from a flight log: it rotates the
// world-frame accelerations into the body frame with the heading, then fits x''_b on pitch,
// y''_b on roll, z'' on thrust and the yaw rate on its command.
//
// API
//   ModelFit::add(u, rate, accel); fit_undamped() -> Result<UndampedFit>; fit_damped() -> Result<DampedFit>
//   fit_vehicle_model(samples) -> Result<VehicleModel>
#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "kestrel/control/vehicle_model.hpp"
#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::control {

struct UndampedFit {
  double k = 0, b = 0;
  double rms = 0;  // residual, in the response's unit
};

struct DampedFit {
  double k1 = 0, k2 = 0, b = 0;
  double rms = 0;
};

class ModelFit {
 public:
  // One sample: command u, the rate s' (velocity) and the response s'' (acceleration).
  void add(double u, double rate, double response);
  Result<UndampedFit> fit_undamped() const;
  Result<DampedFit> fit_damped() const;
  std::size_t samples() const { return n_; }
  std::size_t skipped() const { return skipped_; }

 private:
  Eigen::Matrix3d ata_ = Eigen::Matrix3d::Zero();  // over [u, s', 1]
  Eigen::Vector3d aty_ = Eigen::Vector3d::Zero();
  double yty_ = 0;
  std::size_t n_ = 0;
  std::size_t skipped_ = 0;
};

// One logged instant: the command in force and the motion it produced.
struct ModelSample {
  AttitudeSetpoint command;
  Eigen::Vector3f velocity_mps = Eigen::Vector3f::Zero();  // world frame
  Eigen::Vector3f accel_mps2 = Eigen::Vector3f::Zero();    // world frame
  float heading_rad = 0;
  float yaw_rate_radps = 0;
};

Result<VehicleModel> fit_vehicle_model(std::span<const ModelSample> samples);

}  // namespace kestrel::control
