#include "kestrel/logs/carmen_writer.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/logs/carmen_reader.hpp"
#include "log_test_files.hpp"

namespace kestrel::logs {
namespace {

using test::TempLogFile;

// A UTM-30LX-like scan with every kind of reading: returns, no return, the error codes.
LaserScan random_scan(std::mt19937& rng, TimeUs stamp, uint16_t beams) {
  LaserScan s;
  s.stamp = stamp;
  s.scan_period = Duration::from_us(25000);
  s.beam_interval = Duration::from_us(17);
  s.first_angle_rad = -2.35619449f;
  s.angle_step_rad = 0.00436332313f;
  s.max_range_mm = 30000;
  s.beam_count = beams;
  std::uniform_int_distribution<int> range(20, 29999);
  std::uniform_int_distribution<int> kind(0, 9);
  for (std::size_t i = 0; i < beams; ++i) {
    const int k = kind(rng);
    s.range_mm[i] = k == 0   ? range_code::kNoReturn
                    : k == 1 ? range_code::kTooNear
                    : k == 2 ? range_code::kDropout
                    : k == 3 ? range_code::kDeflected
                             : static_cast<uint16_t>(range(rng));
  }
  return s;
}

void round_trip(const char* name) {
  TempLogFile file(name);
  std::mt19937 rng(42);
  std::vector<LaserScan> scans;
  std::vector<Pose2d> poses;
  std::vector<ImuSample> imus;
  CarmenWriter writer;
  ASSERT_EQ(writer.open(file.c_str()), Status::kOk);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int k = 0; k < 40; ++k) {
    const TimeUs t = TimeUs::from_us(1'000'000 + 25'000 * k);
    for (int j = 0; j < 5; ++j) {
      ImuSample imu;
      imu.stamp = t + Duration::from_us(5000 * j);
      imu.accel_mps2 = Eigen::Vector3f(static_cast<float>(u(rng)), static_cast<float>(u(rng)), 9.80665f);
      imu.gyro_radps = Eigen::Vector3f(static_cast<float>(u(rng) * 1e-3), 0.125f, -static_cast<float>(u(rng)));
      imus.push_back(imu);
      ASSERT_EQ(writer.write_imu(imu), Status::kOk);
    }
    scans.push_back(random_scan(rng, t, k == 0 ? 1 : 1081));
    poses.push_back(Pose2d{u(rng), u(rng), wrap_angle(u(rng))});
    ASSERT_EQ(writer.write_scan(scans.back(), poses.back()), Status::kOk);
  }
  ASSERT_EQ(writer.close(), Status::kOk);

  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  LogRecord rec;
  std::size_t si = 0, ii = 0;
  Status s;
  while (ok(s = reader.next(rec))) {
    if (rec.kind == LogRecord::Kind::kLaser) {
      ASSERT_LT(si, scans.size());
      const LaserScan& w = scans[si];
      const LaserScan& r = rec.scan;
      EXPECT_EQ(r.stamp, w.stamp);
      EXPECT_EQ(r.scan_period, w.scan_period);
      EXPECT_EQ(r.beam_interval, w.beam_interval);
      EXPECT_EQ(r.first_angle_rad, w.first_angle_rad);
      EXPECT_EQ(r.angle_step_rad, w.angle_step_rad);
      EXPECT_EQ(r.max_range_mm, w.max_range_mm);
      ASSERT_EQ(r.beam_count, w.beam_count);
      for (std::size_t i = 0; i < w.beam_count; ++i)
        ASSERT_EQ(r.range_mm[i], w.range_mm[i]) << "scan " << si << " beam " << i;
      ASSERT_TRUE(rec.has_pose);
      EXPECT_NEAR(rec.pose.x, poses[si].x, 1e-6);
      EXPECT_NEAR(rec.pose.y, poses[si].y, 1e-6);
      EXPECT_NEAR(rec.pose.theta, poses[si].theta, 1e-8);
      ++si;
    } else {
      ASSERT_LT(ii, imus.size());
      EXPECT_EQ(rec.imu.stamp, imus[ii].stamp);
      EXPECT_EQ(rec.imu.accel_mps2, imus[ii].accel_mps2);
      EXPECT_EQ(rec.imu.gyro_radps, imus[ii].gyro_radps);
      ++ii;
    }
  }
  EXPECT_EQ(s, Status::kNoData) << reader.error().line << ": " << reader.error().reason;
  EXPECT_EQ(si, scans.size());
  EXPECT_EQ(ii, imus.size());
}

TEST(CarmenWriter, RoundTripPlainIsExact) { round_trip("rt.log"); }
TEST(CarmenWriter, RoundTripGzipIsExact) { round_trip("rt.log.gz"); }

TEST(CarmenWriter, RejectsBadInputAndWritesWithoutAllocating) {
  TempLogFile file("alloc.log.gz");
  CarmenWriter writer;
  LaserScan scan;
  EXPECT_EQ(writer.write_scan(scan, {}), Status::kClosed);
  ASSERT_EQ(writer.open(file.c_str(), "my host"), Status::kOk);
  EXPECT_EQ(writer.write_scan(scan, {}), Status::kInvalidArgument);  // no beams
  std::mt19937 rng(1);
  scan = random_scan(rng, TimeUs::from_us(5), 1081);
  EXPECT_EQ(writer.write_scan(scan, Pose2d{0, std::nan(""), 0}), Status::kInvalidArgument);
  ImuSample imu;
  imu.accel_mps2.x() = std::numeric_limits<float>::infinity();
  EXPECT_EQ(writer.write_imu(imu), Status::kInvalidArgument);
  imu.accel_mps2.x() = 0;
  {
    alloc_guard::Scope guard;
    for (int k = 0; k < 100; ++k) {
      scan.stamp = TimeUs::from_us(1000 * k);
      imu.stamp = scan.stamp;
      ASSERT_EQ(writer.write_scan(scan, Pose2d{1, 2, 3}), Status::kOk);
      ASSERT_EQ(writer.write_imu(imu), Status::kOk);
    }
    EXPECT_EQ(guard.allocations(), 0u);
  }
  ASSERT_EQ(writer.close(), Status::kOk);
  CarmenReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  LogRecord rec;
  int n = 0;
  Status s;
  while (ok(s = reader.next(rec))) ++n;
  EXPECT_EQ(s, Status::kNoData) << reader.error().reason;
  EXPECT_EQ(n, 200);
}

TEST(CarmenWriter, UnwritablePathIsAnIoError) {
  CarmenWriter writer;
  EXPECT_EQ(writer.open("/nonexistent/dir/out.log"), Status::kIoError);
}

}  // namespace
}  // namespace kestrel::logs
