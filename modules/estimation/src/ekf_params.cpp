#include "kestrel/estimation/ekf_params.hpp"

namespace kestrel::estimation {

std::array<params::ParamField, kEkfParamCount> ekf_param_fields(EkfParams& p) {
  return {{
      {"accel_noise_xy", &p.accel_noise_xy, 1e-9f, 1e3f, "(m/s^2)^2/Hz",
       "accelerometer white noise density, horizontal"},
      {"accel_noise_z", &p.accel_noise_z, 1e-9f, 1e3f, "(m/s^2)^2/Hz", "accelerometer white noise density, vertical"},
      {"accel_bias_walk", &p.accel_bias_walk, 1e-14f, 1e2f, "(m/s^3)^2/Hz", "accelerometer bias random walk density"},
      {"gyro_noise", &p.gyro_noise, 1e-12f, 1e1f, "(rad/s)^2/Hz", "yaw gyro white noise density"},
      {"gyro_bias_walk", &p.gyro_bias_walk, 1e-16f, 1e0f, "(rad/s^2)^2/Hz", "yaw gyro bias random walk density"},
      {"position_walk", &p.position_walk, 0.0f, 1e1f, "m^2/s", "unmodelled position random walk"},
      {"pose_cov_scale", &p.pose_cov_scale, 1e-4f, 1e4f, "1", "scale of the scan matcher's x, y covariance"},
      {"heading_cov_scale", &p.heading_cov_scale, 1e-4f, 1e4f, "1", "scale of the scan matcher's heading variance"},
      {"altimeter_var", &p.altimeter_var, 1e-10f, 1e2f, "m^2", "altimeter variance when the sample has none"},
      {"altimeter_var_scale", &p.altimeter_var_scale, 1e-4f, 1e4f, "1", "scale of the altimeter's variance"},
      {"at_rest_var", &p.at_rest_var, 1e-10f, 1e2f, "(m/s)^2", "zero-velocity variance while resting on the ground"},
      {"init_pos_var", &p.init_pos_var, 1e-10f, 1e4f, "m^2", "initial position variance"},
      {"init_vel_var", &p.init_vel_var, 1e-10f, 1e4f, "(m/s)^2", "initial velocity variance"},
      {"init_accel_bias_var", &p.init_accel_bias_var, 1e-10f, 1e2f, "(m/s^2)^2", "initial accelerometer bias variance"},
      {"init_heading_var", &p.init_heading_var, 1e-10f, 1e1f, "rad^2", "initial heading variance"},
      {"init_gyro_bias_var", &p.init_gyro_bias_var, 1e-12f, 1e0f, "(rad/s)^2", "initial gyro bias variance"},
      {"pose_gate_chi2", &p.pose_gate_chi2, 0.1f, 1e6f, "1", "gate on the pose innovation, chi-square 3 dof"},
      {"altitude_gate_chi2", &p.altitude_gate_chi2, 0.1f, 1e6f, "1",
       "gate on the altitude innovation, chi-square 1 dof"},
      {"max_correction_m", &p.max_correction_m, 0.0f, 1e3f, "m", "largest accepted SLAM correction"},
      {"altitude_relock_s", &p.altitude_relock_s, 0.0f, 60.0f, "s",
       "a run of gated heights this long is decided: a floor step or a re-lock (0: never)"},
      {"altitude_step_tol_m", &p.altitude_step_tol_m, 0.01f, 0.3f, "m",
       "largest step within a run of gated heights; least jump of a floor step; settled readings' spread"},
      {"altitude_relock_vel_var", &p.altitude_relock_vel_var, 0.0f, 1e2f, "(m/s)^2",
       "added to the vertical velocity variance at a height re-lock"},
      {"max_imu_gap_s", &p.max_imu_gap_s, 1e-3f, 10.0f, "s", "longer IMU gaps restart the state history"},
      {"max_future_s", &p.max_future_s, 0.0f, 1.0f, "s", "how far a measurement may lead the newest IMU sample"},
      {"gravity_mps2", &p.gravity_mps2, 9.7f, 9.9f, "m/s^2", "local gravity"},
  }};
}

Status validate(const EkfParams& p) {
  EkfParams copy = p;
  return params::check_ranges(ekf_param_fields(copy));
}

Status load_ekf_params(const char* path, EkfParams& out, params::ParamError& error) {
  // Every EKF parameter stands alone: validate() is the range check the file already passed.
  return params::load_params_struct(path, out, ekf_param_fields, [](const EkfParams& p) { return validate(p); },
                                    "EKF parameters out of range", error);
}

}  // namespace kestrel::estimation
