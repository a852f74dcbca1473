// The controller's parameter file: what design_controller() writes, the firmware loads; bad
// files are clear errors.
#include "kestrel/control/controller_params.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <string>

namespace kestrel::control {
namespace {

TEST(ControllerParams, DesignedParametersRoundTripThroughTheFile) {
  VehicleModel m;
  m.pitch = {9.4f, 0.12f};
  m.thrust = {19.0f, -9.6f};
  const Result<ControllerParams> designed = design_controller(m, LqrWeights{}, 0.025);
  ASSERT_TRUE(designed.ok());
  ControllerParams p = designed.value();
  const std::string path = testing::TempDir() + "controller_params_test.params";
  params::ParamError err;
  ASSERT_EQ(params::save_params_file(path.c_str(), controller_param_fields(p), "kestrel controller", err), Status::kOk)
      << err.message;
  ControllerParams loaded = default_controller_params();
  ASSERT_EQ(load_controller_params(path.c_str(), loaded, err), Status::kOk) << err.message;
  EXPECT_EQ(loaded.model.pitch.k, p.model.pitch.k);
  EXPECT_EQ(loaded.model.thrust.b, p.model.thrust.b);
  EXPECT_EQ(loaded.gain_x_p, p.gain_x_p);
  EXPECT_EQ(loaded.gain_z_d, p.gain_z_d);
  EXPECT_EQ(loaded.gain_yaw, p.gain_yaw);
  std::remove(path.c_str());
}

TEST(ControllerParams, InconsistentOrMalformedFilesAreRefused) {
  const std::string path = testing::TempDir() + "controller_params_bad.params";
  auto write = [&](const char* text) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs(text, f);
    std::fclose(f);
  };
  const ControllerParams before = default_controller_params();
  ControllerParams p = before;
  params::ParamError err;
  write("max_tilt_rad = 2.0  # too much\n");
  EXPECT_EQ(load_controller_params(path.c_str(), p, err), Status::kOutOfRange);
  EXPECT_NE(std::strstr(err.message, "max_tilt_rad"), nullptr);
  EXPECT_EQ(err.line, 1);
  write("gain_x_p = 0.3\nkp_x = 0.3\n");
  EXPECT_EQ(load_controller_params(path.c_str(), p, err), Status::kNotFound);
  EXPECT_EQ(err.line, 2);
  // Each value in range, together inconsistent: hover thrust 0.9 above max_thrust.
  write("k_thrust = 10\nb_thrust = -9\n");
  EXPECT_EQ(load_controller_params(path.c_str(), p, err), Status::kInvalidArgument);
  EXPECT_NE(std::strstr(err.message, "hover thrust"), nullptr);
  EXPECT_EQ(p.gain_x_p, before.gain_x_p);
  EXPECT_EQ(p.model.thrust.k, before.model.thrust.k);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace kestrel::control
