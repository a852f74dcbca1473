// Parameter files: round trip, and a clear error for every kind of bad line.
#include "kestrel/estimation/ekf_params.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include "text_mutation.hpp"

namespace kestrel::estimation {
namespace {

TEST(EkfParams, WriteThenParseRoundTrips) {
  EkfParams p;
  p.accel_noise_xy = 1.2345678e-4f;
  p.pose_cov_scale = 3.5f;
  p.gyro_bias_walk = 7.5e-11f;
  char buf[params::kMaxParamFileBytes];
  const auto n = params::write_params(ekf_param_fields(p), "test", buf, sizeof(buf));
  ASSERT_TRUE(n.ok());
  EXPECT_NE(std::strstr(buf, "accel_noise_xy = "), nullptr);
  EXPECT_NE(std::strstr(buf, "(m/s^2)^2/Hz"), nullptr);  // units in the comments
  EkfParams q;
  params::ParamError err;
  ASSERT_EQ(params::parse_params(std::string_view(buf, n.value()), ekf_param_fields(q), err), Status::kOk)
      << err.message;
  EXPECT_EQ(q.accel_noise_xy, p.accel_noise_xy);
  EXPECT_EQ(q.pose_cov_scale, p.pose_cov_scale);
  EXPECT_EQ(q.gyro_bias_walk, p.gyro_bias_walk);
  EXPECT_EQ(validate(q), Status::kOk);
  // Too small a buffer is an error, not a truncated file.
  EXPECT_EQ(params::write_params(ekf_param_fields(p), "test", buf, 100).status(), Status::kCapacityExceeded);
}

struct BadCase {
  const char* text;
  Status status;
  int line;
  const char* in_message;
};

TEST(EkfParams, BadLinesAreClearErrorsAndChangeNothing) {
  const BadCase cases[] = {
      {"# ok\naccel_noise_xy = 1e-3\nacel_noise_z = 1e-3\n", Status::kNotFound, 3, "unknown key 'acel_noise_z'"},
      {"pose_cov_scale = 2\npose_cov_scale = 3\n", Status::kMalformed, 2, "duplicate key 'pose_cov_scale'"},
      {"pose_cov_scale 2\n", Status::kMalformed, 1, "expected 'key = value'"},
      {"pose_cov_scale =\n", Status::kMalformed, 1, "has no value"},
      {"pose_cov_scale = two\n", Status::kMalformed, 1, "not a number"},
      {"pose_cov_scale = 2 m\n", Status::kMalformed, 1, "not a number"},
      {"pose_cov_scale = nan\n", Status::kNotFinite, 1, "not finite"},
      {"pose_cov_scale = -1\n", Status::kOutOfRange, 1, "outside"},
      {"\n\ngravity_mps2 = 1.6\n", Status::kOutOfRange, 3, "'gravity_mps2'"},
  };
  for (const BadCase& bc : cases) {
    EkfParams p;
    p.accel_noise_xy = 5e-3f;
    params::ParamError err;
    EXPECT_EQ(params::parse_params(bc.text, ekf_param_fields(p), err), bc.status) << bc.text;
    EXPECT_EQ(err.line, bc.line) << bc.text;
    EXPECT_NE(std::strstr(err.message, bc.in_message), nullptr) << err.message;
    EXPECT_EQ(p.accel_noise_xy, 5e-3f);  // all or nothing
  }
}

TEST(EkfParams, LoadsAFileAndReportsAMissingOne) {
  const std::string path = testing::TempDir() + "ekf_params_test.params";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("# learnt\r\naccel_noise_xy = 2.5e-4   # trailing comment\r\n\r\n  pose_cov_scale=0.5\n", f);
    std::fclose(f);
  }
  EkfParams p;
  params::ParamError err;
  ASSERT_EQ(load_ekf_params(path.c_str(), p, err), Status::kOk) << err.message;
  EXPECT_FLOAT_EQ(p.accel_noise_xy, 2.5e-4f);
  EXPECT_FLOAT_EQ(p.pose_cov_scale, 0.5f);
  EXPECT_FLOAT_EQ(p.accel_noise_z, EkfParams{}.accel_noise_z);  // absent keys keep defaults
  std::remove(path.c_str());
  EXPECT_EQ(load_ekf_params(path.c_str(), p, err), Status::kIoError);
  EXPECT_NE(std::strstr(err.message, "cannot open"), nullptr);
  // Saving and loading through the file functions.
  p.gyro_noise = 3e-6f;
  ASSERT_EQ(params::save_params_file(path.c_str(), ekf_param_fields(p), "saved", err), Status::kOk);
  EkfParams q;
  ASSERT_EQ(load_ekf_params(path.c_str(), q, err), Status::kOk) << err.message;
  EXPECT_EQ(q.gyro_noise, p.gyro_noise);
  std::remove(path.c_str());
}

// The shipped file that turns the height filter's runs off (for comparing with the figures
// flown before they were on) loads, and changes nothing else.
TEST(EkfParams, TheShippedFileWithoutHeightRunsTurnsOnlyThemOff) {
  EkfParams p;
  params::ParamError err;
  ASSERT_EQ(load_ekf_params(KESTREL_SOURCE_DIR "/host_sim/sim/configs/no_height_runs.ekf", p, err), Status::kOk)
      << err.message;
  EXPECT_EQ(p.altitude_relock_s, 0.0f);
  EkfParams expected;
  expected.altitude_relock_s = 0.0f;
  const auto loaded = ekf_param_fields(p);
  const auto defaults = ekf_param_fields(expected);
  for (std::size_t i = 0; i < loaded.size(); ++i) EXPECT_EQ(*loaded[i].value, *defaults[i].value) << loaded[i].key;
}

// Every tool prints a parameter file's error in these words: a line's error with its line, a
// file that will not open once, not "PATH:0: cannot open 'PATH'", and an inconsistent set (no
// line, no path in its message) with the path that says which file.
TEST(EkfParams, ErrorsAreDescribedWithThePathOnce) {
  char buf[256];
  params::ParamError err;
  EkfParams p;
  ASSERT_EQ(load_ekf_params("/nonexistent/ekf.params", p, err), Status::kIoError);
  params::describe("/nonexistent/ekf.params", err, buf, sizeof(buf));
  EXPECT_STREQ(buf, "cannot open '/nonexistent/ekf.params'");
  err.line = 3;
  std::snprintf(err.message, sizeof(err.message), "unknown key 'x'");
  params::describe("a.params", err, buf, sizeof(buf));
  EXPECT_STREQ(buf, "a.params:3: unknown key 'x'");
  err.line = 0;
  params::describe("a.params", err, buf, sizeof(buf));
  EXPECT_STREQ(buf, "a.params: unknown key 'x'");
  EXPECT_EQ(params::describe("a.params", err, buf, 4), 25);  // truncated, as snprintf
  EXPECT_STREQ(buf, "a.p");
  // A path too long for the message, which is cut off inside it: named once all the same.
  const std::string long_path = "/nonexistent/" + std::string(200, 'd') + "/ekf.params";
  ASSERT_EQ(load_ekf_params(long_path.c_str(), p, err), Status::kIoError);
  char wide[512];
  params::describe(long_path.c_str(), err, wide, sizeof(wide));
  EXPECT_EQ(std::string(wide).rfind("cannot open '/nonexistent/ddd", 0), 0u) << wide;
}

// Regression: a directory opens for reading and then fails to read, and that read error was not
// checked, so --ekf /tmp (and every parameter file option) ran on the defaults.
TEST(EkfParams, ADirectoryIsNotAParameterFile) {
  const std::string dir = testing::TempDir();
  EkfParams p;
  p.gyro_noise = 7e-6f;
  params::ParamError err;
  EXPECT_EQ(load_ekf_params(dir.c_str(), p, err), Status::kIoError);
  EXPECT_NE(std::strstr(err.message, "(is a directory)"), nullptr) << err.message;
  EXPECT_EQ(p.gyro_noise, 7e-6f);  // unchanged
}

TEST(EkfParams, RandomlyMutatedFilesAreRefusedWholeOrApplied) {
  // The file as the writer emits it: a comment line of help, unit and range before each key.
  const EkfParams defaults;
  EkfParams written = defaults;
  char buf[params::kMaxParamFileBytes];
  const auto n = params::write_params(ekf_param_fields(written), "learnt", buf, sizeof(buf));
  ASSERT_TRUE(n.ok());
  const std::string base(buf, n.value());
  std::mt19937 rng(23);
  const char alphabet[] = "0123456789 .-+e=#\n\r\txnaif_";
  // Half the trials edit only key lines (comments are most of the text): from the '=' on.
  const test::EditPosition in_a_value = [](const std::string& text, std::size_t drawn, std::mt19937& r) {
    const std::size_t line_start = text.rfind('\n', drawn) == std::string::npos ? 0 : text.rfind('\n', drawn) + 1;
    const std::size_t line_end = std::min(text.find('\n', line_start), text.size());
    const std::size_t eq = text.find(" = ", line_start);
    return text[line_start] != '#' && eq < line_end ? eq + r() % (line_end - eq) : drawn;
  };
  int errors = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::string text = test::mutate_text(base, alphabet, rng, trial % 2 == 1 ? in_a_value : test::anywhere);
    EkfParams p = defaults;
    params::ParamError err;
    const Status s = params::parse_params(text, ekf_param_fields(p), err);
    if (s != Status::kOk) {
      ++errors;
      const int lines = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
      EXPECT_GE(err.line, 1) << err.message;
      EXPECT_LE(err.line, lines) << err.message;
      EXPECT_NE(err.message[0], '\0');
      EkfParams untouched = defaults;
      const auto got = ekf_param_fields(p);
      const auto want = ekf_param_fields(untouched);
      for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(*got[i].value, *want[i].value) << "a refused file changed " << got[i].key << ": " << err.message;
      }
      continue;
    }
    EXPECT_EQ(err.line, 0);
    // Every value it took is finite and inside its field's range.
    for (const params::ParamField& f : ekf_param_fields(p)) {
      EXPECT_TRUE(std::isfinite(*f.value)) << f.key;
      EXPECT_GE(*f.value, f.min) << f.key;
      EXPECT_LE(*f.value, f.max) << f.key;
    }
    EXPECT_EQ(validate(p), Status::kOk);
  }
  // Most mutations must be caught; the rest changed a number into another number in range, a
  // comment or the spacing.
  EXPECT_GT(errors, 105);
}

}  // namespace
}  // namespace kestrel::estimation
