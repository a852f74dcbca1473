// Paper 000 equation 1 against its closed-form solutions.
#include <gtest/gtest.h>

#include <cmath>

#include "kestrel/sim/vehicle.hpp"

namespace kestrel::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

VehicleState hovering(double z = 1.0, double yaw = 0) {
  VehicleState s;
  s.position_m = {0, 0, z};
  s.yaw_rad = yaw;
  s.on_ground = false;
  return s;
}

AttitudeSetpoint cmd(double pitch, double roll, double thrust, double yaw_rate) {
  AttitudeSetpoint u;
  u.pitch_rad = static_cast<float>(pitch);
  u.roll_rad = static_cast<float>(roll);
  u.thrust = static_cast<float>(thrust);
  u.yaw_rate_radps = static_cast<float>(yaw_rate);
  return u;
}

void run(Vehicle& v, const AttitudeSetpoint& u, double seconds) {
  const int64_t n = static_cast<int64_t>(std::llround(seconds / v.step_duration().seconds()));
  for (int64_t i = 0; i < n; ++i) v.step(u, true);
}

TEST(Vehicle, InstantAttitudeMatchesTheParabolasOfEquation1) {
  VehicleParams p;
  p.attitude_tau_s = 0;
  p.b_pitch = 0.05;
  p.b_roll = -0.03;
  Vehicle v(p, hovering(), Rng(1));
  const double up = 0.1, ur = -0.05, ut = 0.55, uy = 0.3, t = 2.0;
  run(v, cmd(up, ur, ut, 0), t);
  const VehicleState& s = v.state();
  const double ax = p.k_pitch * static_cast<float>(up) + p.b_pitch;
  const double ay = p.k_roll * static_cast<float>(ur) + p.b_roll;
  const double az = p.k_thrust * static_cast<float>(ut) + p.b_thrust;
  EXPECT_NEAR(s.position_m.x(), 0.5 * ax * t * t, 1e-9);
  EXPECT_NEAR(s.position_m.y(), 0.5 * ay * t * t, 1e-9);
  EXPECT_NEAR(s.position_m.z(), 1.0 + 0.5 * az * t * t, 1e-9);
  EXPECT_NEAR(s.velocity_mps.x(), ax * t, 1e-9);
  EXPECT_NEAR(s.accel_mps2.z(), az, 1e-9);
  EXPECT_EQ(s.stamp.us, 2000000);
  // Yaw: theta(t) = (k u + b) t.
  p.b_yaw = 0.01;
  Vehicle w(p, hovering(), Rng(1));
  run(w, cmd(0, 0, 0.5, uy), 1.0);
  EXPECT_NEAR(w.state().yaw_rad, (p.k_yaw * static_cast<float>(uy) + p.b_yaw) * 1.0, 1e-9);
  EXPECT_NEAR(w.state().yaw_rate_radps, p.k_yaw * static_cast<float>(uy) + p.b_yaw, 1e-12);
}

TEST(Vehicle, BodyFrameFollowsTheHeading) {
  VehicleParams p;
  p.attitude_tau_s = 0;
  Vehicle v(p, hovering(1.0, kPi / 2), Rng(1));
  run(v, cmd(0.1, 0, 0.5, 0), 1.0);  // nose towards +y: pitching forward moves along +y
  EXPECT_NEAR(v.state().position_m.x(), 0, 1e-9);
  EXPECT_NEAR(v.state().position_m.y(), 0.5 * p.k_pitch * static_cast<float>(0.1), 1e-9);
  Vehicle r(p, hovering(1.0, kPi / 2), Rng(1));
  run(r, cmd(0, 0.1, 0.5, 0), 1.0);  // positive roll accelerates to the left: -x here
  EXPECT_NEAR(r.state().position_m.x(), -0.5 * p.k_roll * static_cast<float>(0.1), 1e-9);
}

TEST(Vehicle, FirstOrderAttitudeLagMatchesItsClosedForm) {
  // x(t) = k u (t²/2 - tau t + tau² (1 - e^(-t/tau))) for a step in pitch at t = 0.
  VehicleParams p;
  p.attitude_tau_s = 0.1;
  Vehicle v(p, hovering(), Rng(1));
  const double u = static_cast<float>(0.1), tau = p.attitude_tau_s;
  for (double t : {0.05, 0.2, 0.5, 1.5}) {
    Vehicle w(p, hovering(), Rng(1));
    run(w, cmd(0.1, 0, 0.5, 0), t);
    const double want = p.k_pitch * u * (t * t / 2 - tau * t + tau * tau * (1 - std::exp(-t / tau)));
    const double vel = p.k_pitch * u * (t - tau * (1 - std::exp(-t / tau)));
    // The discrete lag leads the continuous one by about one step.
    EXPECT_NEAR(w.state().position_m.x(), want, 0.002 * t + 1e-4) << t;
    EXPECT_NEAR(w.state().velocity_mps.x(), vel, 0.002) << t;
    EXPECT_NEAR(w.state().pitch_rad, u * (1 - std::exp(-t / tau)), 0.001) << t;
  }
}

TEST(Vehicle, FloorStopsTheVehicleAndThrustLiftsIt) {
  VehicleParams p;
  VehicleState s;
  s.position_m = {0, 0, 0};
  Vehicle v(p, s, Rng(1));
  run(v, cmd(0.2, 0, 0.4, 1.0), 1.0);  // less than hover thrust: stays on the floor
  EXPECT_EQ(v.state().position_m, Eigen::Vector3d(0, 0, 0));
  EXPECT_TRUE(v.state().on_ground);
  EXPECT_EQ(v.state().yaw_rad, 0);
  run(v, cmd(0, 0, 0.6, 0), 1.0);
  EXPECT_GT(v.state().position_m.z(), 0.9);
  EXPECT_FALSE(v.state().on_ground);
  // Motors off: falls back and lands without bouncing.
  for (int i = 0; i < 2000; ++i) v.step(cmd(0, 0, 0.6, 0), false);
  EXPECT_EQ(v.state().position_m.z(), 0);
  EXPECT_EQ(v.state().velocity_mps.norm(), 0);
}

TEST(Vehicle, CommandsAreClampedAndNonFiniteIgnored) {
  VehicleParams p;
  p.attitude_tau_s = 0;
  Vehicle v(p, hovering(), Rng(1));
  run(v, cmd(5.0, 0, 0.5, 100), 0.1);
  EXPECT_NEAR(v.state().pitch_rad, p.max_tilt_rad, 1e-12);
  EXPECT_NEAR(v.state().yaw_rate_radps, p.max_yaw_rate_radps, 1e-12);
  Vehicle n(p, hovering(), Rng(1));
  run(n, cmd(std::nan(""), INFINITY, 0.5, std::nan("")), 0.5);
  EXPECT_TRUE(n.state().position_m.allFinite());
  EXPECT_NEAR(n.state().position_m.x(), 0, 1e-12);
}

TEST(Vehicle, GustsPushTheVehicleWithTheConfiguredStrength) {
  VehicleParams p;
  p.gust_std_mps2 = 0.5;
  p.gust_tau_s = 0.5;
  Vehicle v(p, hovering(), Rng(9));
  double s2 = 0;
  int n = 0;
  for (int i = 0; i < 200000; ++i) {
    v.step(cmd(0, 0, 0.5, 0), true);
    if (i % 10 == 0) {
      s2 += v.state().accel_mps2.x() * v.state().accel_mps2.x();
      ++n;
    }
  }
  EXPECT_NEAR(std::sqrt(s2 / n), 0.5, 0.08);
  EXPECT_GT(v.state().position_m.head<2>().norm(), 0.1);
}

TEST(Vehicle, BodyRatesAndAttitudeAreConsistent) {
  VehicleParams p;
  Vehicle v(p, hovering(), Rng(1));
  run(v, cmd(0, 0, 0.5, 0.5), 1.0);
  EXPECT_NEAR(v.state().body_rate_radps.z(), 0.5, 1e-6);
  const Eigen::Quaterniond q = v.state().attitude();
  EXPECT_NEAR(2 * std::atan2(q.z(), q.w()), v.state().yaw_rad, 1e-9);
  EXPECT_STREQ(p.validate(), "");
  p.step_s = 0.0;
  EXPECT_STRNE(p.validate(), "");
}

}  // namespace
}  // namespace kestrel::sim
