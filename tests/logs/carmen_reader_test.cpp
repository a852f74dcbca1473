#include "kestrel/logs/carmen_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "kestrel/core/alloc_guard.hpp"
#include "log_test_files.hpp"
#include "text_mutation.hpp"

namespace kestrel::logs {
namespace {

using test::TempLogFile;

// A FLASER line with ranges r_i = 1 + 0.001 * i metres, except the ones overridden.
std::string flaser(int n, double t, double x = 1.5, double y = -2.25, double theta = 0.5) {
  std::string s = "FLASER " + std::to_string(n);
  char buf[64];
  for (int i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, " %.3f", 1.0 + 0.001 * i);
    s += buf;
  }
  std::snprintf(buf, sizeof buf, " %g %g %g", x, y, theta);
  s += buf;
  s += buf;
  std::snprintf(buf, sizeof buf, " %.6f hostname %.6f\n", t, t + 0.001);
  s += buf;
  return s;
}

Status read_all(CarmenReader& r, int& records) {
  LogRecord rec;
  records = 0;
  Status s;
  while (ok(s = r.next(rec))) ++records;
  return s;
}

TEST(CarmenReader, ReadsFlaserWithCarmenGeometryAndPose) {
  TempLogFile file("flaser.log");
  std::string text = "# comment\n\nPARAM robot_front_laser_max 81.9 host 0.1\nODOM 1 2 3 0 0 0 0.5 host 0.5\n";
  text += flaser(181, 12.345678);
  file.write(text);

  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  LogRecord rec;
  ASSERT_EQ(reader.next(rec), Status::kOk) << reader.error().reason;
  EXPECT_EQ(rec.kind, LogRecord::Kind::kLaser);
  EXPECT_EQ(rec.line, 5u);
  EXPECT_EQ(rec.scan.beam_count, 181);
  EXPECT_EQ(rec.scan.range_mm[0], 1000);
  EXPECT_EQ(rec.scan.range_mm[180], 1180);
  EXPECT_FLOAT_EQ(rec.scan.first_angle_rad, static_cast<float>(-M_PI / 2));
  EXPECT_FLOAT_EQ(rec.scan.angle_step_rad, static_cast<float>(M_PI / 180));
  EXPECT_NEAR(rec.scan.angle_of(180), M_PI / 2, 1e-5);
  EXPECT_EQ(rec.scan.stamp.us, 12'345'678);
  EXPECT_DOUBLE_EQ(rec.timestamp_s, 12.345678);
  ASSERT_TRUE(rec.has_pose);
  EXPECT_DOUBLE_EQ(rec.pose.x, 1.5);
  EXPECT_DOUBLE_EQ(rec.pose.y, -2.25);
  EXPECT_DOUBLE_EQ(rec.pose.theta, 0.5);
  EXPECT_DOUBLE_EQ(rec.odom_pose.y, -2.25);
  EXPECT_EQ(reader.next(rec), Status::kNoData);
  EXPECT_EQ(reader.next(rec), Status::kNoData);
  EXPECT_EQ(reader.stats().laser_records, 1u);
  EXPECT_EQ(reader.stats().skipped_lines, 4u);
  EXPECT_EQ(reader.stats().lines, 5u);
}

TEST(CarmenReader, BeamStepFollowsCarmenForEachBeamCount) {
  struct Case {
    int n;
    double step_deg;
    double first_deg;
  };
  for (const Case c : {Case{180, 1.0, -90}, Case{181, 1.0, -90}, Case{360, 0.5, -90}, Case{361, 0.5, -90},
                       Case{401, 0.25, -50}, Case{91, 2.0, -90}}) {
    TempLogFile file("geometry.log");
    file.write(flaser(c.n, 1.0));
    CarmenReader reader;
    ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
    LogRecord rec;
    ASSERT_EQ(reader.next(rec), Status::kOk) << c.n << ": " << reader.error().reason;
    EXPECT_EQ(rec.scan.beam_count, c.n);
    EXPECT_NEAR(rec.scan.angle_step_rad, c.step_deg * M_PI / 180, 1e-7) << c.n;
    EXPECT_NEAR(rec.scan.first_angle_rad, c.first_deg * M_PI / 180, 1e-7) << c.n;
  }
}

TEST(CarmenReader, MaxRangeAndZeroReadingsAreNoReturnAndSmallCodesKept) {
  TempLogFile file("codes.log.gz");
  file.write_gz("FLASER 5 0 81.91 80.0 0.002 79.999 0 0 0 0 0 0 3.0 h 3.0\n");
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  LogRecord rec;
  ASSERT_EQ(reader.next(rec), Status::kOk) << reader.error().reason;
  EXPECT_EQ(rec.scan.range_mm[0], range_code::kNoReturn);
  EXPECT_EQ(rec.scan.range_mm[1], range_code::kNoReturn);
  EXPECT_EQ(rec.scan.range_mm[2], range_code::kNoReturn);
  EXPECT_EQ(rec.scan.range_mm[3], range_code::kDropout);
  // 79.999 m is below FLASER's maximum but beyond what uint16 millimetres hold.
  EXPECT_EQ(rec.scan.range_mm[4], range_code::kNoReturn);
  EXPECT_EQ(rec.scan.max_range_mm, 65535);
}

TEST(CarmenReader, ReadsRobotLaser1WithRemissionsAndImu) {
  TempLogFile file("robotlaser.log");
  file.write(
      "ROBOTLASER1 0 -2.35619449 4.71238898 0.00436332 30.0 0.01 0 4 1.234 30.0 0.001 29.999 "
      "2 0.5 0.6 1.0 2.0 0.25 0.9 1.9 0.2 0.3 0.1 0.5 0.5 0 100.000250 kestrel 100.000250\n"
      "IMU 0.1 -0.2 9.81 1 0 0 0 0 0 0 0.01 0.02 -0.03 100.005 kestrel 100.005\n");
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  LogRecord rec;
  ASSERT_EQ(reader.next(rec), Status::kOk) << reader.error().reason;
  EXPECT_EQ(rec.kind, LogRecord::Kind::kLaser);
  EXPECT_EQ(rec.scan.beam_count, 4);
  EXPECT_EQ(rec.scan.range_mm[0], 1234);
  EXPECT_EQ(rec.scan.range_mm[1], range_code::kNoReturn);
  EXPECT_EQ(rec.scan.range_mm[2], range_code::kTooNear);
  EXPECT_EQ(rec.scan.range_mm[3], 29999);
  EXPECT_EQ(rec.scan.max_range_mm, 30000);
  EXPECT_FLOAT_EQ(rec.scan.first_angle_rad, -2.35619449f);
  EXPECT_FLOAT_EQ(rec.scan.angle_step_rad, 0.00436332f);
  EXPECT_EQ(rec.scan.stamp.us, 100'000'250);
  EXPECT_DOUBLE_EQ(rec.pose.x, 1.0);
  EXPECT_DOUBLE_EQ(rec.pose.theta, 0.25);
  EXPECT_DOUBLE_EQ(rec.odom_pose.x, 0.9);
  ASSERT_EQ(reader.next(rec), Status::kOk) << reader.error().reason;
  EXPECT_EQ(rec.kind, LogRecord::Kind::kImu);
  EXPECT_FALSE(rec.has_pose);
  EXPECT_EQ(rec.line, 2u);
  EXPECT_EQ(rec.imu.stamp.us, 100'005'000);
  EXPECT_FLOAT_EQ(rec.imu.accel_mps2.z(), 9.81f);
  EXPECT_FLOAT_EQ(rec.imu.gyro_radps.x(), 0.01f);
  EXPECT_FLOAT_EQ(rec.imu.gyro_radps.z(), -0.03f);
  EXPECT_EQ(reader.next(rec), Status::kNoData);
}

TEST(CarmenReader, KestrelTimingParamsReachTheScans) {
  TempLogFile file("params.log");
  file.write("PARAM kestrel_laser_scan_period_us 25000 kestrel 0\nPARAM kestrel_laser_beam_interval_us 17 kestrel 0\n"
             "PARAM kestrel_imu_period_us 5000 kestrel 0\n" + flaser(10, 2.0));
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  LogRecord rec;
  ASSERT_EQ(reader.next(rec), Status::kOk) << reader.error().reason;
  EXPECT_EQ(rec.scan.scan_period.us, 25000);
  EXPECT_EQ(rec.scan.beam_interval.us, 17);
  EXPECT_EQ(reader.imu_period().us, 5000);
}

struct BadCase {
  const char* name;
  std::string text;
  Status status;
  uint32_t line;
};

TEST(CarmenReader, BadLinesGiveStatusAndLineNumber) {
  const std::string good = flaser(3, 1.0);
  const BadCase cases[] = {
      {"too few ranges", good + "FLASER 4 1 2 3 0 0 0 0 0 0 2.0 h 2.0\n", Status::kMalformed, 2},
      {"too many fields", good + good + "FLASER 2 1 2 0 0 0 0 0 0 3.0 h 3.0 7\n", Status::kMalformed, 3},
      {"bad number", "FLASER 3 1 2x 3 0 0 0 0 0 0 2.0 h 2.0\n", Status::kMalformed, 1},
      {"bad count", "FLASER three 1 2 3 0 0 0 0 0 0 2.0 h 2.0\n", Status::kMalformed, 1},
      {"negative count", "FLASER -3 1 2 3 0 0 0 0 0 0 2.0 h 2.0\n", Status::kMalformed, 1},
      {"zero count", "FLASER 0 0 0 0 0 0 0 2.0 h 2.0\n", Status::kMalformed, 1},
      {"nan range", good + "FLASER 3 1 nan 3 0 0 0 0 0 0 2.0 h 2.0\n", Status::kNotFinite, 2},
      {"two signs", "FLASER 3 1 2 3 +-1.5 0 0 0 0 0 2.0 h 2.0\n", Status::kMalformed, 1},
      {"two signs count", "FLASER +-3 1 2 3 0 0 0 0 0 0 2.0 h 2.0\n", Status::kMalformed, 1},
      {"inf pose", "FLASER 3 1 2 3 inf 0 0 0 0 0 2.0 h 2.0\n", Status::kNotFinite, 1},
      {"nan time", "FLASER 3 1 2 3 0 0 0 0 0 0 NaN h 2.0\n", Status::kNotFinite, 1},
      {"negative range", "FLASER 3 1 -2 3 0 0 0 0 0 0 2.0 h 2.0\n", Status::kMalformed, 1},
      {"too many beams", "FLASER 1082 1 2 3\n", Status::kCapacityExceeded, 1},
      {"huge count", "FLASER 99999999999999999999 1\n", Status::kMalformed, 1},
      {"backwards time", good + flaser(3, 0.5), Status::kTimeJump, 2},
      {"garbage line", good + "\x01\x02garbage\n", Status::kMalformed, 2},
      {"lower-case word", "hello world\n", Status::kMalformed, 1},
      {"truncated last line", good + "FLASER 3 1 2 3 0 0 0 0 0 0 2.0 h 2", Status::kMalformed, 2},
      {"imu short", "IMU 0 0 9.8 1 0 0 0 0 0 0 0 0 0 1.0 h\n", Status::kMalformed, 1},
      {"imu nan", "IMU 0 0 nan 1 0 0 0 0 0 0 0 0 0 1.0 h 1.0\n", Status::kNotFinite, 1},
      {"robotlaser remission count", "ROBOTLASER1 0 -1 2 0.5 30 0.01 0 2 1 2 3 0.1 0 0 0 0 0 0 0 0 0 0 0 1.0 h 1.0\n",
       Status::kMalformed, 1},
      {"robotlaser huge remission count",
       "ROBOTLASER1 0 -1 2 0.5 30 0.01 0 2 1 2 9223372036854775807 0 0 0 0 0 0 0 0 0 0 0 1.0 h 1.0\n",
       Status::kMalformed, 1},
      {"robotlaser max range", "ROBOTLASER1 0 -1 2 0.5 0 0.01 0 2 1 2 0 0 0 0 0 0 0 0 0 0 0 0 1.0 h 1.0\n",
       Status::kMalformed, 1},
      // Finite as doubles, but not as the floats the records carry: inf, or a step of zero.
      {"imu accel beyond float", "IMU 0 0 1e40 1 0 0 0 0 0 0 0 0 0 1.0 h 1.0\n", Status::kNotFinite, 1},
      {"imu gyro beyond float", "IMU 0 0 9.8 1 0 0 0 0 0 0 0 -4e38 0 1.0 h 1.0\n", Status::kNotFinite, 1},
      {"robotlaser start beyond float", "ROBOTLASER1 0 1e40 2 0.5 30 0.01 0 2 1 2 0 0 0 0 0 0 0 0 0 0 0 0 1.0 h 1.0\n",
       Status::kNotFinite, 1},
      {"robotlaser step beyond float", "ROBOTLASER1 0 -1 2 1e39 30 0.01 0 2 1 2 0 0 0 0 0 0 0 0 0 0 0 0 1.0 h 1.0\n",
       Status::kNotFinite, 1},
      {"robotlaser step zero as float", "ROBOTLASER1 0 -1 2 1e-300 30 0.01 0 2 1 2 0 0 0 0 0 0 0 0 0 0 0 0 1.0 h 1.0\n",
       Status::kMalformed, 1},
      {"param value", "PARAM kestrel_imu_period_us fast h 0\n", Status::kMalformed, 1},
      {"param range", "PARAM kestrel_imu_period_us -5 h 0\n", Status::kOutOfRange, 1},
  };
  for (const BadCase& c : cases) {
    TempLogFile file("bad.log");
    file.write(c.text);
    CarmenReader reader;
    ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
    int records = 0;
    const Status s = read_all(reader, records);
    EXPECT_EQ(s, c.status) << c.name << ": " << reader.error().reason;
    EXPECT_EQ(reader.error().status, c.status) << c.name;
    EXPECT_EQ(reader.error().line, c.line) << c.name << ": " << reader.error().reason;
    EXPECT_GT(std::string(reader.error().reason).size(), 0u) << c.name;
    // Sticky: the reader does not resume after a bad line.
    LogRecord rec;
    EXPECT_EQ(reader.next(rec), c.status) << c.name;
  }
}

TEST(CarmenReader, EmptyFileIsAnEmptyLog) {
  TempLogFile file("empty.log");
  file.write("");
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  int records = 0;
  EXPECT_EQ(read_all(reader, records), Status::kNoData);
  EXPECT_EQ(records, 0);
}

TEST(CarmenReader, TimeOrderPolicies) {
  TempLogFile file("order.log");
  file.write(flaser(3, 1.0) + flaser(3, 2.0) + flaser(3, 1.5) + flaser(3, 3.0) +
             "IMU 0 0 9.8 1 0 0 0 0 0 0 0 0 0 0.2 h 0.2\n");
  {
    CarmenReaderOptions opt;
    opt.time_order = TimeOrder::kAccept;
    CarmenReader reader(opt);
    ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
    int records = 0;
    // The IMU stream is checked on its own: an IMU stamp older than the last scan is fine.
    EXPECT_EQ(read_all(reader, records), Status::kNoData) << reader.error().reason;
    EXPECT_EQ(records, 5);
    EXPECT_EQ(reader.stats().backward_stamps, 1u);
  }
  {
    CarmenReaderOptions opt;
    opt.time_order = TimeOrder::kDrop;
    CarmenReader reader(opt);
    ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
    LogRecord rec;
    std::vector<int64_t> stamps;
    while (ok(reader.next(rec))) stamps.push_back(rec.kind == LogRecord::Kind::kLaser ? rec.scan.stamp.us : -1);
    EXPECT_EQ(stamps, (std::vector<int64_t>{1'000'000, 2'000'000, 3'000'000, -1}));
    EXPECT_EQ(reader.stats().backward_stamps, 1u);
  }
}

TEST(CarmenReader, LineLongerThanTheBufferIsAnError) {
  TempLogFile file("long.log");
  std::string text = flaser(3, 1.0) + "ODOM";
  while (text.size() < LineReader::kMaxLineBytes + 100) text += " 0.000000";
  text += "\n";
  file.write(text);
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  int records = 0;
  EXPECT_EQ(read_all(reader, records), Status::kCapacityExceeded);
  EXPECT_EQ(records, 1);
  EXPECT_EQ(reader.error().line, 2u);
}

TEST(CarmenReader, TruncatedGzipIsAnError) {
  TempLogFile full("full.log.gz");
  std::string text;
  for (int i = 0; i < 200; ++i) text += flaser(181, 1.0 + i);
  full.write_gz(text);
  const std::string bytes = full.read();
  TempLogFile cut("cut.log.gz");
  cut.write(bytes.substr(0, bytes.size() / 2));
  CarmenReader reader;
  ASSERT_EQ(reader.open(cut.c_str()), Status::kOk);
  int records = 0;
  EXPECT_EQ(read_all(reader, records), Status::kMalformed);
  EXPECT_LT(records, 200);
  EXPECT_GT(reader.error().line, 0u);
  EXPECT_STRNE(reader.error().reason, "");
}

TEST(CarmenReader, BinaryGarbageIsAnErrorNotAnEmptyLog) {
  TempLogFile file("garbage.bin");
  std::string bytes;
  uint32_t x = 12345;
  for (int i = 0; i < 5000; ++i) {
    x = x * 1103515245u + 12345u;
    bytes.push_back(static_cast<char>(x >> 24));
  }
  file.write(bytes);
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  int records = 0;
  const Status s = read_all(reader, records);
  EXPECT_NE(s, Status::kNoData);
  EXPECT_NE(s, Status::kOk);
  EXPECT_EQ(records, 0);
}

TEST(CarmenReader, MissingFileAndCrLf) {
  CarmenReader reader;
  EXPECT_EQ(reader.open("/nonexistent/dir/x.log"), Status::kIoError);
  EXPECT_EQ(reader.error().status, Status::kIoError);
  LogRecord rec;
  EXPECT_NE(reader.next(rec), Status::kOk);

  TempLogFile file("crlf.log");
  std::string line = flaser(3, 1.0);
  line.pop_back();
  line += "\r\n";
  file.write(line);
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  ASSERT_EQ(reader.next(rec), Status::kOk) << reader.error().reason;
  EXPECT_EQ(rec.scan.range_mm[2], 1002);
}

// Mutated logs (bytes replaced, deleted, inserted): the reader always ends with kNoData or an
// error, never crashes (run under host-asan too), and never hands out a scan past kMaxBeams.
TEST(CarmenReader, RandomlyMutatedLogsNeverCrash) {
  const std::string base =
      flaser(181, 1.0) + "ODOM 0 0 0 0 0 0 1.1 h 1.1\n" +
      "ROBOTLASER1 0 -2.35 4.71 0.00436 30.0 0.01 0 3 1.234 30.0 0.001 1 0.5 1.0 2.0 0.25 0.9 1.9 0.2 0.3 "
      "0.1 0.5 0.5 0 2.0 kestrel 2.0\n" +
      "IMU 0.1 -0.2 9.81 1 0 0 0 0 0 0 0.01 0.02 -0.03 2.5 kestrel 2.5\n" + flaser(361, 3.0);
  std::mt19937 rng(7);
  const char alphabet[] = "0123456789 .-+eEnaifFLASERIMU\n\t#x\r";
  TempLogFile file("mutated.log");
  int errors = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const std::string text = test::mutate_text(base, alphabet, rng);
    file.write(text);
    CarmenReader reader;
    ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
    LogRecord rec;
    Status s;
    int records = 0;
    while (ok(s = reader.next(rec)) && records < 100) {
      ++records;
      if (rec.kind == LogRecord::Kind::kLaser) {
        ASSERT_LE(rec.scan.beam_count, kMaxBeams);
      }
    }
    ASSERT_LT(records, 100);
    if (s != Status::kNoData) {
      ++errors;
      EXPECT_GT(reader.error().line, 0u);
    }
  }
  // Most mutations must be caught; the rest changed a number into another valid number.
  EXPECT_GT(errors, 100);
}

TEST(CarmenReader, NextDoesNotAllocate) {
  TempLogFile file("alloc.log.gz");
  std::string text;
  for (int i = 0; i < 50; ++i) text += flaser(361, 1.0 + i) + "ODOM 0 0 0 0 0 0 1 h 1\n";
  file.write_gz(text);
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  LogRecord rec;
  int records = 0;
  {
    alloc_guard::Scope guard;
    while (ok(reader.next(rec))) ++records;
    EXPECT_EQ(guard.allocations(), 0u);
  }
  EXPECT_EQ(records, 50);
}

}  // namespace
}  // namespace kestrel::logs
