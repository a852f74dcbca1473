#pragma once
// A synthetic flight for the estimation tests: an analytic, smooth trajectory (sums of sines in
// x, y, z and heading) and the sensor streams the filter's model assumes: IMU specific force in
// the body frame with a constant body-frame bias and white noise, the yaw gyro with bias and
// noise, scan-matcher poses and altimeter heights with white noise of the stated covariance,
// and ground truth at every IMU sample. With `tilt` the vehicle flies like a quadrotor: the
// specific force is thrust along body z only, and the horizontal acceleration comes from roll
// and pitch, which are reported in FlightStatus (right-handed about body x and y, as the
// simulator's autopilot reports them).
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "kestrel/core/messages.hpp"
#include "kestrel/estimation/ekf_params.hpp"
#include "kestrel/estimation/nav_filter.hpp"
#include "kestrel/estimation/noise_learning.hpp"

namespace kestrel::test {

struct SyntheticConfig {
  double duration_s = 20.0;
  int imu_hz = 200;
  int pose_hz = 40;
  int64_t pose_offset_us = 1700;    // poses are not taken exactly at IMU samples
  float accel_sigma = 0.1f;         // m/s^2 per sample
  float gyro_sigma = 0.003f;        // rad/s per sample
  float accel_bias_sigma = 0.1f;    // m/s^2, per-axis body bias drawn per flight
  float gyro_bias_sigma = 0.01f;    // rad/s
  float pose_sigma = 0.01f;         // m
  float heading_sigma = 0.005f;     // rad
  float alt_sigma = 0.01f;          // m
  float amplitude = 1.0f;           // scales the horizontal motion
  float yaw_amplitude = 0.6f;       // rad
  bool tilt = false;
  bool draw_biases = true;          // else use the two below
  Eigen::Vector3f accel_bias = Eigen::Vector3f::Zero();
  float gyro_bias = 0;
  uint32_t seed = 1;
};

struct SyntheticFlight {
  std::vector<ImuSample> imu;
  std::vector<FlightStatus> attitude;
  std::vector<PoseMeasurement2> poses;
  std::vector<AltimeterSample> altitude;
  std::vector<estimation::TruthSample> truth;
  std::vector<float> heading;  // true heading at each truth sample
  Eigen::Vector3f accel_bias = Eigen::Vector3f::Zero();  // body frame
  float gyro_bias = 0;

  estimation::RecordedRun run(Duration latency = {}) const {
    return {imu, attitude, poses, altitude, truth, latency};
  }
};

// Filter parameters that match the generator's noise exactly.
inline estimation::EkfParams matched_params(const SyntheticConfig& c) {
  estimation::EkfParams p;
  const float T = 1.0f / static_cast<float>(c.imu_hz);
  p.accel_noise_xy = c.accel_sigma * c.accel_sigma * T;
  p.accel_noise_z = c.accel_sigma * c.accel_sigma * T;
  p.accel_bias_walk = 1e-12f;
  p.gyro_noise = c.gyro_sigma * c.gyro_sigma * T;
  p.gyro_bias_walk = 1e-14f;
  p.position_walk = 0.0f;
  p.init_pos_var = c.pose_sigma * c.pose_sigma;
  p.init_vel_var = 1.0f;
  p.init_accel_bias_var = c.accel_bias_sigma * c.accel_bias_sigma;
  p.init_heading_var = c.heading_sigma * c.heading_sigma;
  p.init_gyro_bias_var = c.gyro_bias_sigma * c.gyro_bias_sigma;
  p.altimeter_var = c.alt_sigma * c.alt_sigma;
  return p;
}

struct TruthAt {
  Eigen::Vector3d p, v, a;
  double psi, psi_dot;
};

inline TruthAt truth_at(const SyntheticConfig& c, double t) {
  const double A = c.amplitude;
  TruthAt s;
  const double wx = 0.5, wy = 0.7, wz = 0.3, wp = 0.2;
  s.p = {0.8 * A * std::sin(wx * t), 0.6 * A * std::sin(wy * t + 1.0), 1.0 + 0.2 * std::sin(wz * t)};
  s.v = {0.8 * A * wx * std::cos(wx * t), 0.6 * A * wy * std::cos(wy * t + 1.0), 0.2 * wz * std::cos(wz * t)};
  s.a = {-0.8 * A * wx * wx * std::sin(wx * t), -0.6 * A * wy * wy * std::sin(wy * t + 1.0),
         -0.2 * wz * wz * std::sin(wz * t)};
  s.psi = c.yaw_amplitude * std::sin(wp * t);
  s.psi_dot = c.yaw_amplitude * wp * std::cos(wp * t);
  return s;
}

inline SyntheticFlight make_flight(const SyntheticConfig& c) {
  constexpr double g = 9.80665;
  std::mt19937 rng(c.seed);
  std::normal_distribution<float> n01(0.0f, 1.0f);
  SyntheticFlight f;
  f.accel_bias = Eigen::Vector3f(n01(rng), n01(rng), n01(rng)) * c.accel_bias_sigma;
  f.gyro_bias = n01(rng) * c.gyro_bias_sigma;
  if (!c.draw_biases) {
    f.accel_bias = c.accel_bias;
    f.gyro_bias = c.gyro_bias;
  }
  const int64_t imu_period = 1000000 / c.imu_hz;
  const int64_t pose_period = 1000000 / c.pose_hz;
  const int64_t end = static_cast<int64_t>(c.duration_s * 1e6);
  int64_t next_pose = c.pose_offset_us;
  for (int64_t t = 0; t <= end; t += imu_period) {
    const TruthAt s = truth_at(c, static_cast<double>(t) * 1e-6);
    // Specific force in the heading frame.
    const Eigen::Vector3d aw = s.a + Eigen::Vector3d(0, 0, g);
    const double cpsi = std::cos(s.psi), spsi = std::sin(s.psi);
    const Eigen::Vector3d h(cpsi * aw.x() + spsi * aw.y(), -spsi * aw.x() + cpsi * aw.y(), aw.z());
    Eigen::Vector3d fb = h;
    FlightStatus st;
    st.stamp = TimeUs::from_us(t);
    if (c.tilt) {
      // Thrust along body z: R = Ry(pitch) Rx(roll) maps (0, 0, T) onto h (right-handed
      // roll: the left side up tilts the thrust towards -y).
      const double T = h.norm();
      const double roll = -std::asin(h.y() / T);
      const double pitch = std::atan2(h.x(), h.z());
      st.roll_rad = static_cast<float>(roll);
      st.pitch_rad = static_cast<float>(pitch);
      fb = Eigen::Vector3d(0, 0, T);
    }
    f.attitude.push_back(st);
    ImuSample imu;
    imu.stamp = TimeUs::from_us(t);
    imu.accel_mps2 = fb.cast<float>() + f.accel_bias +
                     Eigen::Vector3f(n01(rng), n01(rng), n01(rng)) * c.accel_sigma;
    imu.gyro_radps = Eigen::Vector3f(0.0f, 0.0f, static_cast<float>(s.psi_dot) + f.gyro_bias + n01(rng) * c.gyro_sigma);
    f.imu.push_back(imu);
    f.truth.push_back({TimeUs::from_us(t), s.p.cast<float>(), s.v.cast<float>()});
    f.heading.push_back(static_cast<float>(s.psi));
    while (next_pose <= t + imu_period && next_pose <= end) {
      if (next_pose > t) {
        const TruthAt m = truth_at(c, static_cast<double>(next_pose) * 1e-6);
        PoseMeasurement2 pm;
        pm.stamp = TimeUs::from_us(next_pose);
        pm.pose = Pose2{static_cast<float>(m.p.x()) + n01(rng) * c.pose_sigma,
                        static_cast<float>(m.p.y()) + n01(rng) * c.pose_sigma,
                        wrap_angle(static_cast<float>(m.psi) + n01(rng) * c.heading_sigma)};
        pm.covariance = Eigen::Vector3f(c.pose_sigma * c.pose_sigma, c.pose_sigma * c.pose_sigma,
                                        c.heading_sigma * c.heading_sigma).asDiagonal();
        f.poses.push_back(pm);
        AltimeterSample alt;
        alt.stamp = pm.stamp;
        alt.height_m = static_cast<float>(m.p.z()) + n01(rng) * c.alt_sigma;
        alt.variance_m2 = c.alt_sigma * c.alt_sigma;
        f.altitude.push_back(alt);
      }
      next_pose += pose_period;
    }
  }
  return f;
}

}  // namespace kestrel::test

namespace kestrel::test {

// Delivers a recorded run to a filter in delivery order (attitude, IMU, then measurements on
// ties; measurements `latency` after their stamp), up to a given time.
class StreamPlayer {
 public:
  StreamPlayer(const SyntheticFlight& f, Duration latency) : f_(f), lat_(latency) {}

  void play_until(estimation::NavFilter& filter, TimeUs until) {
    const TimeUs never{INT64_MAX};
    for (;;) {
      const TimeUs t_att = i_att_ < f_.attitude.size() ? f_.attitude[i_att_].stamp : never;
      const TimeUs t_imu = i_imu_ < f_.imu.size() ? f_.imu[i_imu_].stamp : never;
      const TimeUs t_pose = i_pose_ < f_.poses.size() ? f_.poses[i_pose_].stamp + lat_ : never;
      const TimeUs t_alt = i_alt_ < f_.altitude.size() ? f_.altitude[i_alt_].stamp + lat_ : never;
      TimeUs next = t_att;
      int which = 0;
      if (t_imu < next) { next = t_imu; which = 1; }
      if (t_pose < next) { next = t_pose; which = 2; }
      if (t_alt < next) { next = t_alt; which = 3; }
      if (next > until || next == never) return;
      switch (which) {
        case 0: filter.set_attitude(f_.attitude[i_att_++]); break;
        case 1: last_ = filter.predict(f_.imu[i_imu_++]); break;
        case 2:
          last_ = filter.update_pose(f_.poses[i_pose_++]);
          if (!ok(last_)) {
            ++pose_failures;
            last_failure = last_;
            failure_at = f_.poses[i_pose_ - 1].stamp;
          }
          break;
        default: last_ = filter.update_altitude(f_.altitude[i_alt_++]); if (!ok(last_)) ++alt_failures; break;
      }
    }
  }
  // Index of the truth sample at or before t (truth is sampled with the IMU).
  std::size_t truth_index(TimeUs t) const {
    std::size_t i = 0;
    while (i + 1 < f_.truth.size() && f_.truth[i + 1].stamp <= t) ++i;
    return i;
  }

  int pose_failures = 0;
  Status last_failure = Status::kOk;
  TimeUs failure_at;
  int alt_failures = 0;

 private:
  const SyntheticFlight& f_;
  Duration lat_;
  std::size_t i_att_ = 0, i_imu_ = 0, i_pose_ = 0, i_alt_ = 0;
  Status last_ = Status::kOk;
};

}  // namespace kestrel::test
