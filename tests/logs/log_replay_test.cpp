#include "kestrel/logs/log_replay.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/logs/carmen_reader.hpp"
#include "kestrel/logs/carmen_writer.hpp"
#include "kestrel/logs/mines_reader.hpp"
#include "log_test_files.hpp"

namespace kestrel::logs {
namespace {

using test::TempLogFile;

constexpr int kScans = 40;
constexpr int kImuPerScan = 5;

// 40 scans at 40 Hz from t = 1 s, IMU at 200 Hz, scan k has all ranges = 1000 + k mm and
// reference pose x = k.
void write_log(const TempLogFile& file, bool bad_line_after_half = false) {
  CarmenWriter w;
  ASSERT_EQ(w.open(file.c_str()), Status::kOk);
  ASSERT_EQ(w.write_param("kestrel_imu_period_us", 5000, TimeUs::from_s(1)), Status::kOk);
  for (int k = 0; k < kScans; ++k) {
    const TimeUs t = TimeUs::from_us(1'000'000 + 25'000 * k);
    for (int j = 0; j < kImuPerScan; ++j) {
      ImuSample imu;
      imu.stamp = t + Duration::from_us(5000 * j);
      imu.accel_mps2.z() = 9.81f;
      imu.gyro_radps.x() = static_cast<float>(k * kImuPerScan + j);
      ASSERT_EQ(w.write_imu(imu), Status::kOk);
    }
    LaserScan s;
    s.stamp = t;
    s.scan_period = Duration::from_us(25000);
    s.first_angle_rad = -1.0f;
    s.angle_step_rad = 0.01f;
    s.max_range_mm = 30000;
    s.beam_count = 201;
    for (std::size_t i = 0; i < s.beam_count; ++i) s.range_mm[i] = static_cast<uint16_t>(1000 + k);
    ASSERT_EQ(w.write_scan(s, Pose2d{static_cast<double>(k), 0, 0}), Status::kOk);
  }
  ASSERT_EQ(w.close(), Status::kOk);
  if (bad_line_after_half) {
    std::string text = file.read();
    std::size_t pos = 0;
    for (int i = 0; i < kScans / 2; ++i) pos = text.find("\nROBOTLASER1", pos + 1);
    ++pos;
    text.insert(pos, "FLASER 2 1 2\n");
    file.write(text);
  }
}

TEST(LogReplay, AsFastAsPolledGivesEveryScanThenEveryImuSample) {
  TempLogFile file("replay.log");
  write_log(file);
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  LogReplay replay(reader);
  ASSERT_EQ(replay.prime(), Status::kOk);
  const hal::LaserGeometry g = replay.laser().geometry();
  EXPECT_EQ(g.beam_count, 201);
  EXPECT_FLOAT_EQ(g.first_angle_rad, -1.0f);
  EXPECT_FLOAT_EQ(g.angle_step_rad, 0.01f);
  EXPECT_EQ(g.max_range_mm, 30000);
  EXPECT_EQ(g.scan_period.us, 25000);
  EXPECT_EQ(replay.imu().sample_period().us, 5000);

  LaserScan scan;
  for (int k = 0; k < kScans; ++k) {
    ASSERT_EQ(replay.laser().poll(scan), Status::kOk) << k;
    EXPECT_EQ(scan.range_mm[7], 1000 + k);
    EXPECT_EQ(scan.stamp.us, 1'000'000 + 25'000 * k);
    EXPECT_DOUBLE_EQ(replay.last_scan_record().pose.x, k);
  }
  EXPECT_EQ(replay.laser().poll(scan), Status::kClosed);
  ImuSample imu;
  for (int i = 0; i < kScans * kImuPerScan; ++i) {
    ASSERT_EQ(replay.imu().poll(imu), Status::kOk) << i;
    EXPECT_EQ(imu.gyro_radps.x(), static_cast<float>(i));
  }
  EXPECT_EQ(replay.imu().poll(imu), Status::kClosed);
  EXPECT_TRUE(replay.finished());
  EXPECT_EQ(replay.dropped_scans(), 0u);
  EXPECT_EQ(replay.dropped_imu(), 0u);
}

TEST(LogReplay, ClockPacedReplayReleasesOnTimeOnTheClocksTimelineWithoutAllocating) {
  TempLogFile file("paced.log.gz");
  write_log(file);
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  ManualTimeSource clock(TimeUs::from_s(50));
  LogReplay replay(reader, &clock);
  ASSERT_EQ(replay.prime(), Status::kOk);
  EXPECT_EQ(replay.time_offset().us, 49'000'000);

  int scans = 0, imus = 0;
  TimeUs last_scan{}, last_imu{};
  LaserScan scan;
  ImuSample imu;
  {
    alloc_guard::Scope guard;
    for (int step = 0; step < 300; ++step) {
      Status s;
      while ((s = replay.imu().poll(imu)) == Status::kOk) {
        EXPECT_LE(imu.stamp, clock.now());
        EXPECT_GT(imu.stamp, last_imu);
        EXPECT_EQ(imu.gyro_radps.x(), static_cast<float>(imus));
        last_imu = imu.stamp;
        ++imus;
      }
      EXPECT_TRUE(s == Status::kNoData || s == Status::kClosed);
      s = replay.laser().poll(scan);
      if (s == Status::kOk) {
        EXPECT_LE(scan.stamp, clock.now());
        // Polled every 5 ms, a scan is picked up within 5 ms of its stamp.
        EXPECT_LT(clock.now() - scan.stamp, Duration::from_us(5000));
        EXPECT_GT(scan.stamp, last_scan);
        last_scan = scan.stamp;
        ++scans;
      }
      clock.advance(Duration::from_us(5000));
    }
    EXPECT_EQ(guard.allocations(), 0u);
  }
  EXPECT_EQ(scans, kScans);
  EXPECT_EQ(imus, kScans * kImuPerScan);
  EXPECT_EQ(last_scan.us, 50'000'000 + 25'000 * (kScans - 1));
  EXPECT_TRUE(replay.finished());
  EXPECT_EQ(replay.laser().poll(scan), Status::kClosed);
}

TEST(LogReplay, SlowPollingKeepsTheNewestScanAndCountsDrops) {
  TempLogFile file("slow.log");
  write_log(file);
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  ManualTimeSource clock(TimeUs::from_s(1));
  ReplayOptions opt;
  opt.align_start = false;
  LogReplay replay(reader, &clock, opt);
  ASSERT_EQ(replay.prime(), Status::kOk);
  clock.set(TimeUs::from_us(1'000'000 + 25'000 * 9));  // ten scans due
  LaserScan scan;
  ASSERT_EQ(replay.laser().poll(scan), Status::kOk);
  EXPECT_EQ(scan.range_mm[0], 1009);
  EXPECT_EQ(replay.dropped_scans(), 9u);
  EXPECT_EQ(replay.laser().poll(scan), Status::kNoData);
}

TEST(LogReplay, ABadLineReachesEachDriverOnceThenClosed) {
  TempLogFile file("bad.log");
  write_log(file, true);
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  LogReplay replay(reader);
  LaserScan scan;
  int scans = 0;
  Status s;
  while ((s = replay.laser().poll(scan)) == Status::kOk) ++scans;
  EXPECT_EQ(scans, kScans / 2 - 1);
  EXPECT_EQ(s, Status::kMalformed);
  EXPECT_EQ(replay.laser().poll(scan), Status::kClosed);
  ImuSample imu;
  while ((s = replay.imu().poll(imu)) == Status::kOk) {
  }
  EXPECT_EQ(s, Status::kMalformed);
  EXPECT_EQ(replay.imu().poll(imu), Status::kClosed);
  EXPECT_GT(replay.source().error().line, 0u);
}

// Stamps each within int64 microseconds, but so far apart (a '-' slipped in front of one) that
// the clock-paced replay's offset plus the later one would wrap: the reader refuses them.
template <class Reader>
Status replay_until_not_ok(Reader& reader, int& scans) {
  ManualTimeSource clock(TimeUs::from_s(50));
  LogReplay replay(reader, &clock);
  LaserScan scan;
  Status s;
  scans = 0;
  for (int step = 0; step < 10 && (s = replay.laser().poll(scan)) != Status::kClosed; ++step) {
    if (s == Status::kOk) ++scans;
    if (s != Status::kOk && s != Status::kNoData) return s;
    clock.advance(Duration::from_ms(25));
  }
  return s;
}

TEST(LogReplay, CarmenStampsTooFarApartAreAnErrorNotAWrappedClock) {
  TempLogFile file("far.log");
  file.write("FLASER 3 1 2 3 0 0 0 0 0 0 -9e12 h 0\nFLASER 3 1 2 3 0 0 0 0 0 0 9e12 h 0\n");
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  int scans = 0;
  EXPECT_EQ(replay_until_not_ok(reader, scans), Status::kOutOfRange) << reader.error().reason;
  EXPECT_EQ(scans, 0);
  EXPECT_EQ(reader.error().line, 1u);
}

TEST(LogReplay, MinesStampsTooFarApartAreAnErrorNotAWrappedClock) {
  TempLogFile file("far.dat");
  std::string text;
  for (const char* stamp : {"-9000000000000000000", "9000000000000000000"}) {
    text += stamp;
    for (int i = 1; i < 24; ++i) text += " 0";
    for (int i = 0; i < 682; ++i) text += " 1000";
    text += "\n";
  }
  file.write(text);
  MinesReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  int scans = 0;
  EXPECT_EQ(replay_until_not_ok(reader, scans), Status::kOutOfRange) << reader.error().reason;
  EXPECT_EQ(scans, 0);
  EXPECT_EQ(reader.error().line, 1u);
}

}  // namespace
}  // namespace kestrel::logs
