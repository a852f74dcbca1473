// Whole real logs from ../shared/data, read end to end; counts and the first and last values
// checked against `zcat FILE | grep ^FLASER | head -1` (and tail -1).
#include <gtest/gtest.h>

#include "kestrel/logs/carmen_reader.hpp"
#include "kestrel/logs/log_replay.hpp"
#include "kestrel/logs/mines_reader.hpp"
#include "kestrel/logs/open_log.hpp"
#include "kestrel_test_paths.hpp"

namespace kestrel::logs {
namespace {

struct Summary {
  int scans = 0;
  int wrong_beam_count = 0;
  LogRecord first;
  LogRecord last;
};

Status read_carmen(const std::string& path, CarmenReader& reader, int beams, Summary& sum) {
  Status s = reader.open(path.c_str());
  if (!ok(s)) return s;
  LogRecord rec;
  while (ok(s = reader.next(rec))) {
    if (rec.kind != LogRecord::Kind::kLaser) continue;
    if (sum.scans == 0) sum.first = rec;
    if (rec.scan.beam_count != beams) ++sum.wrong_beam_count;
    ++sum.scans;
    sum.last = rec;
  }
  return s;
}

TEST(RealData, Freiburg079) {
  CarmenReader reader;
  Summary sum;
  ASSERT_EQ(read_carmen(test::shared_data_path("carmen/freiburg-079.log.gz"), reader, 360, sum), Status::kNoData)
      << "line " << reader.error().line << ": " << reader.error().reason;
  EXPECT_EQ(sum.scans, 4791);
  EXPECT_EQ(sum.wrong_beam_count, 0);
  EXPECT_EQ(reader.stats().backward_stamps, 0u);
  EXPECT_EQ(reader.stats().lines, 19496u);
  // FLASER 360 1.65 1.66 ... 1 0.00123601 -0.00106807 2.85e-05 ... 0.227623 pippo 0.227623
  EXPECT_EQ(sum.first.line, 192u);
  EXPECT_EQ(sum.first.scan.range_mm[0], 1650);
  EXPECT_EQ(sum.first.scan.range_mm[1], 1660);
  EXPECT_EQ(sum.first.scan.range_mm[359], 1000);
  EXPECT_DOUBLE_EQ(sum.first.pose.x, 0.00123601);
  EXPECT_DOUBLE_EQ(sum.first.pose.y, -0.00106807);
  EXPECT_DOUBLE_EQ(sum.first.pose.theta, 2.85e-05);
  EXPECT_EQ(sum.first.scan.stamp.us, 227'623);
  EXPECT_NEAR(sum.first.scan.angle_step_rad, M_PI / 360, 1e-9);
  // FLASER 360 6.5 9.9 ... 4.25 0.0319692 -0.94701 -1.8314 ... 1061.5 pippo 1061.5
  EXPECT_EQ(sum.last.line, 19494u);
  EXPECT_EQ(sum.last.scan.range_mm[0], 6500);
  EXPECT_EQ(sum.last.scan.range_mm[1], 9900);
  EXPECT_EQ(sum.last.scan.range_mm[359], 4250);
  EXPECT_DOUBLE_EQ(sum.last.pose.x, 0.0319692);
  EXPECT_DOUBLE_EQ(sum.last.pose.theta, -1.8314);
  EXPECT_EQ(sum.last.scan.stamp.us, 1'061'500'000);
}

TEST(RealData, IntelStepsBackInTimeFourTimes) {
  {
    // Strict by default: the first backward stamp (FLASER at line 5647) stops the reader.
    CarmenReader reader;
    Summary sum;
    EXPECT_EQ(read_carmen(test::shared_data_path("carmen/intel.log.gz"), reader, 180, sum), Status::kTimeJump);
    EXPECT_EQ(reader.error().line, 5647u);
    EXPECT_EQ(sum.scans, 295);
  }
  CarmenReaderOptions opt;
  opt.time_order = TimeOrder::kAccept;
  CarmenReader reader(opt);
  Summary sum;
  ASSERT_EQ(read_carmen(test::shared_data_path("carmen/intel.log.gz"), reader, 180, sum), Status::kNoData)
      << "line " << reader.error().line << ": " << reader.error().reason;
  EXPECT_EQ(sum.scans, 910);
  EXPECT_EQ(sum.wrong_beam_count, 0);
  EXPECT_EQ(reader.stats().backward_stamps, 4u);
  // FLASER 180 1.09 1.08 ... 1.23 0.600266 -0.0320327 -0.354665 ... 32.9068 pippo 32.9068
  EXPECT_EQ(sum.first.line, 175u);
  EXPECT_EQ(sum.first.scan.range_mm[0], 1090);
  EXPECT_EQ(sum.first.scan.range_mm[1], 1080);
  EXPECT_EQ(sum.first.scan.range_mm[179], 1230);
  EXPECT_DOUBLE_EQ(sum.first.pose.x, 0.600266);
  EXPECT_DOUBLE_EQ(sum.first.pose.theta, -0.354665);
  EXPECT_EQ(sum.first.scan.stamp.us, 32'906'800);
  EXPECT_NEAR(sum.first.scan.angle_step_rad, M_PI / 180, 1e-9);
  // FLASER 180 1.01 1.01 ... 1.11 -0.596494 -0.101202 0.0119294 ... 2683.77 pippo 2683.77
  EXPECT_EQ(sum.last.line, 16316u);
  EXPECT_EQ(sum.last.scan.range_mm[0], 1010);
  EXPECT_EQ(sum.last.scan.range_mm[179], 1110);
  EXPECT_DOUBLE_EQ(sum.last.pose.x, -0.596494);
  EXPECT_DOUBLE_EQ(sum.last.pose.y, -0.101202);
  EXPECT_EQ(sum.last.scan.stamp.us, 2'683'770'000);
}

TEST(RealData, MinesExp2) {
  MinesReader reader;
  ASSERT_EQ(reader.open(test::shared_data_path("mines/exp2.dat").c_str()), Status::kOk);
  LogRecord rec, first, last;
  int scans = 0;
  Status s;
  while (ok(s = reader.next(rec))) {
    if (scans == 0) first = rec;
    last = rec;
    ++scans;
    ASSERT_EQ(rec.scan.beam_count, 682);
  }
  ASSERT_EQ(s, Status::kNoData) << "line " << reader.error().line << ": " << reader.error().reason;
  EXPECT_EQ(scans, 641);
  // head -1 exp2.dat: 361431443 ..., range fields 24..86 are 0, then 559 557 ...
  EXPECT_EQ(first.scan.stamp.us, 361431443);
  EXPECT_EQ(first.scan.range_mm[0], range_code::kNoReturn);
  EXPECT_EQ(first.scan.range_mm[63], 559);
  EXPECT_EQ(first.scan.range_mm[64], 557);
  int zeros = 0;
  for (std::size_t i = 0; i < 682; ++i) zeros += first.scan.range_mm[i] == 0;
  EXPECT_EQ(zeros, 421);
  // tail -1 exp2.dat: 424593575 ..., first range of at least 20 mm is beam 69: 1923
  EXPECT_EQ(last.line, 641u);
  EXPECT_EQ(last.scan.stamp.us, 424593575);
  EXPECT_EQ(last.scan.range_mm[69], 1923);
}

TEST(RealData, Freiburg079ThroughTheHalReplayDrivers) {
  LogError err;
  auto source = open_log(test::shared_data_path("carmen/freiburg-079.log.gz").c_str(), LogFormat::kAuto, {}, err);
  ASSERT_NE(source, nullptr) << err.reason;
  LogReplay replay(*source);
  ASSERT_EQ(replay.prime(), Status::kOk);
  EXPECT_EQ(replay.laser().geometry().beam_count, 360);
  LaserScan scan;
  int scans = 0;
  Status s;
  while ((s = replay.laser().poll(scan)) == Status::kOk) ++scans;
  EXPECT_EQ(s, Status::kClosed);
  EXPECT_EQ(scans, 4791);
  EXPECT_DOUBLE_EQ(replay.last_scan_record().pose.x, 0.0319692);
}

}  // namespace
}  // namespace kestrel::logs
