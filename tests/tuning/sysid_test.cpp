// kestrel-sysid's core: from a short open-loop excitation flight of the simulator, the fit of
// equation 1 recovers the simulated vehicle's gains, offsets and attitude lag (non-default
// values, so a fit that returned the defaults fails), and the controller file written from it
// loads back unchanged.
#include <gtest/gtest.h>

#include <filesystem>

#include "kestrel/autonomy/stack_config.hpp"
#include "kestrel/control/controller_params.hpp"
#include "kestrel/params/param_file.hpp"
#include "kestrel/tuning/sysid.hpp"

namespace kestrel::tuning {
namespace {

FlightSpec excitation_flight() {
  FlightSpec spec;
  spec.kind = FlightKind::kManual;
  spec.script_text = sysid_script_text();
  spec.duration_s = 14;
  sim::VehicleParams& v = spec.sim.vehicle;
  v.k_pitch = 8.6;
  v.b_pitch = 0.03;  // offsets integrate over the open-loop flight: small, to stay in the hallway
  v.k_roll = 10.4;
  v.b_roll = -0.01;
  v.k_thrust = 21.0;  // hover still at 0.5, so the script's climb and hover stay in the arena
  v.b_thrust = -10.5;
  v.k_yaw = 0.9;
  v.b_yaw = 0.01;
  v.attitude_tau_s = 0.12;
  return spec;
}

TEST(Sysid, RecoversSimulatedGainsOffsetsAndLag) {
  const FlightSpec spec = excitation_flight();
  FlightLog log;
  ASSERT_EQ(fly_and_record(spec, log), "");
  ASSERT_FALSE(log.collided);
  const SysidResult r = identify_vehicle(log);
  ASSERT_EQ(r.status, Status::kOk);
  EXPECT_GT(r.samples, 1000u);
  const sim::VehicleParams& v = spec.sim.vehicle;
  EXPECT_NEAR(r.model.pitch.k, v.k_pitch, 0.02 * v.k_pitch);
  EXPECT_NEAR(r.model.roll.k, v.k_roll, 0.02 * v.k_roll);
  EXPECT_NEAR(r.model.thrust.k, v.k_thrust, 0.02 * v.k_thrust);
  EXPECT_NEAR(r.model.yaw.k, v.k_yaw, 0.02 * v.k_yaw);
  EXPECT_NEAR(r.model.pitch.b, v.b_pitch, 0.02);
  EXPECT_NEAR(r.model.roll.b, v.b_roll, 0.02);
  EXPECT_NEAR(r.model.thrust.b, v.b_thrust, 0.05);
  EXPECT_NEAR(r.model.yaw.b, v.b_yaw, 0.01);
  EXPECT_NEAR(r.lag_s[0], v.attitude_tau_s, 0.011);
  EXPECT_NEAR(r.lag_s[1], v.attitude_tau_s, 0.011);
  EXPECT_LT(r.lag_s[2], 0.011);  // thrust acts at once in the simulator
  // Without the lag the tilt axes fit much worse: the lag search is what makes k right.
  EXPECT_GT(r.rms_no_lag[0], 5 * r.rms[0]);
}

TEST(Sysid, ControllerFileFromTheFitLoadsBack) {
  FlightLog log;
  ASSERT_EQ(fly_and_record(excitation_flight(), log), "");
  const SysidResult r = identify_vehicle(log);
  ASSERT_EQ(r.status, Status::kOk);
  const Result<control::ControllerParams> d =
      control::design_controller(r.model, control::LqrWeights{}, 0.025, autonomy::vehicle_controller_params());
  ASSERT_TRUE(d.ok());
  control::ControllerParams p = d.value();
  EXPECT_GT(p.gain_x_p, 0.0f);
  EXPECT_GT(p.gain_z_d, 0.0f);
  const std::string path = (std::filesystem::temp_directory_path() / "kestrel_sysid_test_controller.params").string();
  params::ParamError err;
  ASSERT_EQ(params::save_params_file(path.c_str(), control::controller_param_fields(p), "test", err), Status::kOk);
  control::ControllerParams back;
  ASSERT_EQ(control::load_controller_params(path.c_str(), back, err), Status::kOk) << err.message;
  auto a = control::controller_param_fields(p);
  auto b = control::controller_param_fields(back);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(*a[i].value, *b[i].value) << a[i].key;
  std::filesystem::remove(path);
}

TEST(Sysid, RefusesAFlightThatDoesNotExciteTheModel) {
  FlightLog log;
  EXPECT_NE(identify_vehicle(log).status, Status::kOk);  // empty
  FlightSpec spec;
  spec.kind = FlightKind::kManual;
  spec.script_text = "0 0 0 0.5 0\n";  // never leaves the floor
  spec.duration_s = 2;
  ASSERT_EQ(fly_and_record(spec, log), "");
  EXPECT_NE(identify_vehicle(log).status, Status::kOk);
}

// Regression: empty script text meant the default tour, so kestrel-sysid --script /dev/null (or a
// comment-only file) flew that tour silently instead of refusing the file as kestrel-sim does.
TEST(FlightLog, AnEmptyScriptIsRefusedWithItsName) {
  FlightLog log;
  FlightSpec spec;
  spec.kind = FlightKind::kManual;
  spec.duration_s = 2;
  spec.script_name = "s.txt";
  EXPECT_EQ(fly_and_record(spec, log), "s.txt: the script has no commands");
  spec.script_text = "# only a comment\n";
  EXPECT_EQ(fly_and_record(spec, log), "s.txt: the script has no commands");
}

}  // namespace
}  // namespace kestrel::tuning
