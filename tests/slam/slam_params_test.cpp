// The compact SLAM's parameter file: keys over the current values, all or nothing.
#include "kestrel/slam/slam_params.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "temp_file.hpp"

namespace kestrel::slam {
namespace {

TEST(SlamParams, AFileLoadsOverTheCurrentValuesOrNotAtAll) {
  params::ParamError err;
  SlamParams p;
  p.iterations = 77;
  const std::string good = test::write_temp_file("slam_params_test_good.slam", "weight = 12\ncell_m = 0.05\n");
  ASSERT_EQ(load_slam_params(good.c_str(), p, err), Status::kOk) << err.message;
  EXPECT_EQ(p.weight, 12.0f);
  EXPECT_EQ(p.cell_m, 0.05f);
  EXPECT_EQ(p.iterations, 77.0f);  // absent from the file: kept
  // Out of range, unknown key, inconsistent pair, missing file: refused, nothing taken.
  const SlamParams before = p;
  for (const char* text : {"cell_m = 2\n", "cells = 0.05\n", "min_points = 900\nmax_points = 100\n"}) {
    const std::string bad = test::write_temp_file("slam_params_test_bad.slam", text);
    EXPECT_NE(load_slam_params(bad.c_str(), p, err), Status::kOk) << text;
    EXPECT_NE(err.message[0], '\0') << text;
    EXPECT_EQ(p.cell_m, before.cell_m);
    EXPECT_EQ(p.min_points, before.min_points);
    std::remove(bad.c_str());
  }
  EXPECT_NE(load_slam_params("/no/such/file.slam", p, err), Status::kOk);
  std::remove(good.c_str());
}

TEST(SlamParams, ValidateChecksEveryRangeAndThePointCounts) {
  EXPECT_EQ(validate(SlamParams{}), Status::kOk);
  SlamParams p;
  p.sigma_xy_m = -1;
  EXPECT_EQ(validate(p), Status::kInvalidArgument);
  p = {};
  p.max_correction_rad = NAN;
  EXPECT_EQ(validate(p), Status::kInvalidArgument);
  p = {};
  p.min_points = p.max_points + 1;
  EXPECT_EQ(validate(p), Status::kInvalidArgument);
}

}  // namespace
}  // namespace kestrel::slam
