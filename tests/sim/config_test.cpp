#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include "kestrel/sim/sim_config.hpp"
#include "text_mutation.hpp"

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
  ConfigFile tops;
  ASSERT_EQ(tops.parse("sim.laser_sees_tops_from_above = 2\n", "c.cfg"), "");
  SimConfig cfg4;
  EXPECT_EQ(cfg4.apply(tops), "sim.laser_sees_tops_from_above must be 0 or 1");
  SimConfig cfg5;
  EXPECT_EQ(cfg5.laser_faces_over_start(), FacesOverStart::kMet);  // the default: the world as it is
  ConfigFile missed;
  ASSERT_EQ(missed.load(KESTREL_SOURCE_DIR "/host_sim/sim/configs/tops_missed.cfg"), "");
  EXPECT_EQ(cfg5.apply(missed), "");
  EXPECT_EQ(cfg5.laser_faces_over_start(), FacesOverStart::kMissed);
  EXPECT_EQ(ConfigFile().load("/nonexistent.cfg"), "cannot open '/nonexistent.cfg'");
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
  EXPECT_EQ(f.entries().size(),
            VehicleParams::kBindingCount + LaserParams::kBindingCount + ImuParams::kBindingCount + 6);  // 6 sim.*
  EXPECT_DOUBLE_EQ(cfg.vehicle.k_thrust, defaults.vehicle.k_thrust);
  EXPECT_DOUBLE_EQ(cfg.vehicle.attitude_tau_s, defaults.vehicle.attitude_tau_s);
  EXPECT_DOUBLE_EQ(cfg.laser.first_angle_rad, defaults.laser.first_angle_rad);
  EXPECT_DOUBLE_EQ(cfg.laser.deflected_beams, defaults.laser.deflected_beams);
  EXPECT_DOUBLE_EQ(cfg.imu.accel_bias_std, defaults.imu.accel_bias_std);
  EXPECT_DOUBLE_EQ(cfg.command_delay_s, defaults.command_delay_s);
  EXPECT_EQ(cfg.laser_sees_tops_from_above, defaults.laser_sees_tops_from_above);
  EXPECT_EQ(cfg.laser_sees_wall_thickness, defaults.laser_sees_wall_thickness);
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

// What the simulator does with an accepted configuration stays inside the types it converts to:
// the laser's period and beam interval become int64 microseconds, its angles floats.
void expect_convertible(const SimConfig& c, const std::string& text) {
  const double max_us = 9.0e18;
  EXPECT_LT(c.laser.scan_period_s * 1e6, max_us) << text;
  EXPECT_LT(c.laser.beam_interval_us, max_us) << text;
  EXPECT_LT(std::fabs(c.laser.first_angle_rad), FLT_MAX) << text;
  EXPECT_LT(std::fabs(c.laser.angle_step_rad), FLT_MAX) << text;
  const hal::LaserGeometry g = c.laser.geometry();
  EXPECT_EQ(g.beam_count, c.laser.beam_count) << text;
  EXPECT_LT(g.min_range_mm, g.max_range_mm) << text;
}

// Regression: the laser's scan period had only a lower bound and its angles none, so a typo such
// as 1e300 passed validation and then overflowed the int64 microseconds (scan period) or the
// float (angles) the simulator converts them to.
TEST(ConfigFile, LaserValuesBeyondTheirTypesAreRefused) {
  const struct {
    const char* text;
    const char* error;
  } cases[] = {
      {"laser.scan_period_s = 1e300\n", "laser.scan_period_s must be at most 10"},
      {"laser.scan_period_s = 11\n", "laser.scan_period_s must be at most 10"},
      {"laser.first_angle_rad = 1e300\n", "laser angles must lie within [-2 pi, 2 pi]"},
      {"laser.angle_step_rad = -1e39\n", "laser angles must lie within [-2 pi, 2 pi]"},
      // A fan every module would refuse: no step, or more than one turn.
      {"laser.angle_step_rad = 0\n",
       "laser.angle_step_rad must be at least 1e-4 rad either way, and beam_count steps at most one turn"},
      {"laser.angle_step_rad = 0.01\n",
       "laser.angle_step_rad must be at least 1e-4 rad either way, and beam_count steps at most one turn"},
  };
  for (const auto& c : cases) {
    ConfigFile f;
    ASSERT_EQ(f.parse(c.text, "c.cfg"), "");
    SimConfig cfg;
    EXPECT_EQ(cfg.apply(f), c.error) << c.text;
  }
  ConfigFile slow;
  ASSERT_EQ(slow.parse("laser.scan_period_s = 10\nlaser.first_angle_rad = -6.28\n", "c.cfg"), "");
  SimConfig cfg;
  EXPECT_EQ(cfg.apply(slow), "");
  expect_convertible(cfg, "slow");
}

// Regression: these keys had no upper bound (or none at all), so 1e200 and the like were taken and
// the flight's physics went NaN or absurd (a 1e10 m body collides at once).
TEST(ConfigFile, PhysicalValuesBeyondSaneBoundsAreRefused) {
  const struct {
    const char* text;
    const char* error;
  } cases[] = {
      {"vehicle.b_thrust = 1e200\n", "vehicle.b_thrust must be in [-50, 50] m/s^2"},
      {"vehicle.gust_std_mps2 = 1e200\n", "vehicle.gust_std_mps2 must be in [0, 20] m/s^2"},
      {"vehicle.gust_std_mps2 = 1e10\n", "vehicle.gust_std_mps2 must be in [0, 20] m/s^2"},
      {"vehicle.body_radius_m = 1e10\n", "vehicle.body_radius_m must be in (0, 5] m"},
      {"vehicle.k_thrust = 0\n", "vehicle.k_thrust must be in (0, 200] m/s^2"},
      {"vehicle.k_pitch = 1e300\n", "vehicle.k_pitch must be in (0, 100] m/s^2 per rad"},
      {"vehicle.max_yaw_rate_radps = 1e9\n", "vehicle.max_yaw_rate_radps must be in (0, 20] rad/s"},
      {"imu.gravity_mps2 = -1e300\n", "imu.gravity_mps2 must be in [0, 50] m/s^2"},
      {"laser.mount_z_m = -1e300\n", "laser.mount_x_m, mount_y_m and mount_z_m must each be in [-2, 2] m"},
  };
  for (const auto& c : cases) {
    ConfigFile f;
    ASSERT_EQ(f.parse(c.text, "c.cfg"), "");
    SimConfig cfg;
    EXPECT_EQ(cfg.apply(f), c.error) << c.text;
  }
}

TEST(ConfigFile, RandomlyMutatedConfigsAreRefusedOrApplied) {
  const std::string base =
      "# tuning\n"
      "vehicle.k_thrust = 19.62   # hover at 0.5\n"
      "vehicle.b_thrust = -9.81\n"
      "vehicle.attitude_tau_s = 0.08\n"
      "vehicle.max_tilt_rad = 0.5\n"
      "vehicle.step_s = 0.001\n"
      "laser.beam_count = 1081\n"
      "laser.first_angle_rad = -2.356194490192345\n"
      "laser.angle_step_rad = 0.004363323129985824\n"
      "laser.min_range_m = 0.1\n"
      "laser.max_range_m = 30\n"
      "laser.scan_period_s = 0.025\n"
      "laser.beam_interval_us = 17\n"
      "laser.dropout_probability = 0.002\n"
      "laser.deflected_beams = 20\n"
      "imu.rate_hz = 200\n"
      "imu.accel_noise_density = 0.004\n"
      "sim.command_delay_s = 0.02\n"
      "sim.ray_grid_cell_m = 1.0\n";
  {
    ConfigFile f;
    ASSERT_EQ(f.parse(base, "c.cfg"), "");
    SimConfig cfg;
    ASSERT_EQ(cfg.apply(f), "");
  }
  std::mt19937 rng(19);
  const char alphabet[] = "0123456789 .-+e=#\n\txnaik_";
  // Half the trials edit only values (the keys are most of the text): from the '=' on.
  const test::EditPosition in_a_value = [](const std::string& text, std::size_t drawn, std::mt19937& r) {
    const std::size_t line_start = text.rfind('\n', drawn) == std::string::npos ? 0 : text.rfind('\n', drawn) + 1;
    const std::size_t eq = text.find('=', line_start);
    const std::size_t line_end = std::min(text.find('\n', line_start), text.size());
    return eq < line_end ? eq + 1 + r() % (line_end - eq) : drawn;
  };
  int errors = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::string text = test::mutate_text(base, alphabet, rng, trial % 2 == 1 ? in_a_value : test::anywhere);
    ConfigFile f;
    std::string error = f.parse(text, "c.cfg");
    SimConfig cfg;
    if (error.empty()) error = cfg.apply(f);
    if (!error.empty()) {
      ++errors;
      // "c.cfg:LINE: reason" for a line's fault, else the rule a value breaks, naming its key.
      if (error.rfind("c.cfg:", 0) == 0) {
        const int line = std::atoi(error.c_str() + 6);
        const int lines = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
        EXPECT_GE(line, 1) << error;
        EXPECT_LE(line, lines) << error;
      } else {
        const bool names_component = error.rfind("vehicle", 0) == 0 || error.rfind("laser", 0) == 0 ||
                                     error.rfind("imu", 0) == 0 || error.rfind("sim.", 0) == 0;
        EXPECT_TRUE(names_component) << error;
      }
      continue;
    }
    ASSERT_EQ(cfg.validate(), "") << text;
    expect_convertible(cfg, text);
  }
  // Most mutations must be caught; the rest changed a number into another acceptable number,
  // a comment or the spacing.
  EXPECT_GT(errors, 220);
}

}  // namespace
}  // namespace kestrel::sim
