#include <gtest/gtest.h>

#include "kestrel/sim/sim_config.hpp"

namespace kestrel::sim {
namespace {

TEST(ConfigFile, AppliesKnownKeysToEveryComponent) {
  ConfigFile f;
  ASSERT_EQ(f.parse("# tuning\nvehicle.k_pitch = 8.5\nimu.rate_hz=100  # slower\n\nlaser.dropout_probability = 0\n"
                    "sim.command_delay_s = 0.2\n",
                    "c.cfg"),
            "");
  SimConfig cfg;
  EXPECT_EQ(cfg.apply(f), "");
  EXPECT_DOUBLE_EQ(cfg.vehicle.k_pitch, 8.5);
  EXPECT_DOUBLE_EQ(cfg.imu.rate_hz, 100);
  EXPECT_DOUBLE_EQ(cfg.laser.dropout_probability, 0);
  EXPECT_DOUBLE_EQ(cfg.command_delay_s, 0.2);
}

TEST(ConfigFile, ErrorsNameTheLine) {
  ConfigFile f;
  EXPECT_EQ(f.parse("a = 1\nb 2\n", "c.cfg"), "c.cfg:2: expected 'key = value'");
  EXPECT_EQ(f.parse("a = x\n", "c.cfg"), "c.cfg:1: value of 'a' is not a finite number: 'x'");
  EXPECT_EQ(f.parse("a = 1\na = 2\n", "c.cfg"), "c.cfg:2: 'a' is already set on line 1");
  EXPECT_EQ(f.parse(" = 2\n", "c.cfg"), "c.cfg:1: missing key before '='");
  ASSERT_EQ(f.parse("vehicle.k_pitch = 1\nvehicle.k_ptich = 2\n", "c.cfg"), "");
  SimConfig cfg;
  EXPECT_EQ(cfg.apply(f), "c.cfg:2: unknown key 'vehicle.k_ptich'");
  ConfigFile bad;
  ASSERT_EQ(bad.parse("imu.rate_hz = 5\n", "c.cfg"), "");
  SimConfig cfg2;
  EXPECT_EQ(cfg2.apply(bad), "imu.rate_hz must be in [10, 1000]");
  ConfigFile half;
  ASSERT_EQ(half.parse("sim.laser_sees_wall_thickness = 0.5\n", "c.cfg"), "");
  SimConfig cfg3;
  EXPECT_EQ(cfg3.apply(half), "sim.laser_sees_wall_thickness must be 0 or 1");
  EXPECT_NE(ConfigFile().load("/nonexistent.cfg").find("/nonexistent.cfg"), std::string::npos);
}

}  // namespace
}  // namespace kestrel::sim

namespace kestrel::sim {
namespace {

TEST(ConfigFile, ShippedExampleHoldsEveryDefault) {
  ConfigFile f;
  ASSERT_EQ(f.load(std::string(KESTREL_SOURCE_DIR) + "/host_sim/sim/configs/hummingbird.cfg"), "");
  SimConfig cfg;
  ASSERT_EQ(cfg.apply(f), "");
  const SimConfig defaults;
  EXPECT_EQ(f.entries().size(), VehicleParams::kBindingCount + LaserParams::kBindingCount + ImuParams::kBindingCount + 5);
  EXPECT_DOUBLE_EQ(cfg.vehicle.k_thrust, defaults.vehicle.k_thrust);
  EXPECT_DOUBLE_EQ(cfg.vehicle.attitude_tau_s, defaults.vehicle.attitude_tau_s);
  EXPECT_DOUBLE_EQ(cfg.laser.first_angle_rad, defaults.laser.first_angle_rad);
  EXPECT_DOUBLE_EQ(cfg.laser.deflected_beams, defaults.laser.deflected_beams);
  EXPECT_DOUBLE_EQ(cfg.imu.accel_bias_std, defaults.imu.accel_bias_std);
  EXPECT_DOUBLE_EQ(cfg.command_delay_s, defaults.command_delay_s);
}

// The README's experiments pass these with --config: each must load and change what it says.
TEST(ConfigFile, ShippedExperimentConfigsApply) {
  const std::string dir = std::string(KESTREL_SOURCE_DIR) + "/host_sim/sim/configs/";
  ConfigFile sweep;
  ASSERT_EQ(sweep.load(dir + "instantaneous_sweep.cfg"), "");
  SimConfig a;
  a.laser = LaserParams::urg04lx();
  ASSERT_EQ(a.apply(sweep), "");
  EXPECT_EQ(a.laser.beam_interval_us, 1);
  EXPECT_EQ(a.laser.beam_count, LaserParams::urg04lx().beam_count);  // the rest stays the URG's

  ConfigFile perfect;
  ASSERT_EQ(perfect.load(dir + "perfect_imu.cfg"), "");
  SimConfig b;
  ASSERT_EQ(b.apply(perfect), "");
  EXPECT_EQ(b.imu.accel_noise_density, 0.0);
  EXPECT_EQ(b.imu.accel_bias_std, 0.0);
  EXPECT_EQ(b.imu.accel_bias_walk, 0.0);
  EXPECT_EQ(b.imu.gyro_noise_density, 0.0);
  EXPECT_EQ(b.imu.gyro_bias_std, 0.0);
  EXPECT_EQ(b.imu.gyro_bias_walk, 0.0);
  EXPECT_EQ(b.imu.rate_hz, SimConfig{}.imu.rate_hz);

  ConfigFile thick;
  ASSERT_EQ(thick.load(dir + "thick_walls.cfg"), "");
  SimConfig c;
  EXPECT_EQ(c.laser_walls(), WallSurfaces::kCentreLines);
  ASSERT_EQ(c.apply(thick), "");
  EXPECT_EQ(c.laser_walls(), WallSurfaces::kBoxOutlines);

  ConfigFile heavy;
  ASSERT_EQ(heavy.load(dir + "heavy_vehicle.cfg"), "");
  SimConfig d;
  ASSERT_EQ(d.apply(heavy), "");
  EXPECT_NEAR(d.vehicle.k_thrust * 0.6 + d.vehicle.b_thrust, 0.0, 1e-9);  // hovers at 0.6
  EXPECT_EQ(d.vehicle.attitude_tau_s, 0.12);
  EXPECT_EQ(d.vehicle.k_pitch, SimConfig{}.vehicle.k_pitch);  // tilt still gives g per radian
}

}  // namespace
}  // namespace kestrel::sim
