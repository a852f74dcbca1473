// Record a simulated run as a CARMEN log, play it back through the logs helper's reader and
// the replay HAL drivers: the scans come back identical, with the true poses as reference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "kestrel/logs/carmen_reader.hpp"
#include "kestrel/logs/log_replay.hpp"
#include "kestrel/sim/builtin_worlds.hpp"
#include "kestrel/sim/carmen_recorder.hpp"
#include "kestrel/sim/sim_observer_list.hpp"

namespace kestrel::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Keep : SimObserver {
  std::vector<LaserScan> scans;
  std::vector<VehicleState> truth;
  std::vector<ImuSample> imu;
  void on_scan(const LaserScan& s, const VehicleState& t) override {
    scans.push_back(s);
    truth.push_back(t);
  }
  void on_imu(const ImuSample& s) override { imu.push_back(s); }
};

void record_and_replay(const LaserParams& laser, const char* name) {
  const auto w = load_builtin_world("cluttered-lab");
  ASSERT_TRUE(w.ok);
  SimConfig cfg;
  cfg.laser = laser;
  Simulation sim(w.world, cfg);
  Keep keep;
  CarmenRecorder rec;
  const std::string path = testing::TempDir() + name;
  ASSERT_EQ(rec.open(path.c_str(), sim.imu().sample_period()), Status::kOk);
  SimObserverList list;
  list.add(&keep);
  list.add(&rec);
  sim.set_observer(&list);
  ASSERT_EQ(sim.flight_controller().arm(true), Status::kOk);
  AttitudeSetpoint sp;
  sp.thrust = 0.55f;
  sp.yaw_rate_radps = 0.5f;
  ASSERT_EQ(sim.flight_controller().send(sp), Status::kOk);
  (void)sim.step_until(TimeUs::from_s(KESTREL_SIM_SHORT_TESTS ? 0.5 : 1.5));
  ASSERT_EQ(rec.close(), Status::kOk);
  ASSERT_FALSE(keep.scans.empty());

  logs::CarmenReader reader;
  ASSERT_EQ(reader.open(path.c_str()), Status::kOk);
  ManualTimeSource clock(TimeUs{0});
  logs::LogReplay replay(reader, &clock);
  ASSERT_EQ(replay.prime(), Status::kOk);
  EXPECT_EQ(replay.laser().geometry().beam_count, laser.geometry().beam_count);
  EXPECT_EQ(replay.imu().sample_period().us, sim.imu().sample_period().us);
  std::size_t n = 0, m = 0;
  LaserScan got;
  ImuSample imu;
  // Read both streams as a consumer on the vehicle would: IMU samples between the scans.
  auto drain_imu = [&] {
    while (replay.imu().poll(imu) == Status::kOk) {
      ASSERT_LT(m, keep.imu.size());
      EXPECT_EQ(imu.stamp.us, (keep.imu[m].stamp + replay.time_offset()).us);
      EXPECT_NEAR((imu.accel_mps2 - keep.imu[m].accel_mps2).norm(), 0, 1e-4);
      EXPECT_NEAR((imu.gyro_radps - keep.imu[m].gyro_radps).norm(), 0, 1e-5);
      ++m;
    }
  };
  // Polled as the vehicle would, on a clock ticking in 1 ms steps.
  for (int64_t ms = 0; ms <= 2000; ++ms) {
    clock.set(TimeUs{ms * 1000});
    drain_imu();
    if (replay.laser().poll(got) != Status::kOk) continue;
    ASSERT_LT(n, keep.scans.size());
    const LaserScan& want = keep.scans[n];
    EXPECT_EQ(got.stamp.us, (want.stamp + replay.time_offset()).us);
    EXPECT_EQ(got.beam_count, want.beam_count);
    EXPECT_EQ(got.scan_period.us, want.scan_period.us);
    EXPECT_EQ(got.beam_interval.us, want.beam_interval.us);
    EXPECT_NEAR(got.first_angle_rad, want.first_angle_rad, 1e-6);
    EXPECT_NEAR(got.angle_step_rad, want.angle_step_rad, 1e-7);
    for (std::size_t i = 0; i < want.beam_count; ++i) ASSERT_EQ(got.range_mm[i], want.range_mm[i]) << n << " " << i;
    const logs::LogRecord& r = replay.last_scan_record();
    ASSERT_TRUE(r.has_pose);
    EXPECT_NEAR(r.pose.x, keep.truth[n].position_m.x(), 1e-5);
    EXPECT_NEAR(r.pose.y, keep.truth[n].position_m.y(), 1e-5);
    EXPECT_NEAR(std::remainder(r.pose.theta - keep.truth[n].yaw_rad, 2 * kPi), 0, 1e-5);
    ++n;
  }
  drain_imu();
  EXPECT_EQ(n, keep.scans.size());
  EXPECT_EQ(m, keep.imu.size());
  EXPECT_EQ(replay.dropped_imu(), 0u);
  std::remove(path.c_str());
}

TEST(CarmenRoundTrip, Utm30lxScansComeBackIdentical) { record_and_replay(LaserParams::utm30lx(), "utm.log"); }
TEST(CarmenRoundTrip, Urg04lxScansComeBackIdenticalFromGzip) {
  record_and_replay(LaserParams::urg04lx(), "urg.log.gz");
}

}  // namespace
}  // namespace kestrel::sim
