#pragma once
// Noise and gating parameters of the navigation filter (paper 000 section 5.2), with their
// parameter-file binding. Noise terms are continuous-time densities so that they do not depend
// on the IMU rate: a white accelerometer noise of per-sample variance s2 at sample period T
// has density s2 * T. These are the numbers the discriminative learning of NoiseLearning tunes.
//
// API
//   EkfParams                     the values, defaults inline
//   std::array<ParamField, N> ekf_param_fields(EkfParams&)   binding for params::parse/write
//   Status validate(const EkfParams&)                         the same ranges, for code paths
//   Status load_ekf_params(path, EkfParams&, ParamError&)     load + validate a file
#include <array>

#include "kestrel/core/status.hpp"
#include "kestrel/params/param_file.hpp"

namespace kestrel::estimation {

struct EkfParams {
  // Process noise.
  float accel_noise_xy = 4e-3f;     // (m/s^2)^2/Hz: accelerometer white noise, horizontal
  float accel_noise_z = 4e-3f;      // (m/s^2)^2/Hz: accelerometer white noise, vertical
  float accel_bias_walk = 1e-5f;    // (m/s^3)^2/Hz: accelerometer bias random walk
  float gyro_noise = 1e-5f;         // (rad/s)^2/Hz: yaw gyro white noise
  float gyro_bias_walk = 1e-8f;     // (rad/s^2)^2/Hz: yaw gyro bias random walk
  float position_walk = 1e-6f;      // m^2/s: unmodelled position motion (keeps P positive)
  // Measurement noise.
  float pose_cov_scale = 1.0f;      // 1: multiplies the scan matcher's x, y covariance
  float heading_cov_scale = 1.0f;   // 1: multiplies the scan matcher's heading variance
  float altimeter_var = 1e-4f;      // m^2: used when a sample carries no variance
  float altimeter_var_scale = 1.0f; // 1: multiplies the altimeter's own variance
  float at_rest_var = 1e-4f;        // (m/s)^2: the zero velocity of a vehicle resting on the ground
  // Initial uncertainty (set when the first pose initialises the filter).
  float init_pos_var = 1e-2f;       // m^2
  float init_vel_var = 1e-2f;       // (m/s)^2
  float init_accel_bias_var = 0.04f;// (m/s^2)^2
  float init_heading_var = 1e-3f;   // rad^2
  float init_gyro_bias_var = 1e-4f; // (rad/s)^2
  // Gates: squared Mahalanobis distance of the innovation, chi-square quantiles.
  float pose_gate_chi2 = 16.27f;    // 1: 3 dof (x, y, heading), 99.9 %
  float altitude_gate_chi2 = 10.83f;// 1: 1 dof, 99.9 %
  float max_correction_m = 10.0f;   // m: larger SLAM corrections are rejected
  // A run of rejected heights: the altimeter measures the height above whatever is below, so a
  // run (readings rejected in a row, no innovation further than altitude_step_tol_m from the one
  // before) that lasts altitude_relock_s (IMU gaps included) and kRelockMinRejected readings is
  // decided. If the readings jumped (over altitude_step_tol_m from the last reading taken within
  // NavFilter::kJumpWithinS of the run's start: faster than the estimate creeps) and stayed (its
  // readings settled, none over altitude_step_tol_m from where they had, for
  // NavFilter::kSettledShare of altitude_relock_s before the decision: at a box's edge a tilted
  // beam meets its side face and ramps the first few; a run that jumped is given kSettledShare of
  // altitude_relock_s more to), the floor moved (a box, a bench): the floor under the vehicle is
  // placed again and the world height kept. So is a run over a raised floor that moved over
  // altitude_step_tol_m and ends within it of where the take-off floor would put it, however it
  // got there (leaving a box, the side face ramps it). Otherwise the estimate moved (a height that
  // crept out of its own gate and would refuse every true reading after it): the height is set
  // from the altimeter again.
  // 0.4 s: the value flown and tested (modules/exploration/EXPERIMENTS.md, The defaults flipped,
  // and Height runs at a box's edge). 0 never decides, the filter before the runs: over furniture
  // whose top the altimeter reads, every true height is refused until the gate widens
  // (EXPERIMENTS, Obstacle tops seen from above).
  float altitude_relock_s = 0.4f;       // s: 0 never decides (a run stays rejected until the gate widens)
  // m: a run's steps between readings; a floor step's least jump; how far settled readings move
  float altitude_step_tol_m = 0.1f;
  float altitude_relock_vel_var = 0.25f;// (m/s)^2: added to the vertical velocity's variance at a re-lock
  // Bad input handling.
  float max_imu_gap_s = 0.1f;       // s: a longer IMU gap restarts the history
  float max_future_s = 0.05f;       // s: a measurement may be stamped this far past the newest IMU sample
  float gravity_mps2 = 9.80665f;    // m/s^2
};

inline constexpr std::size_t kEkfParamCount = 25;
std::array<params::ParamField, kEkfParamCount> ekf_param_fields(EkfParams& p);
Status validate(const EkfParams& p);
// Loads `path` over the defaults in `out`; on any error `out` is unchanged.
Status load_ekf_params(const char* path, EkfParams& out, params::ParamError& error);

}  // namespace kestrel::estimation
